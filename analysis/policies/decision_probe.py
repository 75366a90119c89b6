"""Does a trained ActiveArena-VLA know what to choose when it must choose? A linear probe on the
decision frames of a built dataset: the count task's press and the inspection task's place.

    python analysis/policies/decision_probe.py --root outputs/datasets/cpu_count_192 \\
        RUN_A/checkpoints/012000/pretrained_model RUN_B/checkpoints/003000/pretrained_model

For every episode it takes the frame ``--offset`` steps after the deciding subtask begins, runs the
policy on it as in training (its memory frames from the dataset), and keeps the last-layer states at
the action queries (their mean). On ``count_target_press_button`` that is the press (the blocks are
counted, the view is on the buttons, the arm has not moved yet; labels: the number of target blocks,
and the matching button's place among the three by azimuth); on ``check_block_color`` the place (the
block picked, its patch shown and turned away again; labels: the patch colour, and the named pad's
place among the three by azimuth). A logistic regression from those states to each label,
cross-validated over episodes (at its best of a few L2 weights: an upper bound), says whether it is
linearly readable where the policy decides; the majority class is the floor. The same from the
predicted chunk, and from the expert's recorded chunk at the same frames (the control: what a policy
that has decided shows). The task is read from the build.
"""

from __future__ import annotations

import argparse
import re
from collections import Counter
from pathlib import Path

import numpy as np
import torch


def count_labels(scene) -> dict[str, int]:
    """The scene's number of target blocks, and where the matching button lies among the three
    (0, 1, 2 by azimuth): the decision the press makes."""
    count = int(scene.params["count"])
    return {"count": count, "button": _place_among(scene, "button", f"button_{count}")}


def inspection_labels(scene) -> dict[str, str | int]:
    """The patch colour, and where the pad it names lies among the pads (0, 1, 2 by azimuth): the
    decision the place makes."""
    colour = scene.params["patch_color"]
    pads = sorted((p["angle"], p["name"]) for p in scene.params["placements"] if p["category"] == "color_pad")
    layout = ", ".join(n.replace("_", " ") for _, n in pads)  # right to left
    return {"colour": colour, "pad": _place_among(scene, "color_pad", f"{colour}_pad"), "layout": layout}


def _place_among(scene, category: str, name: str) -> int:
    ordered = sorted((p["angle"], p["name"]) for p in scene.params["placements"] if p["category"] == category)
    return [n for _, n in ordered].index(name)


# task: (the deciding subtask's index, the default offset into it, the labels of a scene)
DECISIONS = {
    "count_target_press_button": (2, 10, count_labels),
    "check_block_color": (4, 0, inspection_labels),
}


def decision_frames(root: Path, offset: int | None) -> tuple[list[int], list[dict]]:
    """Dataset indices of each episode's decision frame, and the episode's labels."""
    import json
    from types import SimpleNamespace

    import pandas as pd

    frame = pd.concat(pd.read_parquet(f) for f in sorted(root.glob("data/*/*.parquet")))
    episodes = [json.loads(line) for line in (root / "meta/activearena/episodes.jsonl").open()]
    tasks = {ep["task"] for ep in episodes}
    if len(tasks) != 1 or not tasks <= DECISIONS.keys():
        raise SystemExit(
            f"{root} holds {sorted(tasks)}; the probe reads one task's build, one of {sorted(DECISIONS)}"
        )
    task = tasks.pop()
    subtask, default_offset, labels_of = DECISIONS[task]
    offset = default_offset if offset is None else offset
    indices, labels = [], []
    for ep in episodes:
        g = frame[frame["episode_index"] == ep["episode_index"]].sort_values("frame_index")
        deciding = np.flatnonzero(g["subtask_index"].to_numpy() == subtask)
        if len(deciding) == 0:
            continue
        indices.append(int(g["index"].to_numpy()[min(deciding[0] + offset, len(g) - 1)]))
        # the scene as the sidecar records it (a counterfactual build's seed is not its scene's)
        sidecar = json.loads(
            (root / f"meta/activearena/sidecars/episode_{ep['episode_index']:06d}.json").read_text()
        )
        labels.append(
            labels_of(SimpleNamespace(params={**sidecar["params"], "placements": sidecar["placements"]}))
        )
    return indices, labels


