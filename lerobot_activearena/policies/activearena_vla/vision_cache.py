"""A frozen vision tower's features of every frame of a build, computed once (``activearena-cache-vision``).

With ``--policy.freeze_vision=true`` the tower is a fixed function of the image, so the chunk memory's
history frames need neither decoding nor the tower at every step: training reads their merged tokens
and DeepStack features from this table by global frame index (``--policy.vision_cache=FILE``). The
current frame still goes through the tower (its image augmentations apply). The table records a
fingerprint of the tower's weights; a policy whose tower differs refuses it."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import torch
from torch import nn

IMAGE_KEY = "observation.images.head"


def tower_fingerprint(visual: nn.Module) -> str:
    """A hash of the vision tower's parameters and buffers (names, shapes and values)."""
    h = hashlib.sha256()
    for name, t in sorted(visual.state_dict().items()):
        h.update(name.encode())
        h.update(str(tuple(t.shape)).encode())
        h.update(t.detach().float().cpu().contiguous().numpy().tobytes())
    return h.hexdigest()[:16]


def episode_frames(ds, episode: int) -> torch.Tensor:
    """An episode's head frames as (T, 3, H, W) uint8, decoded as LeRobot's dataset decodes them."""
    from lerobot.datasets.video_utils import decode_video_frames

    from .processor_activearena_vla import to_uint8

    ep = ds.meta.episodes[episode]
    rows = range(int(ep["dataset_from_index"]), int(ep["dataset_to_index"]))
    start = float(ep[f"videos/{IMAGE_KEY}/from_timestamp"])
    stamps = [start + float(t) for t in ds.hf_dataset.select(rows)["timestamp"]]
    path = ds.root / ds.meta.get_video_file_path(episode, IMAGE_KEY)
    frames = decode_video_frames(path, stamps, ds.tolerance_s, ds._video_backend)
    return to_uint8(frames)


@torch.no_grad()
def compute_vision_cache(
    vlm_path: str,
    root: str | Path,
    repo_id: str,
    image_max_pixels: int,
    out: str | Path,
    batch_size: int = 64,
) -> dict:
    """Run the tower of ``vlm_path`` over every head frame of the dataset at ``root`` and save the
    table to ``out`` (safetensors). Returns its metadata."""
    from lerobot.datasets.lerobot_dataset import LeRobotDataset
    from safetensors.torch import save_file
    from tqdm import tqdm
    from transformers import AutoProcessor

    from .processor_activearena_vla import image_inputs, one_token_pixels
    from .vlm_loading import load_from_vlm_path, load_policy_vlm

    vlm = load_policy_vlm(vlm_path).eval()
    images = load_from_vlm_path(AutoProcessor.from_pretrained, vlm_path, "processor").image_processor
    ds = LeRobotDataset(repo_id, root=root)
    if IMAGE_KEY not in ds.meta.video_keys:
        raise ValueError(f"{root} has no {IMAGE_KEY} video; its features: {sorted(ds.features)}")
    embeds = deep = grid = None
    for episode in tqdm(range(ds.meta.total_episodes), desc="vision features", unit="episode"):
        first = int(ds.meta.episodes[episode]["dataset_from_index"])
        frames = episode_frames(ds, episode)
        for s in range(0, len(frames), batch_size):
            pv, thw = image_inputs(
                images, frames[s : s + batch_size], image_max_pixels, one_token_pixels(images), "cpu"
            )
            feats = vlm.model.get_image_features(pv.flatten(0, 1), thw)
            e = torch.stack(list(feats.pooler_output))
            d = torch.stack([f.reshape(e.shape) for f in feats.deepstack_features])
            if embeds is None:
                embeds = e.new_zeros((ds.meta.total_frames, *e.shape[1:]))
                deep = d.new_zeros((len(d), ds.meta.total_frames, *e.shape[1:]))
                grid = thw[0]
            rows = slice(first + s, first + s + len(e))
            embeds[rows], deep[:, rows] = e, d
    meta = {
        "vlm_path": str(vlm_path),
        "fingerprint": tower_fingerprint(vlm.model.visual),
        "image_max_pixels": int(image_max_pixels),
        "grid": [int(v) for v in grid],
        "frames": int(ds.meta.total_frames),
        "root": str(Path(root).resolve()),
    }
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    save_file(
        {"embeds": embeds.contiguous(), "deepstack": deep.contiguous()}, str(out), {"meta": json.dumps(meta)}
    )
    return meta


class VisionCache:
    """The table of ``compute_vision_cache``, checked against the policy's tower and image size."""

    def __init__(self, path: str | Path, visual: nn.Module, image_max_pixels: int):
        from safetensors import safe_open
        from safetensors.torch import load_file

        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(
                f"--policy.vision_cache={str(path)!r} does not exist: make it with `activearena-cache-vision "
                "VLM_PATH --root BUILD --repo-id REPO_ID --image-max-pixels N --out FILE` from the training "
                "build and the policy's --policy.vlm_path"
            )
        with safe_open(str(path), "pt") as f:
            self.meta = json.loads(f.metadata()["meta"])
        mine = tower_fingerprint(visual)
        if self.meta["fingerprint"] != mine:
            raise ValueError(
                f"{path} holds the features of a different vision tower (fingerprint "
                f"{self.meta['fingerprint']}, made from {self.meta['vlm_path']}; this policy's is {mine}): "
                "rerun activearena-cache-vision with this policy's --policy.vlm_path"
            )
        if self.meta["image_max_pixels"] != image_max_pixels:
            raise ValueError(
                f"{path} was computed at image_max_pixels={self.meta['image_max_pixels']}, the policy reads "
                f"{image_max_pixels}: rerun activearena-cache-vision with --image-max-pixels {image_max_pixels}"
            )
        tables = load_file(str(path))
        self.embeds, self.deepstack = tables["embeds"], tables["deepstack"]
        self.grid = torch.tensor(self.meta["grid"])

    def features(self, index: int, device: torch.device) -> tuple[torch.Tensor, list[torch.Tensor]]:
        """The frame at global ``index``: its merged tokens and DeepStack features, as the tower gives them."""
        if not 0 <= index < len(self.embeds):
            raise IndexError(
                f"frame {index} is outside the vision cache ({len(self.embeds)} frames): it was made from "
                f"another build ({self.meta['root']}); rerun activearena-cache-vision on the training build"
            )
        return self.embeds[index].to(device), [d[index].to(device) for d in self.deepstack]
