"""Physical grasping: a 0.3 kg can is lifted 15 cm and shaken without slipping out, and the pill bottle
carried by the pick-and-place routine stays in the gripper (no welds)."""

from collections.abc import Iterator

import mujoco
import numpy as np
import pytest

from lerobot_activearena.expert.ik import ArmIK, grasp_rotation, interpolate_pose
from lerobot_activearena.expert.motion import CONTROL_DT, arm_of, interpolate_joints, with_arm
from lerobot_activearena.sim.action import LEFT_GRIPPER, RIGHT_GRIPPER, TORSO_YAW
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


def side_grasp_frames(obj_center: np.ndarray, standoff: float) -> tuple[np.ndarray, np.ndarray]:
    """TCP position ``standoff`` m short of the object along the robot-to-object ray, and the
    gripper rotation (approach horizontal and radial, fingers closing horizontally)."""
    radial = np.array([obj_center[0], obj_center[1], 0.0])
    radial /= np.linalg.norm(radial)
    closing = np.array([-radial[1], radial[0], 0.0])
    return obj_center - standoff * radial, grasp_rotation(radial, closing)


def pick_and_shake(
    sim: ActiveArenaSim,
    ik: ArmIK,
    obj: str,
    side: str,
    lift: float = 0.15,
    shake_amp: float = 0.05,
    shake_cycles: int = 2,
) -> Iterator[tuple[str, np.ndarray]]:
    """Yield (phase, action) pairs; the caller steps the sim with each action."""
    info = next(o for o in sim.info.objects if o.name == obj)
    body = sim.data.body(info.body)
    center = body.xpos + body.xmat.reshape(3, 3) @ np.asarray(info.center_offset)
    action = sim.home_action()
    torso = action[TORSO_YAW] = sim.state()[TORSO_YAW]
    q = arm_of(action, side)

    def goto(phase, pos, rot, gripper, vel=1.0):
        """Joint-space move (used only through free space above the clutter)."""
        nonlocal q, action
        q_goal = ik.solve(side, q, torso, pos, rot)
        for qa in interpolate_joints(q, q_goal, max_vel=vel):
            action = with_arm(action, side, qa, gripper)
            yield phase, action
        q = q_goal

    def line(phase, pos, rot, gripper, speed=0.15):
        """Straight Cartesian TCP segment at ``speed`` m/s, IK at every control step."""
        nonlocal q, action
        p0, rot0 = ik.tcp_pose(side, q, torso)
        n = max(2, int(np.ceil(np.linalg.norm(np.asarray(pos) - p0) / (speed * CONTROL_DT))))
        for k in range(1, n + 1):
            pk, rot_k = interpolate_pose(p0, rot0, pos, rot, k / n)
            q = ik.solve(side, q, torso, pk, rot_k)
            action = with_arm(action, side, q, gripper)
            yield phase, action

    pre, rot = side_grasp_frames(center, 0.12)
    safe_z = center[2] + 0.25
    yield from goto("approach", np.array([pre[0], pre[1], safe_z]), rot, 1.0)
    yield from line("approach", pre, rot, 1.0)
    grasp, _ = side_grasp_frames(center, -0.005)
    yield from line("reach", grasp, rot, 1.0, speed=0.1)
    for _ in range(15):
        action = with_arm(action, side, q, 0.0)
        yield "close", action
    up = grasp + np.array([0, 0, lift])
    yield from line("lift", up, rot, 0.0, speed=0.1)
    lateral = rot[:, 0]
    for _cycle in range(shake_cycles):
        for sgn in (1, -1):
            yield from line("shake", up + sgn * shake_amp * lateral, rot, 0.0, speed=0.4)
    yield from line("shake", up, rot, 0.0, speed=0.4)
    for _ in range(8):
        yield "hold", action


def test_can_lifted_and_shaken_stays_in_gripper():
    b = SceneBuilder()
    b.add_object("can", "can", 0.45, 65.0, mass=0.3)
    model, info = b.compile()
    assert model.neq == 6, "only the finger couplings are equality constraints: no weld"
    assert model.body("can").mass[0] > 0.29
    sim = ActiveArenaSim(model, info)
    z0 = sim.data.body("can").xpos[2]

    def can_in_tcp():
        tcp, can = sim.data.site("astribot_right_tcp"), sim.data.body("can")
        return tcp.xmat.reshape(3, 3).T @ (can.xpos - tcp.xpos)

    rel_lift, shake_disp = None, []
    for phase, action in pick_and_shake(sim, ArmIK(), "can", "right"):
        sim.step(action)
        if phase == "lift" and rel_lift is None:
            rel_lift = can_in_tcp()
        if phase == "shake":
            shake_disp.append(
                np.linalg.norm(sim.data.site("astribot_right_tcp").xpos - sim.data.body("can").xpos)
            )
    slip = np.linalg.norm(can_in_tcp() - rel_lift)
    assert sim.data.body("can").xpos[2] - z0 > 0.12, "can was not lifted"
    assert slip < 0.005, f"can slipped {slip * 1000:.1f} mm in the gripper"
    assert np.ptp(shake_disp) < 0.01
    assert 0.3 < sim.state()[15] < 0.9, "gripper should be stopped by the can, neither open nor closed"


