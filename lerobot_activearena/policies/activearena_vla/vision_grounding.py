"""Visual grounding for a backbone trained from scratch.

Qwen3-VL-2B arrives knowing where things are in an image; a tiny Qwen3-VL made by
``activearena-make-tiny-vlm`` knows nothing. This fits the tiny model's vision tower to say where the
current subtask's focus object is in the head image, from a built dataset's per-frame annotations
(``focus_object_visible``, ``target_uv_norm``): which merged visual token holds it, or none. With a
``search_weight`` it also says where the task's search targets in view are and how many there are
(``object_uv_norm``, ``search_target_mask`` and the sidecar's ``search_targets``): a count task's
counting frames have no focus object, and the blocks to count are what the tower must keep. With an
``identity_weight`` it also says which objects are in each token by what they look like (the sidecar's
object names without instance numbers: "button 2", "green block"): a frozen tower must tell the
buttons apart for a policy to press the one of the count. With a ``reading_window`` the inspected object
of an inspection task is named with what its hidden face shows while it is shown (the expert's reading:
"gray block showing green"), so a frozen tower keeps what a memory frame must carry. The
policy then trains from the grounded backbone as the paper's trains from Qwen3-VL's.
"""

from __future__ import annotations

import json
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
from torch import nn

ANNOTATIONS = ("focus_object_visible", "target_uv_norm")
SEARCH_ANNOTATIONS = ("object_uv_norm", "visible_object_mask", "search_target_mask")


@dataclass
class GroundingFrames:
    """A build's head frames and where their focus object is."""

    images: torch.Tensor  # (N, 3, H, W) uint8
    visible: np.ndarray  # (N,) bool
    uv: np.ndarray  # (N, 2) normalised (u, v); (-1, -1) where not visible
    episodes: np.ndarray  # (N,) episode index
    frames: np.ndarray  # (N,) frame index in the episode
    # (N, M, 2): each search target in view (searched for now, and one the task needs seen: the
    # sidecar's ``search_targets``), its (u, v); (-1, -1) for every other slot. None: not loaded.
    search_uv: np.ndarray | None = None
    # (N, M): each object in view, its appearance class (an index into ``classes``); -1 elsewhere
    object_class: np.ndarray | None = None
    object_uv: np.ndarray | None = None  # (N, M, 2) every object's (u, v)
    classes: list[str] | None = None


def appearance_class(key: str, name: str) -> str:
    """An object's name without its instance number: the tasks name the k-th of several alike objects
    ``<kind>_<k>`` / "<kind> <k + 1>" ("green block 2"), which look the same; a number that is part of
    what the object shows stays ("button 2", key ``button_2``)."""
    stem, _, index = key.rpartition("_")
    words = name.rsplit(" ", 1)
    if stem and index.isdigit() and len(words) == 2 and words[1] == str(int(index) + 1):
        return words[0]
    return name


READING = " showing "  # an appearance class that names a reading: "<object> showing <what it shows>"


def reading_text(value) -> str:
    """An expert reading as words: a colour as it is, a can's label by its values ("red", "2024-05-01")."""
    return " ".join(str(v) for v in value.values()) if isinstance(value, dict) else str(value)


def reading_rows(
    episodes: np.ndarray, frames: np.ndarray, inspections: dict[int, list[dict]], window: int
) -> list[tuple[np.ndarray, str, str]]:
    """Per expert reading (``inspections``: per episode, the sidecar's ``expert_notes.inspections``):
    the rows of (``episodes``, ``frames``) within ``window`` frames of it, the inspected object's key and
    the reading's words."""
    out = []
    for ep, entries in inspections.items():
        for entry in entries:
            if "reading" not in entry:
                continue
            near = (episodes == ep) & (np.abs(frames - int(entry["frame"])) <= window)
            out.append((np.flatnonzero(near), entry["object"], reading_text(entry["reading"])))
    return out


