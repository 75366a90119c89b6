"""check_block_color (IA): read the gray block's hidden back colour and place it on that pad.

Task Description:
    A gray block hides a coloured patch on its back face (facing away from the robot). Pick it up,
    turn it in the hand until the head camera sees the patch, turn it back, then find the pad of
    that colour and place the block on it.
Randomizations:
    Patch colour (red / green / blue); pad colours permuted: one pad out of the home view on a
    random side, two anywhere in the arms' band; block at 40-140 deg, patch facing outward;
    clutter and (OOD) appearance.
Success Conditions:
    on_matching_pad: the block rests on the pad of its patch colour (inside the pad less 1 cm);
    block_released: no robot contact; both for 8 frames. The patch counts as task-relevant
    information: a policy that never showed it to the camera fails as DM.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from ...annotations.schema import CAMERA_INSPECT, STAGE_ANCHOR, STAGE_SEARCH
from ...expert import primitives as P
from ...expert import routines as R
from ...expert.context import ExpertError
from ...expert.ik import grasp_rotation, rot_z
from ...sim import embodiment as E
from ...sim.visibility import surface_point_visible
from .. import predicates as Pr
from ..base import Subtask, Task
from ..draft import HIDDEN, Region

PAD_COLORS = ("red", "green", "blue")
LIFT = 0.16


def patch_visible(model, data, info) -> bool:
    """Whether the head camera sees the block's back patch right now."""
    body = data.body(info.body)
    R = body.xmat.reshape(3, 3)
    point = body.xpos + R @ np.asarray(info.extra["patch_center_body"])
    normal = R @ np.asarray(info.extra["patch_normal_body"])
    cam = model.camera(E.HEAD_CAMERA).id
    return surface_point_visible(model, data, cam, point, normal, model.geom(info.extra["patch_geom"]).id, 512, 384,
                                 exclude_body=model.body(f"{E.PREFIX}head_link_2").id)