CARRIED = {  # task -> the object its expert carries (seed 0, ID)
    "move_pillbottle_pad_rotate_view": "pill_bottle",
    "move_stapler_pad_rotate_view": "stapler",
    "place_mouse_pad_rotate_view": "mouse",
    "place_shoe_rotate_view": "shoe",
    "place_container_plate_rotate_view": "container",
    "place_object_scale_rotate_view": "target_object",
    "place_object_stand_rotate_view": "target_object",
    "place_fan_rotate_view": "fan",
    "place_a2b_left_rotate_view": "object_a",
    "stack_blocks_two_rotate_view": "green_block",
    "stamp_seal_rotate_view": "seal",
    "beat_block_hammer_rotate_view": "hammer",  # held across the handle, before and after the strike
    "place_cans_plasticbox_rotate_view": "first_can",
    "place_a2b_right_rotate_view": "object_a",
}
BELL_SEED = 1  # place_a2b_right, ID seed 1: A is the bell (0.35 kg, held around its dome)
# place_fan, ID seed 1: the wrist turns the held fan half a turn (the long way round: the short way
# meets a wrist limit). The 0.35 kg fan creeps along the pads meanwhile (14 mm; seeds 0-15: 1-26 mm,
# the largest while the torso turns) but stays held: the bound for it is looser.
LONG_TURN_SEED, FAN_CREEP = 1, 0.02
GRIPPER = {"left": LEFT_GRIPPER, "right": RIGHT_GRIPPER}  # action index of each gripper command
SEATED = 8  # held frames after lift-off in which the object seats itself in the pads


@pytest.mark.parametrize(
    "task, seed",
    [(task, 0) for task in sorted(CARRIED)]
    + [("place_fan_rotate_view", LONG_TURN_SEED), ("place_a2b_right_rotate_view", BELL_SEED)],
)
def test_the_expert_carries_without_slip(task, seed):
    """The experts' grasps are physical too (no welds): while a gripper alone holds the object up,
    it stays put in the gripper's frame (within 5 mm) once seated: in the first frames off the
    table a rounded object (a mouse's shell) settles in the pads (up to 8 mm). Carrying ends when the
    release begins: a frame reached by an opening gripper command is not carried (the object slides
    out then, by design)."""
    from lerobot_activearena.episodes.rollout import run_expert_episode
    from lerobot_activearena.sim.embodiment import TCP_SITES
    from lerobot_activearena.tasks.predicates import held_by_gripper

    obj = CARRIED[task]
    offsets, welds, previous = [], [], []

    def on_frame(t, sim, frame, action):
        if t == 0:
            welds.append(int((sim.model.eq_type == mujoco.mjtEq.mjEQ_WELD).sum()))
        arm = held_by_gripper(sim, obj)
        releasing = arm is not None and previous and previous[-1][GRIPPER[arm]] > 0.0
        previous.append(action)
        if arm is not None and not releasing:
            tcp, body = sim.data.site(TCP_SITES[arm]), sim.data.body(obj)
            offsets.append(tcp.xmat.reshape(3, 3).T @ (body.xpos - tcp.xpos))

    r = run_expert_episode(task, seed, "id", on_frame=on_frame)
    assert r.success and welds == [0] and len(offsets) > 20, (r.failure, len(offsets))
    offsets = np.array(offsets)
    settle = np.linalg.norm(offsets[:SEATED] - offsets[0], axis=1).max()
    drift = np.linalg.norm(offsets[SEATED:] - offsets[SEATED], axis=1).max()
    print(
        f"{task}: {obj} settled {settle * 1000:.1f} mm, then moved {drift * 1000:.1f} mm over {len(offsets)} held frames"
    )
    assert settle < 0.008, f"the {obj} shifted {settle * 1000:.1f} mm in the gripper as it came up"
    bound = FAN_CREEP if (task, seed) == ("place_fan_rotate_view", LONG_TURN_SEED) else 0.005
    assert drift < bound, f"the {obj} moved {drift * 1000:.1f} mm in the gripper while carried"