def features(
    policy_dir: Path,
    repo_id: str,
    root: Path,
    indices: list[int],
    spans: list[str] | None = None,
    span: str = "decoded",
) -> tuple[np.ndarray, np.ndarray]:
    """(episodes, width) mean action-query states, (episodes, chunk * dims) predicted chunks and the
    recorded ones. A ``think_first`` policy's decoded spans go to ``spans`` where one is given. It acts
    on its own decoded span, or on the annotated one (``span="annotated"``, teacher-forced as in
    training), or on the annotated one with the named colour (and place) swapped for the next (``"swapped"``)."""
    from lerobot_activearena.eval.learning_curve import policy_inputs, scoring_policy

    cfg, policy, pre, _, ds = scoring_policy(policy_dir, repo_id, root)
    if span == "swapped":
        swap_named_colour(pre)
    loader = torch.utils.data.DataLoader(torch.utils.data.Subset(ds, indices), batch_size=16)
    states, chunks, recorded = [], [], []
    decode = policy.decode_actions

    def keep(hidden, kind):
        from lerobot_activearena.policies.activearena_vla.modeling_activearena_vla import QUERY

        states.append(hidden[kind == QUERY].view(kind.shape[0], -1, hidden.shape[-1]).float().mean(1))
        return decode(hidden, kind)

    policy.decode_actions = keep
    if spans is not None and getattr(policy, "think_first", False):
        think_then_act = policy.think_then_act

        def decoded(*args, **kwargs):
            tokens, chunk = think_then_act(*args, **kwargs)
            spans.extend(policy.text_tokenizer.decode(list(t)) for t in tokens)
            return tokens, chunk

        policy.think_then_act = decoded
    with torch.no_grad():
        for batch in loader:
            if span != "decoded":  # the action and index make the preprocessor write the think target
                b = pre(policy_inputs(batch, cfg) | {k: batch[k] for k in ("action", "index")})
                chunks.append(policy.encode(*policy.training_args(b))[0].flatten(1))
            else:
                chunks.append(policy.predict_action_chunk(pre(policy_inputs(batch, cfg))).flatten(1))
            recorded.append(batch["action"].flatten(1))
    return torch.cat(states).numpy(), torch.cat(chunks).numpy(), torch.cat(recorded).numpy()


def swap_named_colour(pre) -> None:
    """The annotation step's decision text names the next colour ("place on the red pad" -> green)."""
    from lerobot_activearena.policies.activearena_vla.dataset_annotations import DatasetAnnotations
    from lerobot_activearena.policies.activearena_vla.processor_activearena_vla import (
        ActiveArenaAnnotationStep,
    )

    (step,) = [s for s in pre.steps if isinstance(s, ActiveArenaAnnotationStep)]
    ann = step._ann = DatasetAnnotations(step.dataset_root, step.repo_id)
    annotated = ann.subtask_and_decision
    ann.subtask_and_decision = lambda index, *flags: swap_colour(annotated(index, *flags))


FOLLOWING = {
    "red": "green",
    "green": "blue",
    "blue": "red",
    "right": "middle",
    "middle": "left",
    "left": "right",
}


def swap_colour(text: str) -> str:
    """The named colour for the next ("place on the red pad" -> "place on the green pad"; red -> green
    -> blue -> red), and a named place with it ("..., the right one" -> "..., the middle one")."""
    text = re.sub(r"place on the (\w+) pad", lambda m: f"place on the {FOLLOWING[m.group(1)]} pad", text)
    return re.sub(r", the (\w+) one", lambda m: f", the {FOLLOWING[m.group(1)]} one", text)