def identity_token_targets(
    object_uv: np.ndarray, object_class: np.ndarray, n_classes: int, rows: int, cols: int
) -> np.ndarray:
    """(N, rows * cols, n_classes) 0/1: which appearance classes each merged token holds."""
    n = len(object_uv)
    f, k = np.nonzero(object_class >= 0)
    u, v = object_uv[f, k, 0], object_uv[f, k, 1]
    cell = np.clip((v * rows).astype(int), 0, rows - 1) * cols + np.clip((u * cols).astype(int), 0, cols - 1)
    out = np.zeros((n, rows * cols, n_classes), np.float32)
    out[f, cell, object_class[f, k]] = 1.0
    return out


def search_target_points(
    object_uv: np.ndarray, visible: np.ndarray, searched: np.ndarray, task_targets: list[np.ndarray]
) -> np.ndarray:
    """(N, M, 2) image points of the objects each frame shows that it searches for and its task needs
    seen (``task_targets``: per frame, the sidecar's object indices); (-1, -1) elsewhere. On a count
    task's counting frames these are the blocks to count (the distractors are searched for too, but
    the task does not need them); on a press they are the button."""
    n, m = visible.shape
    needed = np.zeros((n, m), bool)
    for i, idx in enumerate(task_targets):
        needed[i, idx] = True
    keep = (visible == 1) & (searched == 1) & needed
    return np.where(keep[..., None], object_uv.reshape(n, m, 2), -1.0).astype(np.float32)


def search_token_targets(search_uv: np.ndarray, rows: int, cols: int) -> tuple[np.ndarray, np.ndarray]:
    """Per frame: which merged tokens hold a search target ((N, rows * cols) 0/1) and how many search
    targets are in view ((N,))."""
    shown = search_uv[..., 0] >= 0
    col = np.clip((search_uv[..., 0] * cols).astype(int), 0, cols - 1)
    row = np.clip((search_uv[..., 1] * rows).astype(int), 0, rows - 1)
    occupied = np.zeros((len(search_uv), rows * cols), np.float32)
    f, k = np.nonzero(shown)
    occupied[f, row[f, k] * cols + col[f, k]] = 1.0
    return occupied, shown.sum(1)


def token_cells(visible: np.ndarray, uv: np.ndarray, rows: int, cols: int) -> np.ndarray:
    """Each frame's class: the row-major index of the merged token (of a ``rows`` x ``cols`` grid) that
    holds the focus object's image point, or ``rows * cols`` where it is not visible."""
    col = np.clip((uv[:, 0] * cols).astype(int), 0, cols - 1)
    row = np.clip((uv[:, 1] * rows).astype(int), 0, rows - 1)
    return np.where(visible, row * cols + col, rows * cols)


def within_cells(uv: np.ndarray, rows: int, cols: int) -> np.ndarray:
    """Where in its merged token the focus object's image point lies: (u, v) in [0, 1] from the token's
    top-left corner (meaningless where the object is not visible)."""
    scaled = np.clip(uv, 0.0, 1.0) * np.array([cols, rows], dtype=np.float32)
    return np.clip(scaled - np.minimum(np.floor(scaled), [cols - 1, rows - 1]), 0.0, 1.0).astype(np.float32)


def check_decoded_size(n_frames: int, shape, root) -> None:
    """Refuse to decode more frames than memory holds (uint8, and a second copy while they are joined)."""
    need = 2 * n_frames * int(np.prod(shape))
    try:
        line = next(x for x in Path("/proc/meminfo").read_text().splitlines() if x.startswith("MemAvailable"))
        available = int(line.split()[1]) * 1024
    except (OSError, StopIteration):
        return  # not Linux: no check
    if need > 0.8 * available:
        fits = max(1, int(0.8 * available / need * n_frames))
        raise ValueError(
            f"grounding on {root} decodes {n_frames} frames of {tuple(shape)} into memory: about "
            f"{need / 2**30:.1f} GiB with {available / 2**30:.1f} GiB available. Ground on a subset of "
            f"its episodes (--episodes 0-N, about {fits} frames fit)"
        )


