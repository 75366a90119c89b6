"""Does a policy's reach aim at the object, open loop? On held-out expert episodes of an
inspect-and-place task, from recorded frames before the expert's grasp, the tool centre (by forward
kinematics of the robot alone) where the predicted chunk's last step puts the picking arm, against
where the expert's action put it then; the expert's action at the grasp frame is on the object.

    python analysis/policies/reach_open_loop.py --repo-id local/cpu_block_frontal_heldout_192_vla \\
        --root outputs/datasets/cpu_block_frontal_heldout_192_vla RUN/checkpoints/002000/pretrained_model

Per checkpoint and lead (frames before the grasp; from leads under the chunk's length the step that
lands on the grasp), over episodes: the correlation of the predicted point's distance from the
robot's base with the expert's (``radius_corr``), of its heading (``angle_corr``) and of its heading
round from the torso's (``arm_angle_corr``: the arm's share of the aim, the torso's turn taken out),
the median torso yaw error, the mean radial bias and the median 3-D miss; ``state_radius_corr``: the same correlation for the arm's tool centre
in the frame's own state, what the policy could copy without looking (the expert raises the arm
over the object about 15 frames before the grasp, so at short leads the state already holds the
distance). If the open-loop distance tracks the expert's from leads where the state does not and
the closed-loop one does not (``pick_offsets.py``), the reach drifts off the expert's states; if it
does not track it there, the policy never learnt the distance from the image. First, rows with
``from_frame``: the torso heading the chunk predicted from each episode's frame 0 (the first
decision: the home view, nothing in memory) and frame 16 ends at, against the expert's; on a
``--turn-error`` build (its torso turned off in the first 16 frames) also how far back towards the
expert's heading the frame-16 chunk turns. ``--max-episodes N`` scores the first N episodes only.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import mujoco
import numpy as np

from lerobot_activearena.sim import embodiment
from lerobot_activearena.sim.action import GRIPPER_INDICES, HEAD_PITCH, TORSO_YAW

LEADS = (45, 40, 35, 30, 25, 20, 15, 8, 1)  # frames before the grasp a chunk is predicted from
FACE_JITTER_DEG = float(np.degrees(0.12))  # the off-centre demonstrations' largest turn error (--face-jitter)


class ToolCentres:
    """Forward kinematics of the robot alone (the expert's IK model): an 18-dim action's joint targets
    to each tool centre."""

    def __init__(self):
        from lerobot_activearena.expert.ik import ArmIK

        self.model = ArmIK().model
        self.data = mujoco.MjData(self.model)
        adr = lambda j: self.model.joint(j).qposadr[0]  # noqa: E731
        self.arm_adr = {s: [adr(j) for j in embodiment.ARM_JOINTS[s]] for s in embodiment.ARMS}
        self.torso, self.head = adr(embodiment.TORSO_YAW_JOINT), adr(embodiment.HEAD_PITCH_JOINT)

    def __call__(self, action: np.ndarray, arm: str) -> np.ndarray:
        start = 0 if arm == "left" else GRIPPER_INDICES[0] + 1
        self.data.qpos[:] = self.model.qpos0
        self.data.qpos[self.arm_adr[arm]] = action[start : start + 7]
        self.data.qpos[self.torso], self.data.qpos[self.head] = action[TORSO_YAW], action[HEAD_PITCH]
        mujoco.mj_kinematics(self.model, self.data)
        return self.data.site(embodiment.TCP_SITES[arm]).xpos.copy()


def grasps(actions: np.ndarray, episodes: np.ndarray) -> list[tuple[int, int, str]]:
    """``(episode, dataset index of the grasp frame, arm)`` per episode: the first frame whose action
    closes a gripper (1 open, 0 closed)."""
    out = []
    for ep in np.unique(episodes):
        idx = np.flatnonzero(episodes == ep)
        closed = actions[idx][:, list(GRIPPER_INDICES)] < 0.5
        if not closed.any():
            continue
        first = int(np.argmax(closed.any(axis=1)))
        out.append((int(ep), int(idx[first]), embodiment.ARMS[int(np.argmax(closed[first]))]))
    return out


def polar(p) -> tuple[float, float]:
    """(m, deg) of a point's xy from the robot's base: 90 deg is straight ahead."""
    return float(np.hypot(p[0], p[1])), float(np.degrees(np.arctan2(p[1], p[0])))


def tracking(pred, true, state) -> dict[str, float]:
    """Over episodes, ``pred`` against ``true`` (tool centres (N, 3), torso yaws (N,)), and ``state``'s
    tool-centre radius against the true one."""
    (pred, pred_yaw), (true, true_yaw), (state, _) = pred, true, state
    pp, tp, sp = (np.array([polar(p) for p in x]) for x in (pred, true, state))
    corr = lambda a, b: float(np.corrcoef(a, b)[0, 1])  # noqa: E731
    return {
        "radius_corr": corr(pp[:, 0], tp[:, 0]),
        "angle_corr": corr(pp[:, 1], tp[:, 1]),
        "arm_angle_corr": corr(pp[:, 1] - np.degrees(pred_yaw), tp[:, 1] - np.degrees(true_yaw)),
        "torso_error_deg": float(np.median(np.abs(np.degrees(pred_yaw - true_yaw)))),
        "radius_bias_cm": float(100 * np.mean(pp[:, 0] - tp[:, 0])),
        "median_miss_cm": float(100 * np.median(np.linalg.norm(pred - true, axis=1))),
        "state_radius_corr": corr(sp[:, 0], tp[:, 0]),
    }


def predict(scorer, frames) -> np.ndarray:
    """The unnormalised chunks a loaded checkpoint (``scoring_policy``'s tuple) predicts from dataset
    frames ``frames``: (frames, steps, 18)."""
    import torch

    from lerobot_activearena.eval.learning_curve import policy_inputs

    cfg, policy, pre, post, ds = scorer
    batch = torch.utils.data.default_collate([ds[int(i)] for i in frames])
    with torch.no_grad():
        return post(policy.predict_action_chunk(pre(policy_inputs(batch, cfg)))).cpu().numpy()


def predicted_points(scorer, leads=LEADS, max_episodes=None):
    """Per lead: (predicted, expert, state) pairs of the picking arm's tool centres (episodes, 3) and
    the torso's yaw (episodes,)."""
    columns = scorer[-1].hf_dataset.with_format("numpy")
    actions, states = np.asarray(columns["action"]), np.asarray(columns["observation.state"])
    episodes = np.asarray(columns["episode_index"])
    fk = ToolCentres()
    out = {lead: ([], [], [], [], [], []) for lead in leads}
    for _, g, arm in grasps(actions, episodes)[:max_episodes]:
        frames = [g - lead for lead in leads if g - lead >= 0 and episodes[g - lead] == episodes[g]]
        chunk = predict(scorer, frames)
        for row, i in enumerate(frames):
            step = min(g - i, chunk.shape[1] - 1)
            for k, action in enumerate((chunk[row, step], actions[i + step], states[i])):
                out[g - i][2 * k].append(fk(action, arm))
                out[g - i][2 * k + 1].append(action[TORSO_YAW])
    return {
        lead: tuple((np.array(v[2 * k]), np.array(v[2 * k + 1])) for k in range(3))
        for lead, v in out.items()
        if v[0]
    }


def first_turns(
    scorer, start_frames=(0, 16), jitter_deg=FACE_JITTER_DEG, max_episodes=None, headings=None
) -> list[dict]:
    """The torso's heading at the end of the chunk predicted from each episode's frame ``f`` (0: the
    first decision, from the home view with nothing in memory; 16: the next, the expert's turn done)
    against the expert's then: correlation, median and largest error, and how many episodes it ends
    further off than the demonstrations' off-centre turns (``jitter_deg``) ever put the torso. Where
    the frame's own torso is further off than that (a ``--turn-error`` build's frame 16): how many, and
    how far back towards the expert's heading the chunk turns (median fraction: 0 holds, 1 is back)."""
    columns = scorer[-1].hf_dataset.with_format("numpy")
    actions, frame_index = np.asarray(columns["action"]), np.asarray(columns["frame_index"])
    states = np.asarray(columns["observation.state"])
    rows = []
    for f in start_frames:
        frames = np.flatnonzero(frame_index == f)[:max_episodes]
        chunk = predict(scorer, frames)
        last = chunk.shape[1] - 1
        pred, true = np.degrees(chunk[:, last, TORSO_YAW]), np.degrees(actions[frames + last, TORSO_YAW])
        err = np.abs(pred - true)
        row = {
            "from_frame": int(f),
            "episodes": len(frames),
            "torso_corr": float(np.corrcoef(pred, true)[0, 1]),
            "torso_error_deg": float(np.median(err)),
            "torso_error_max_deg": float(err.max()),
            f"over_{jitter_deg:.1f}_deg": int((err > jitter_deg).sum()),
        }
        state = np.degrees(states[frames, TORSO_YAW])
        off = np.abs(state - true) > jitter_deg
        if f > 0 and off.any():
            back = (state - pred)[off] / (state - true)[off]
            row |= {"state_off_episodes": int(off.sum()), "turned_back_fraction": float(np.median(back))}
        rows.append(row)
        if headings is not None:  # frame f's dataset indices, predicted and expert headings (deg)
            headings[f] = (frames, pred, true)
    return rows


def draw_first_views(scorer, frames, pred, true, root: Path, out: Path, n: int = 4) -> None:
    """The frame-0 head images of the ``n`` episodes whose first chunk ends furthest from the expert's
    heading and the ``n`` nearest, captioned with the first inspected object's place and both
    headings, a 3 x 4 grid (the 12 tokens of a 192 x 256 frame) drawn over them."""
    from PIL import Image, ImageDraw

    ds = scorer[-1]
    episodes = np.asarray(ds.hf_dataset.with_format("numpy")["episode_index"])
    order = np.argsort(-np.abs(pred - true))
    tiles = []
    for j in [*order[:n], *order[-n:]]:
        image = ds[int(frames[j])]["observation.images.head"]
        image = image[-1] if image.dim() == 4 else image
        tile = Image.fromarray((image.permute(1, 2, 0).numpy() * 255).astype(np.uint8))
        ep = int(episodes[frames[j]])
        side = json.loads((root / f"meta/activearena/sidecars/episode_{ep:06d}.json").read_text())
        inspected = (side.get("expert_notes") or {}).get("inspections", [{}])[0].get("object")
        place = next((q for q in side["placements"] if q["name"] == inspected), None)
        draw = ImageDraw.Draw(tile)
        w, h = tile.size
        for x in range(w // 4, w, w // 4):
            draw.line([x, 0, x, h], fill=(255, 255, 255))
        for y in range(h // 3, h, h // 3):
            draw.line([0, y, w, y], fill=(255, 255, 255))
        draw.rectangle([0, 0, w, 24], fill=(0, 0, 0))
        where = f"{place['angle']:.0f} deg, {100 * place['r']:.0f} cm" if place else "?"
        name = str(inspected).replace("_", " ")
        draw.text((3, 1), f"episode {ep}: {name} at {where}", fill=(255, 255, 255))
        draw.text((3, 12), f"torso: expert {true[j]:+.0f}, policy {pred[j]:+.0f} deg", fill=(255, 255, 0))
        tiles.append(tile)
    w, h = tiles[0].size
    sheet = Image.new("RGB", (w * n, h * 2))
    for k, tile in enumerate(tiles):
        sheet.paste(tile, ((k % n) * w, (k // n) * h))
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("checkpoints", nargs="+", type=Path)
    p.add_argument("--repo-id", required=True)
    p.add_argument("--root", type=Path, required=True)
    p.add_argument("--memory-ablation", choices=["none", "blank"], default="none")
    p.add_argument("--max-episodes", type=int, help="the first N episodes only")
    p.add_argument(
        "--first-views",
        type=Path,
        help="draw the frame-0 views of the 4 worst and 4 best first turns (one checkpoint) to this PNG",
    )
    args = p.parse_args()
    from lerobot_activearena.eval.protocol import register_policy_types

    register_policy_types()
    from lerobot_activearena.eval.learning_curve import scoring_policy

    for ckpt in args.checkpoints:
        scorer = scoring_policy(ckpt, args.repo_id, args.root, args.memory_ablation)
        head = {"checkpoint": str(ckpt), "memory_ablation": args.memory_ablation}
        headings = {}
        for row in first_turns(scorer, max_episodes=args.max_episodes, headings=headings):
            print(json.dumps(head | row), flush=True)
        if args.first_views:
            draw_first_views(scorer, *headings[0], args.root, args.first_views)
            print(f"first views -> {args.first_views}", flush=True)
        points = predicted_points(scorer, max_episodes=args.max_episodes)
        for lead, (pred, true, state) in sorted(points.items(), reverse=True):
            row = head | {"lead": lead, "episodes": len(true[0])} | tracking(pred, true, state)
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