def fit_probe(x: np.ndarray, y: np.ndarray, l2: float):
    """A multinomial logistic regression (standardised inputs, L2); returns its predict function."""
    classes = sorted(set(y.tolist()))
    target = torch.tensor([classes.index(v) for v in y])
    mu, sd = x.mean(0), x.std(0) + 1e-6
    xt = torch.tensor((x - mu) / sd, dtype=torch.float32)
    lin = torch.nn.Linear(x.shape[1], len(classes))
    opt = torch.optim.LBFGS(lin.parameters(), max_iter=200)

    def closure():
        opt.zero_grad()
        loss = torch.nn.functional.cross_entropy(lin(xt), target) + l2 * lin.weight.square().sum()
        loss.backward()
        return loss

    opt.step(closure)

    def predict(v: np.ndarray) -> np.ndarray:
        with torch.no_grad():
            out = lin(torch.tensor((v - mu) / sd, dtype=torch.float32)).argmax(1).numpy()
        return np.array(classes)[out]

    return predict


def cv_accuracy(x: np.ndarray, y: np.ndarray, l2: float, folds: int = 5, seed: int = 0) -> float:
    order = np.random.default_rng(seed).permutation(len(y))
    correct = 0
    for k in range(folds):
        test = order[k::folds]
        train = np.setdiff1d(order, test)
        correct += int((fit_probe(x[train], y[train], l2)(x[test]) == y[test]).sum())
    return correct / len(y)


def best_probe(x: np.ndarray, y: np.ndarray, x_out=None, y_out=None) -> str:
    """The probe's cross-validated accuracy at its best L2 weight (an upper bound: chosen on the same
    folds); with held-out episodes, the accuracy there of the probe fitted on all of ``x`` at that weight."""
    scores = {l2: cv_accuracy(x, y, l2) for l2 in L2_WEIGHTS}
    l2 = max(scores, key=scores.get)
    text = f"{scores[l2]:.0%}"
    if x_out is not None:
        text += f" / held-out {(fit_probe(x, y, l2)(x_out) == y_out).mean():.0%}"
    return text


L2_WEIGHTS = (1e-3, 1e-2, 1e-1, 1.0)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("checkpoints", nargs="+", type=Path, help="ActiveArena-VLA pretrained_model folders")
    p.add_argument("--root", type=Path, required=True, help="a build of one task (with meta/activearena)")
    p.add_argument("--repo-id", default=None, help="default: local/<root folder name>")
    p.add_argument(
        "--offset",
        type=int,
        default=None,
        help="frames after the deciding subtask begins (default: the task's)",
    )
    p.add_argument(
        "--heldout-root", type=Path, help="a build of other seeds: the probes fitted above, tested there"
    )
    p.add_argument(
        "--span",
        choices=("decoded", "annotated", "swapped"),
        default="decoded",
        help="what a think_first policy acts on: its own decoding, the annotated span (teacher-forced), "
        "or the annotated span with the named colour swapped (then also: how far that moves the chunk)",
    )
    p.add_argument("--episodes", type=int, default=None, help="the build's first N episodes only")
    args = p.parse_args()
    if args.span != "decoded":
        print(f"think_first policies act on the {args.span} span")
    repo_id = args.repo_id or f"local/{args.root.name}"
    indices, labels = decision_frames(args.root, args.offset)
    indices, labels = indices[: args.episodes], labels[: args.episodes]
    targets = {name: np.array([lab[name] for lab in labels]) for name in labels[0]}
    held = {}
    if args.heldout_root is not None:
        h_indices, h_labels = decision_frames(args.heldout_root, args.offset)
        held = {name: np.array([lab[name] for lab in h_labels]) for name in h_labels[0]}
    for name, y in targets.items():
        floor = Counter(y.tolist()).most_common(1)[0][1] / len(y)
        print(
            f"{len(y)} episodes, {name} {dict(sorted(Counter(y.tolist()).items()))}: majority class {floor:.0%}"
        )
    print(
        "probe accuracy, cross-validated over the build's episodes at the best L2 weight"
        + (f" / fitted there, tested on {len(h_indices)} held-out episodes:" if held else ":")
    )

    def probes(data, out=None) -> str:
        return ", ".join(
            f"{n} {best_probe(data, y, *((out, held[n]) if out is not None else ()))}"
            for n, y in targets.items()
        )

    for i, ckpt in enumerate(args.checkpoints):
        spans: list[str] = []
        x, chunk, expert = features(ckpt, repo_id, args.root, indices, spans, args.span)
        if args.span == "swapped":
            _, kept, _ = features(ckpt, repo_id, args.root, indices, span="annotated")
            print(
                f"  {ckpt} the swap moves the chunk by {np.abs(chunk - kept).mean():.4f} (mean, normalised); "
                f"from one episode's to the next's {np.abs(kept - np.roll(kept, 1, 0)).mean():.4f}"
            )
        hx = hchunk = hexpert = None
        if held:
            hx, hchunk, hexpert = features(
                ckpt, f"local/{args.heldout_root.name}", args.heldout_root, h_indices
            )
        if i == 0:
            print(f"  the expert's recorded chunk: {probes(expert, hexpert)}")
        print(f"  {ckpt} action-query states: {probes(x, hx)}")
        print(f"  {ckpt} predicted chunk: {probes(chunk, hchunk)}")
        if spans and "colour" in targets:
            print(f"  {ckpt} decoded span (think_first): {named_colours(spans, targets['colour'])}")
            if any(re.search(r", the \w+ one", t) for t in spans):  # a decision_place policy
                print(f"  {ckpt} decoded span's place: {named_places(spans, targets['pad'])}")
            if any(" pad right, " in t for t in spans):  # a decision_layout policy
                print(f"  {ckpt} decoded span's layout: {named_layouts(spans, targets['layout'])}")