def load_grounding_frames(
    root: str | Path,
    camera: str = "observation.images.head",
    search: bool = False,
    identity: bool = False,
    reading_window: int = 0,
    episodes: list[int] | None = None,
) -> GroundingFrames:
    """Every frame of the build at ``root`` (of its ``episodes`` only, if given): its decoded head image
    and its focus annotations (and, with ``search``, its search targets' image points; with
    ``identity``, every object's point and appearance class, and with ``reading_window`` > 0 an
    inspected object's class within that many frames of the expert's reading is "<class> showing
    <reading>"). The frames are held decoded in memory; a build too large for it is refused before
    decoding, with the subset to pass."""
    import pandas as pd
    from lerobot.datasets.video_utils import decode_video_frames
    from tqdm import tqdm

    root = Path(root)
    data = pd.concat(pd.read_parquet(f) for f in sorted(root.glob("data/*/*.parquet")))
    missing = [c for c in ANNOTATIONS if c not in data.columns]
    if missing:
        raise ValueError(
            f"{root} has no per-frame {', '.join(missing)}: ground on the full build that "
            "activearena-build-dataset wrote, not on its slimmed copy (activearena-slim-dataset drops them)"
        )
    if (search or identity) and (missing := [c for c in SEARCH_ANNOTATIONS if c not in data.columns]):
        raise ValueError(
            f"{root} has no per-frame {', '.join(missing)}: grounding on search targets or object identities "
            "needs a build made by this version of activearena-build-dataset (rebuild it), or pass "
            "--search-weight 0 --identity-weight 0"
        )
    info = json.loads((root / "meta/info.json").read_text())
    if camera not in info["features"]:
        raise ValueError(f"{root} has no {camera}; its features: {sorted(info['features'])}")
    ep_table = pd.concat(pd.read_parquet(f) for f in sorted((root / "meta/episodes").glob("*/*.parquet")))
    if episodes is not None:
        unknown = sorted(set(episodes) - set(ep_table["episode_index"].astype(int)))
        if unknown:
            raise ValueError(
                f"{root} has no episode {unknown[0]} (it holds {len(ep_table)}, indexed from 0): pass "
                "--episodes within them"
            )
        ep_table = ep_table[ep_table["episode_index"].isin(episodes)]
        data = data[data["episode_index"].isin(episodes)]
    check_decoded_size(len(data), info["features"][camera]["shape"], root)
    data = data.sort_values("index")
    images, parts = [], []
    for _, ep in tqdm(list(ep_table.iterrows()), desc="decoding frames", unit="episode"):
        rows = data[data["episode_index"] == ep["episode_index"]]
        parts.append(rows)
        path = root / info["video_path"].format(
            video_key=camera,
            chunk_index=int(ep[f"videos/{camera}/chunk_index"]),
            file_index=int(ep[f"videos/{camera}/file_index"]),
        )
        stamps = (
            float(ep[f"videos/{camera}/from_timestamp"]) + rows["frame_index"].to_numpy() / info["fps"]
        ).tolist()
        images.append(
            decode_video_frames(path, stamps, 1 / (2 * info["fps"]), backend="pyav", return_uint8=True)
        )
    order = pd.concat(parts)
    search_uv = object_class = object_uv = classes = None
    if search or identity:
        sidecars = {
            int(ep): json.loads((root / f"meta/activearena/sidecars/episode_{int(ep):06d}.json").read_text())
            for ep in ep_table["episode_index"]
        }
        object_uv = np.stack(order["object_uv_norm"].to_numpy()).reshape(len(order), -1, 2)
        visible = np.stack(order["visible_object_mask"].to_numpy())
    if search:
        search_uv = search_target_points(
            object_uv,
            visible,
            np.stack(order["search_target_mask"].to_numpy()),
            [np.asarray(sidecars[int(ep)]["search_targets"], int) for ep in order["episode_index"]],
        )
    if identity:
        named = {
            ep: {o["index"]: appearance_class(o["key"], o["name"]) for o in side["objects"]}
            for ep, side in sidecars.items()
        }
        readings = []
        if reading_window > 0:
            inspections = {
                ep: side.get("expert_notes", {}).get("inspections", []) for ep, side in sidecars.items()
            }
            readings = reading_rows(
                order["episode_index"].to_numpy(),
                order["frame_index"].to_numpy(),
                inspections,
                reading_window,
            )
            if not readings:
                raise ValueError(
                    f"{root} holds no expert readings (expert_notes.inspections): --reading-window needs a "
                    "build of an inspection task (check_block_color, check_cola_color...)"
                )
        slot = {ep: {o["key"]: o["index"] for o in side["objects"]} for ep, side in sidecars.items()}
        shown = []  # (rows, object slot, class name) of each reading
        for rows, key, words in readings:
            if len(rows):
                ep = int(order["episode_index"].to_numpy()[rows[0]])
                k = slot[ep][key]
                shown.append((rows, k, f"{named[ep][k]}{READING}{words}"))
        classes = sorted({c for slots in named.values() for c in slots.values()} | {c for _, _, c in shown})
        slot_class = {
            ep: np.array([classes.index(slots.get(k, classes[0])) for k in range(visible.shape[1])])
            for ep, slots in named.items()
        }
        per_frame = np.stack([slot_class[int(ep)] for ep in order["episode_index"]])
        for rows, k, name in shown:
            per_frame[rows, k] = classes.index(name)
        object_class = np.where(visible == 1, per_frame, -1)
    return GroundingFrames(
        images=torch.cat(images),
        visible=order["focus_object_visible"].to_numpy().astype(bool),
        uv=np.stack(order["target_uv_norm"].to_numpy()).astype(np.float32),
        episodes=order["episode_index"].to_numpy(),
        frames=order["frame_index"].to_numpy(),
        search_uv=search_uv,
        object_class=object_class,
        object_uv=object_uv if identity else None,
        classes=classes,
    )