class CheckBlockColor(Task):
    name = "check_block_color"
    category = "IA"
    instruction = "Inspect the gray block's hidden color and place it on the matching pad."
    subtasks = (
        Subtask(1, "pick_target_block", "locate and pick up the gray target block", 0),
        Subtask(2, "inspect_target_block_backside", "reveal and identify the block's backside color", 1),
        Subtask(3, "restore_target_block_pose", "restore the block to a placement-ready pose", 2),
        Subtask(4, "place_target_block_on_matching_pad", "localize the matching pad and place the block on it", 3),
    )
    max_episode_steps = 296

    def layout(self, draft):
        rng = draft.rng
        colors = list(rng.permutation(PAD_COLORS))
        arms = ("left", "right")
        draft.place("color_pad", f"{colors[0]}_pad", f"{colors[0]} pad", HIDDEN, color=colors[0], margin=0.03, arms=arms)
        for c in colors[1:]:
            draft.place("color_pad", f"{c}_pad", f"{c} pad", Region(angle=(40.0, 140.0)), color=c, margin=0.03, arms=arms)
        patch = PAD_COLORS[int(rng.integers(0, 3))]
        draft.place("patch_block", "gray_block", "gray block", Region(angle=(40.0, 140.0)), patch_color=patch,
                    margin=0.04, arms=arms)
        draft.params["patch_color"] = patch

    def search_targets(self, scene):
        return [scene.objects.index("gray_block"), scene.objects.index(f"{scene.params['patch_color']}_pad")]

    def information_hidden_at_start(self, scene):
        data = mujoco.MjData(scene.model)
        mujoco.mj_forward(scene.model, data)
        return not patch_visible(scene.model, data, scene.obj("gray_block"))

    def information_seen(self, sim, scene):
        return patch_visible(sim.model, sim.data, scene.obj("gray_block"))

    def evaluate(self, sim, scene, monitor):
        pad = f"{scene.params['patch_color']}_pad"
        info = scene.obj(pad)
        return {"on_matching_pad": Pr.resting_on(sim, "gray_block", pad, info.half_extents[0], info.extra["top"]),
                "block_released": Pr.released(sim, "gray_block")}

    def expert(self, ctx, scene):
        block = ctx.idx("gray_block")
        with ctx.subtask(1):
            side = yield from R.find_and_face(ctx, block)
            # Fingers on the faces beside the patch, with the finger order that lets the wrist turn later.
            inspect = self._inspect_point(ctx, side)
            closing, angle = self._grasp_for_turn(ctx, side, block, inspect)
            yield from P.pick(ctx, side, block, closing=closing, lift=LIFT, flip_ok=False)

        with ctx.subtask(2):
            ctx.intent.stage, ctx.intent.info_complete, ctx.intent.focus = STAGE_SEARCH, False, block
            # Bring the block in front of the shoulder (where the wrist can turn it), then turn it.
            _, rot = P.tcp_pose(ctx, side)
            yield from P.arm_line(ctx, side, inspect, rot, 0.0, speed=0.2)
            yield from P.rotate_carried(ctx, side, angle)
            ctx.intent.stage = STAGE_ANCHOR
            yaw, pitch = ctx.gaze.aim(ctx.center(block), ctx.yaw, ctx.pitch, fix_yaw=True)
            yield from P.move_head_torso_to(ctx, yaw, pitch, CAMERA_INSPECT)
            info = ctx.obj(block)
            for _ in range(6):
                if patch_visible(ctx.sim.model, ctx.sim.data, info):
                    break
                yield from P.hold(ctx, 1)
            else:
                raise ExpertError("the back patch never came into view")
            color = info.extra["patch_color"]  # read off the visible patch
            ctx.notes["observed_color"] = color
            ctx.intent.info_complete = True
            yield from P.hold(ctx, 3)

        with ctx.subtask(3):
            P.start_action(ctx, {block})
            ctx.intent.carried = {block}
            yield from P.rotate_carried(ctx, side, -angle)

        with ctx.subtask(4):
            pad = ctx.idx(f"{color}_pad")
            yield from R.find_and_face(ctx, pad, side)
            P.start_action(ctx, {block, pad})
            ctx.intent.carried = {block}
            yield from P.place(ctx, side, block, ctx.center(pad)[:2], ctx.top_z(pad), yaw_free=True)
            yield from R.finish(ctx, side)

    @staticmethod
    def _inspect_point(ctx, side: str) -> np.ndarray:
        """In front of the arm's shoulder, below the head: the wrist can turn there and the camera sees it."""
        lateral = -0.19 if side == "left" else 0.19
        c, s = math.cos(ctx.yaw), math.sin(ctx.yaw)
        return np.array([c * lateral - s * 0.38, s * lateral + c * 0.38, 0.87])

    @staticmethod
    def _grasp_for_turn(ctx, side: str, block: int, inspect) -> tuple[np.ndarray, float]:
        """Finger-closing axis (+/- the block's y) and turn angle: the first pair whose whole turn
        at ``inspect`` IK can follow (a half turn, or 3/4 / 2/3 of one: the patch is then seen obliquely)."""
        _, Rb = ctx.pose(block)
        c = ctx.center(block)
        grasp = np.array([c[0], c[1], max(c[2], ctx.bottom_z(block) + P.GRASP_Z_MIN_ABOVE_BOTTOM)])
        path = [grasp + [0, 0, 0.12], grasp, grasp + [0, 0, LIFT]]
        first = -1.0 if side == "left" else 1.0
        angles = [f * a for a in (math.pi, 0.75 * math.pi, 2 * math.pi / 3) for f in (first, -first)]
        for angle in angles:
            for sign in (1.0, -1.0):
                R = grasp_rotation([0, 0, -1], sign * Rb[:, 1])
                try:
                    q = P.arm_of(ctx.action, side)
                    for pos in path:
                        q = P.solve_ik(ctx, side, q, pos, R)
                    for frac in np.linspace(0.0, 1.0, 9):
                        th = frac * angle
                        q = P.solve_ik(ctx, side, q, inspect, rot_z(th) @ R)
                    return sign * Rb[:, 1], angle
                except ExpertError:
                    continue
        raise ExpertError(f"the {side} wrist cannot turn the block to show its back")