def named_colours(spans: list[str], colours: np.ndarray) -> str:
    """How often a think-first policy's decoded span names the patch colour ("place on the red pad")."""
    named = [m.group(1) if (m := re.search(r"place on the (\w+) pad", s)) else None for s in spans]
    right = sum(n == c for n, c in zip(named, colours.tolist(), strict=True))
    return f"names the right colour in {right / len(spans):.0%}, none in {named.count(None) / len(spans):.0%}"


def named_places(spans: list[str], pads: np.ndarray) -> str:
    """How often a decision_place span names the named pad's place ("..., the right one"; pads by
    azimuth 0, 1, 2 = right, middle, left)."""
    from lerobot_activearena.policies.activearena_vla.dataset_annotations import PLACE_WORDS

    words = PLACE_WORDS[3]
    named = [m.group(1) if (m := re.search(r", the (\w+) one", s)) else None for s in spans]
    right = sum(n == words[int(p)] for n, p in zip(named, pads.tolist(), strict=True))
    return f"names the right place in {right / len(spans):.0%}, none in {named.count(None) / len(spans):.0%}"


def named_layouts(spans: list[str], layouts: np.ndarray) -> str:
    """How often a decision_layout span lists the pads right to left as they lie ("blue pad right, green
    pad middle, red pad left"), and how often it names the decided place as its own list has it."""
    from lerobot_activearena.policies.activearena_vla.dataset_annotations import PLACE_WORDS

    pattern = ", ".join(rf"(\w+ pad) {w}" for w in PLACE_WORDS[3])
    listed = [m.groups() if (m := re.search(pattern, s)) else None for s in spans]
    right = sum(
        lay is not None and ", ".join(lay) == t for lay, t in zip(listed, layouts.tolist(), strict=True)
    )
    copied = 0
    for lay, s in zip(listed, spans, strict=True):
        colour, place = re.search(r"place on the (\w+) pad", s), re.search(r", the (\w+) one", s)
        if lay and colour and place and f"{colour.group(1)} pad" in lay:
            copied += PLACE_WORDS[3][lay.index(f"{colour.group(1)} pad")] == place.group(1)
    return (
        f"lists the pads right in {right / len(spans):.0%}, none in {listed.count(None) / len(spans):.0%}; "
        f"the place follows its own list in {copied / len(spans):.0%}"
    )


if __name__ == "__main__":
    main()