# act_cpu_jitter's colour ranges (configs/policy/baselines); no shift: it would move the labels
JITTER = {"brightness": (0.6, 1.4), "contrast": (0.7, 1.3), "saturation": (0.5, 1.5), "hue": (-0.1, 0.1)}


def color_jitter(images: torch.Tensor) -> torch.Tensor:
    """(N, 3, H, W) uint8 -> the same images, each with its own random brightness, contrast, saturation and
    hue (``JITTER``'s ranges, in a random order; torch's global random stream). Nothing moves, so the
    frames' annotations still hold."""
    from torchvision.transforms import v2

    jitter = v2.ColorJitter(**JITTER)
    return torch.stack([jitter(image) for image in images])


def random_convolution(images: torch.Tensor, p: float = 0.5, kernel_sizes=(1, 3, 5, 7)) -> torch.Tensor:
    """(N, 3, H, W) uint8 -> each frame, with probability ``p``, mixed with itself filtered by a random
    convolution (RandConv, Xu et al. 2021): a k x k kernel (k from ``kernel_sizes``) of Gaussian weights
    recolours and retextures the frame while edges and shapes stay in place; the result is brought
    back to the frame's per-channel mean and spread and blended with it at a random weight. Torch's
    global random stream."""
    out = []
    for image in images:
        if float(torch.rand(())) >= p:
            out.append(image)
            continue
        k = kernel_sizes[int(torch.randint(len(kernel_sizes), ()))]
        x = image.float()[None] / 255
        weight = torch.randn(3, 3, k, k) / (3 * k * k) ** 0.5
        y = nn.functional.conv2d(x, weight, padding=k // 2)
        mean, spread = x.mean((2, 3), keepdim=True), x.std((2, 3), keepdim=True)
        y = (y - y.mean((2, 3), keepdim=True)) / (y.std((2, 3), keepdim=True) + 1e-6) * spread + mean
        mix = float(torch.rand(()))
        out.append(((mix * x + (1 - mix) * y).clamp(0, 1) * 255).round().to(torch.uint8)[0])
    return torch.stack(out)


def token_grid(image_processor, images: torch.Tensor, max_pixels: int) -> tuple[int, int]:
    """The merged-token grid (rows, cols) the processor makes of these images."""
    from .processor_activearena_vla import image_inputs, one_token_pixels

    _, thw = image_inputs(image_processor, images[:1], max_pixels, one_token_pixels(image_processor), "cpu")
    merge = image_processor.merge_size
    return int(thw[0, 1]) // merge, int(thw[0, 2]) // merge


@dataclass
class GroundingOutput:
    logits: torch.Tensor  # (N, T + 1): the focus object's token, or "not in view"
    points: torch.Tensor  # (N, T, 2): where in each token it would be
    search: torch.Tensor  # (N, T): a search target is in this token
    count: torch.Tensor  # (N, C + 1): how many search targets are in view
    identity: torch.Tensor  # (N, T, K): each appearance class is in this token


class GroundingHead(nn.Module):
    """A logit per merged token (the focus object is there) and one for "not in view" from their mean;
    per token, where in it the object would be ((u, v) in [0, 1]); per token, a logit that a search
    target is there; from the mean, logits of how many are in view (0 .. ``max_count``); per token, a
    logit per appearance class (which kind of object is there)."""

    def __init__(self, width: int, max_count: int = 0, n_classes: int = 0):
        super().__init__()
        self.token = nn.Linear(width, 1)
        self.absent = nn.Linear(width, 1)
        self.point = nn.Linear(width, 2)
        self.search = nn.Linear(width, 1)
        self.count = nn.Linear(width, max_count + 1)
        self.identity = nn.Linear(width, max(n_classes, 1))

    def forward(self, tokens: torch.Tensor) -> GroundingOutput:
        """(N, T, D) -> focus logits (N, T + 1), points (N, T, 2), search logits (N, T), count logits."""
        mean = tokens.mean(1)
        logits = torch.cat([self.token(tokens)[..., 0], self.absent(mean)], dim=-1)
        return GroundingOutput(
            logits,
            torch.sigmoid(self.point(tokens)),
            self.search(tokens)[..., 0],
            self.count(mean),
            self.identity(tokens),
        )


class GroundedTower(nn.Module):
    """A Qwen3-VL's vision tower with a grounding head on its merged tokens and one on each DeepStack
    feature (the tower's middle layers, which the language model also reads). Returns their outputs."""

    def __init__(self, vlm, image_processor, max_pixels: int, max_count: int = 0, n_classes: int = 0):
        super().__init__()
        self.vlm, self.image_processor, self.max_pixels = vlm, image_processor, max_pixels
        taps = len(vlm.config.vision_config.deepstack_visual_indexes)
        self.heads = nn.ModuleList(
            GroundingHead(vlm.config.vision_config.out_hidden_size, max_count, n_classes)
            for _ in range(1 + taps)
        )

    def forward(self, images: torch.Tensor) -> list[GroundingOutput]:
        from .processor_activearena_vla import image_inputs, one_token_pixels

        pv, thw = image_inputs(
            self.image_processor, images, self.max_pixels, one_token_pixels(self.image_processor), "cpu"
        )
        out = self.vlm.model.get_image_features(pv.flatten(0, 1), thw)
        n = len(images)
        features = [
            torch.stack(list(out.pooler_output)),
            *(d.reshape(n, -1, d.shape[-1]) for d in out.deepstack_features),
        ]
        return [head(f) for head, f in zip(self.heads, features, strict=True)]


def grounding_loss(
    outputs: list[GroundingOutput],
    cells: torch.Tensor,
    within: torch.Tensor,
    point_weight: float,
    search: tuple[torch.Tensor, torch.Tensor] | None = None,
    search_weight: float = 0.0,
    identity: torch.Tensor | None = None,
    identity_weight: float = 0.0,
) -> torch.Tensor:
    """Cross-entropy over the tokens and "not in view", plus ``point_weight`` x the L1 error of the point
    predicted in the token that holds the object (frames that show it), plus ``search_weight`` x (the
    per-token binary cross-entropy of "a search target is here" + the cross-entropy of how many are in
    view; ``search``: ``search_token_targets``' two arrays as tensors), plus ``identity_weight`` x the
    cross-entropy over the appearance classes in the tokens that hold objects of one class (``identity``:
    ``identity_token_targets``), averaged over the heads."""
    none = outputs[0].logits.shape[-1] - 1
    seen = torch.nonzero(cells != none).flatten()
    if identity_weight:
        single = identity.sum(-1) == 1  # tokens that hold objects of one class
        named = identity[single].argmax(-1)
    total = 0.0
    for out in outputs:
        total = total + nn.functional.cross_entropy(out.logits, cells)
        if point_weight and len(seen):
            guess = out.points[seen, cells[seen]]
            total = total + point_weight * nn.functional.l1_loss(guess, within[seen])
        if search_weight:
            occupied, count = search
            total = total + search_weight * (
                nn.functional.binary_cross_entropy_with_logits(out.search, occupied)
                + nn.functional.cross_entropy(out.count, count)
            )
        if identity_weight and len(single):
            total = total + identity_weight * nn.functional.cross_entropy(out.identity[single], named)
    return total / len(outputs)


def _accuracy(
    model: GroundedTower,
    images,
    cells,
    uv,
    grid: tuple[int, int],
    batch: int,
    search=None,
    identity=None,
    classes: list[str] | None = None,
) -> dict[str, float]:
    """Held-out figures. Point errors are in pixels of ``images``, over the frames that show the object and
    whose token is named right: the predicted point's, and the token centre's for comparison. With
    ``search`` (``search_token_targets``' arrays): how often the number of search targets in view is
    right (beside always guessing the most common number), and the per-token precision and recall. With
    ``identity`` (``identity_token_targets``): in the tokens that hold objects of one class, how often
    that class has the highest logit (beside always guessing the most common class), and the same over
    the tokens whose class names a reading (``classes``: the class names)."""
    rows, cols = grid
    model.eval()
    with torch.no_grad():
        outs = [model(images[i : i + batch])[0] for i in range(0, len(images), batch)]
    model.train()
    pred = torch.cat([o.logits.argmax(-1) for o in outs])
    points = torch.cat([o.points for o in outs])
    cells = torch.as_tensor(cells)
    absent = cells == rows * cols
    figures = {
        "frames": len(cells),
        "in_view_accuracy": float(((pred == rows * cols) == absent).float().mean()),
        "token_accuracy_where_visible": float((pred[~absent] == cells[~absent]).float().mean())
        if (~absent).any()
        else float("nan"),
        "accuracy": float((pred == cells).float().mean()),
    }
    hit = torch.nonzero((pred == cells) & ~absent).flatten()
    if len(hit):
        cell = cells[hit]
        corner = torch.stack([cell % cols, cell // cols], -1).float()
        scale = torch.tensor([images.shape[-1] / cols, images.shape[-2] / rows])
        true = torch.as_tensor(uv[hit.numpy()]) * torch.tensor([images.shape[-1], images.shape[-2]])
        point = (corner + points[hit, cell]) * scale
        centre = (corner + 0.5) * scale
        figures["median_point_error_px"] = round(float((point - true).norm(dim=-1).median()), 2)
        figures["median_centre_error_px"] = round(float((centre - true).norm(dim=-1).median()), 2)
    if search is not None:
        occupied, count = (torch.as_tensor(a) for a in search)
        guess = torch.cat([o.count.argmax(-1) for o in outs])
        there = torch.cat([o.search for o in outs]) > 0
        figures["search_count_accuracy"] = float((guess == count).float().mean())
        figures["search_count_majority"] = float((count == count.mode().values).float().mean())
        figures["search_token_precision"] = float(occupied[there].mean()) if there.any() else float("nan")
        figures["search_token_recall"] = (
            float(there[occupied == 1].float().mean()) if (occupied == 1).any() else float("nan")
        )
    if identity is not None:
        identity = torch.as_tensor(identity)
        single = identity.sum(-1) == 1
        truth = identity[single].argmax(-1)
        guess = torch.cat([o.identity for o in outs])[single].argmax(-1)
        figures["identity_accuracy"] = float((guess == truth).float().mean())
        figures["identity_majority"] = float((truth == truth.mode().values).float().mean())
        if classes is not None and (reads := torch.tensor([READING in c for c in classes])[truth]).any():
            figures["reading_accuracy"] = float((guess[reads] == truth[reads]).float().mean())
            figures["reading_majority"] = float((truth[reads] == truth[reads].mode().values).float().mean())
    return figures


def ground_vision_tower(
    vlm_path: str | Path,
    root: str | Path,
    out_dir: str | Path,
    epochs: int = 5,
    batch_size: int = 64,
    lr: float = 3e-4,
    max_pixels: int = 12288,
    val_every: int = 10,
    seed: int = 0,
    point_weight: float = 0.0,
    search_weight: float = 0.0,
    identity_weight: float = 0.0,
    reading_window: int = 0,
    jitter: bool = False,
    random_conv: bool = False,
    eval_root: str | Path | None = None,
    episodes: list[int] | None = None,
) -> dict:
    """Fit ``vlm_path``'s vision tower to the focus object's place in the build at ``root``'s head frames
    and save the whole model (tokenizer and processor copied) to ``out_dir``. Every ``val_every``-th
    episode is held out and scored. ``point_weight`` > 0 also fits where in its token the object lies (the
    token alone places it within half a token). ``search_weight`` > 0 also fits which tokens hold a search
    target and how many are in view; ``identity_weight`` > 0 which appearance classes each token holds
    (with ``reading_window`` > 0, an inspected object near the expert's reading as what it shows).
    ``jitter`` colour-jitters every training batch (``color_jitter``), ``random_conv`` passes half its
    frames through a random convolution (``random_convolution``). ``eval_root`` (another build, an OOD
    one say) is scored whole after each epoch too, the focus figures with an ``eval_`` prefix.
    ``episodes``: ground on those of the build only (None: all). Returns the figures also written to
    ``out_dir/grounding.json``."""
    from tqdm import tqdm
    from transformers import AutoProcessor

    from .vlm_loading import load_policy_vlm

    torch.manual_seed(seed)
    if reading_window > 0 and identity_weight <= 0:
        raise ValueError(
            "--reading-window names the readings among the identity classes: it needs --identity-weight > 0"
        )
    frames = load_grounding_frames(
        root,
        search=search_weight > 0,
        identity=identity_weight > 0,
        reading_window=reading_window,
        episodes=episodes,
    )
    extra = load_grounding_frames(eval_root) if eval_root is not None else None
    # as the policy builds it (linear patch embedding, batched vision attention): the same weights, and
    # PyTorch's CPU Conv3d backward is most of a grounding step otherwise
    vlm = load_policy_vlm(str(vlm_path))
    processor = AutoProcessor.from_pretrained(vlm_path)
    rows, cols = token_grid(processor.image_processor, frames.images, max_pixels)
    search = search_token_targets(frames.search_uv, rows, cols) if search_weight > 0 else None
    identity = (
        identity_token_targets(frames.object_uv, frames.object_class, len(frames.classes), rows, cols)
        if identity_weight > 0
        else None
    )
    model = GroundedTower(
        vlm,
        processor.image_processor,
        max_pixels,
        int(search[1].max()) if search else 0,
        len(frames.classes) if identity is not None else 0,
    )
    cells = token_cells(frames.visible, frames.uv, rows, cols)
    within = torch.as_tensor(within_cells(frames.uv, rows, cols))
    held = frames.episodes % val_every == val_every - 1
    if not held.any() or held.all():
        raise ValueError(
            f"holding out every {val_every}-th episode leaves no held-out or no training episode of "
            f"{len(set(frames.episodes.tolist()))}; build more episodes or change val_every"
        )
    train_idx = np.flatnonzero(~held)
    params = [*vlm.model.visual.parameters(), *model.heads.parameters()]
    opt = torch.optim.AdamW(params, lr=lr, weight_decay=1e-4)
    steps = epochs * int(np.ceil(len(train_idx) / batch_size))
    sched = torch.optim.lr_scheduler.OneCycleLR(opt, max_lr=lr, total_steps=steps, pct_start=0.1)
    rng = np.random.default_rng(seed)
    target = torch.as_tensor(cells)
    history = []
    with tqdm(total=steps, desc="grounding the vision tower", unit="step") as bar:
        for epoch in range(epochs):
            order, losses = rng.permutation(train_idx), []
            for i in range(0, len(order), batch_size):
                b = order[i : i + batch_size]
                batch_search = search and (torch.as_tensor(search[0][b]), torch.as_tensor(search[1][b]))
                images = color_jitter(frames.images[b]) if jitter else frames.images[b]
                images = random_convolution(images) if random_conv else images
                loss = grounding_loss(
                    model(images),
                    target[b],
                    within[b],
                    point_weight,
                    batch_search,
                    search_weight,
                    None if identity is None else torch.as_tensor(identity[b]),
                    identity_weight,
                )
                opt.zero_grad()
                loss.backward()
                opt.step()
                sched.step()
                losses.append(loss.item())
                bar.update()
                bar.set_postfix(epoch=epoch, loss=f"{loss.item():.3f}")
            held_search = search and (search[0][held], search[1][held])
            scores = _accuracy(
                model,
                frames.images[held],
                cells[held],
                frames.uv[held],
                (rows, cols),
                4 * batch_size,
                held_search,
                None if identity is None else identity[held],
                frames.classes,
            )
            if extra is not None:
                elsewhere = _accuracy(
                    model,
                    extra.images,
                    token_cells(extra.visible, extra.uv, rows, cols),
                    extra.uv,
                    (rows, cols),
                    4 * batch_size,
                )
                scores.update({f"eval_{k}": v for k, v in elsewhere.items()})
            history.append({"epoch": epoch + 1, "train_loss": round(float(np.mean(losses)), 4), **scores})
            tqdm.write(json.dumps(history[-1]))
    out = Path(out_dir)
    tmp = out.with_name(out.name + ".partial")
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.copytree(vlm_path, tmp)
    vlm.save_pretrained(tmp)
    report = {
        "vlm_path": str(vlm_path),
        "dataset_root": str(root),
        "grid": [rows, cols],
        "train_frames": int(len(train_idx)),
        "held_out_episodes": sorted(set(frames.episodes[held].tolist())),
        "epochs": epochs,
        "batch_size": batch_size,
        "lr": lr,
        "point_weight": point_weight,
        "search_weight": search_weight,
        "identity_weight": identity_weight,
        "reading_window": reading_window,
        "jitter": JITTER if jitter else None,
        "random_conv": random_conv,
        "eval_root": None if eval_root is None else str(eval_root),
        "classes": frames.classes,
        "history": history,
    }
    (tmp / "grounding.json").write_text(json.dumps(report, indent=1) + "\n")
    shutil.rmtree(out, ignore_errors=True)
    tmp.rename(out)
    return report
