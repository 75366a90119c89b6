"""Astribot S1 class robot built procedurally with MjSpec from the real robot's kinematic facts.

Kinematics (body offsets, joint axes, limits, camera mount, gripper pads) come from
``data/astribot_s1_kinematics.json``; geometry is primitives (capsules, boxes). Torso joints 1-3 and
head yaw are baked into a fixed standing pose (``STANDING_POSE``) so the controlled joints are the
18 of the paper's action: two 7-DoF arms, two grippers, torso yaw, head pitch.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from importlib import resources

import mujoco
import numpy as np

ROBOT_TYPE = "astribot_s1"  # LeRobot robot_type of datasets recorded on this embodiment
PREFIX = "astribot_"
ARMS = ("left", "right")
ARM_JOINTS = {side: [f"{PREFIX}arm_{side}_joint_{i}" for i in range(1, 8)] for side in ARMS}
TORSO_YAW_JOINT = f"{PREFIX}torso_joint_4"
HEAD_PITCH_JOINT = f"{PREFIX}head_joint_2"
HEAD_CAMERA = f"{PREFIX}head"
# Paper, App. "Moving Cameras and Calibration": the head camera on head_link_2 at this translation (m)
# and roll-pitch-yaw (camera frame x forward, y left, z up). No offset along the pitch axis (link z),
# so the home view is symmetric about the torso heading (the official model's camera sits 8 cm left).
HEAD_CAMERA_MOUNT = (0.066, -0.210, 0.0)
HEAD_CAMERA_RPY = (np.pi / 2, 0.0, 0.0)
WRIST_CAMERAS = {side: f"{PREFIX}arm_{side}_effector" for side in ARMS}
TCP_SITES = {side: f"{PREFIX}{side}_tcp" for side in ARMS}


def other_arm(side: str) -> str:
    """The arm on the other side."""
    if side not in ARMS:
        raise ValueError(f"arm must be one of {ARMS}, got {side!r}")
    return ARMS[1 - ARMS.index(side)]


# Fixed joints of the real robot (rad): the lift chain (joints 1-3) folded as a standing pose that
# keeps link 4 upright, and head yaw at 0 (horizontal view changes come from torso yaw).
STANDING_POSE = {
    f"{PREFIX}torso_joint_1": 0.6,
    f"{PREFIX}torso_joint_2": -1.2,
    f"{PREFIX}torso_joint_3": 0.6,
    f"{PREFIX}head_joint_1": 0.0,
}

# Paper, App. "Astribot Embodiment Adaptation", table of control parameters.
HOME_ARM = {
    "left": np.array([-0.4, -0.7, -1.0, 1.4, -0.9, 0.0, 0.0]),
    "right": np.array([0.4, -0.7, 1.0, 1.4, 0.9, 0.0, 0.0]),
}
# On the two-level workspace HOME_ARM puts the grippers inside the upper band's slab (TCP at r 0.62 m,
# z 1.06 m); as the authors' release does for its two-level tasks, arm joint 1 goes to -/+0.11
# instead (TCP at r 0.57 m, z 0.93 m: under the slab, inside its inner edge).
TWO_LEVEL_HOME_ARM = {
    "left": np.array([-0.11, -0.7, -1.0, 1.4, -0.9, 0.0, 0.0]),
    "right": np.array([0.11, -0.7, 1.0, 1.4, 0.9, 0.0, 0.0]),
}


def home_arm(two_level: bool) -> dict[str, np.ndarray]:
    """The arms' home on the one- or two-level workspace."""
    return TWO_LEVEL_HOME_ARM if two_level else HOME_ARM


HOME_TORSO_YAW = 0.0
HOME_HEAD_PITCH = 1.0
TORSO_YAW_RANGE = (-1.2, 1.2)
HEAD_PITCH_RANGE = (-1.22, 1.22)
HEAD_LIMITS = (10.0, 25.0)  # rad/s, rad/s^2
TORSO_LIMITS = (2.5, 10.0)
ARM_GAINS = (2000.0, 200.0)  # stiffness, damping
TORSO_GAINS = (3000.0, 800.0)
HEAD_GAINS = (300.0, 30.0)  # not in the paper's table: a light head servo
# Gripper: the active finger joint closes from 0 (open) to GRIPPER_CLOSED_RAD with the paper's drive
# 4000/200; its 120 N force limit is the pad squeeze force (torque = force x finger lever).
GRIPPER_CLOSED_RAD = 0.93
GRIPPER_FINGER_LEVER = 0.055
GRIPPER_FORCE = 120.0
GRIPPER_GAINS = (4000.0, 200.0)
# Finger joints that follow the active joint L1 (q = coef * q_L1): the pads stay parallel.
GRIPPER_COUPLING = (("L11", 1.0), ("R1", 1.0), ("R11", -1.0))

# Collision bits: robot geoms collide with the world and objects, never with each other.
ROBOT_CONTYPE, ROBOT_CONAFFINITY = 2, 1
VISUAL_GROUP, COLLISION_GROUP = 2, 3
ROBOT_COLOR = (0.82, 0.83, 0.86, 1.0)
ROBOT_DARK = (0.18, 0.19, 0.22, 1.0)


def load_kinematics() -> dict:
    text = resources.files("lerobot_activearena.sim").joinpath("data/astribot_s1_kinematics.json").read_text()
    return json.loads(text)


def _quat(q) -> np.ndarray:
    return np.asarray(q if q is not None else (1.0, 0.0, 0.0, 0.0), dtype=float)


def _euler_quat(euler) -> np.ndarray:
    out = np.zeros(4)
    mujoco.mju_euler2Quat(out, np.asarray(euler, dtype=float), "xyz")
    return out


def _axis_quat(axis, angle) -> np.ndarray:
    out = np.zeros(4)
    mujoco.mju_axisAngle2Quat(out, np.asarray(axis, dtype=float), float(angle))
    return out


def _mul(a, b) -> np.ndarray:
    out = np.zeros(4)
    mujoco.mju_mulQuat(out, np.asarray(a, float), np.asarray(b, float))
    return out


@dataclass
class RobotSpecInfo:
    """Names the rest of the simulator needs to find in the compiled model."""

    actuated_joints: list[str] = field(default_factory=list)  # the 16 non-gripper joints, action order
    gripper_joints: dict[str, str] = field(default_factory=dict)  # side -> active finger joint
    body_names: list[str] = field(default_factory=list)


def _link_radius(name: str) -> float:
    if "gripper" in name:
        return 0.007 if name.endswith(("_L1", "_R1")) else 0.0
    if "arm" in name:
        link = int(name.rsplit("_", 1)[-1]) if name[-1].isdigit() else 7
        return 0.05 if link <= 3 else 0.042 if link <= 5 else 0.036
    return 0.0


def _add_bone_geoms(body: mujoco.MjsBody, node: dict) -> None:
    """Capsules from a link's origin to each child's origin: light geometry, also the collision."""
    r = _link_radius(node["name"])
    if r == 0.0:
        return
    for child in node["children"]:
        p = np.asarray(child["pos"], float)
        if np.linalg.norm(p) < 1e-4:
            continue
        g = body.add_geom()
        g.name = f"{node['name']}_to_{child['name'].removeprefix(PREFIX)}"
        g.type = mujoco.mjtGeom.mjGEOM_CAPSULE
        g.fromto = np.concatenate([np.zeros(3), p])
        g.size[0] = r
        g.rgba = ROBOT_COLOR
        g.contype, g.conaffinity, g.group = ROBOT_CONTYPE, ROBOT_CONAFFINITY, VISUAL_GROUP
        if "gripper" in node["name"]:  # finger bars: looks only, the pads do the contact
            g.rgba, g.contype, g.conaffinity = ROBOT_DARK, 0, 0


def _add_gripper_geoms(body: mujoco.MjsBody, node: dict, side: str) -> None:
    for box in node["collision_boxes"]:
        g = body.add_geom()
        is_pad = "L11" in node["name"] or "R11" in node["name"]
        g.name = (
            f"{PREFIX}gripper_{side}_pad_{'L' if 'L11' in node['name'] else 'R'}"
            if is_pad
            else f"{PREFIX}gripper_{side}_palm"
        )
        g.type = mujoco.mjtGeom.mjGEOM_BOX
        g.size = np.asarray(box["size"], float)
        g.pos = np.asarray(box["pos"], float)
        g.rgba = ROBOT_DARK
        g.contype, g.conaffinity, g.group = ROBOT_CONTYPE, ROBOT_CONAFFINITY, VISUAL_GROUP
        if is_pad:
            # Grasp-holding contact: high friction with torsional/rolling terms, stiff, wins priority.
            g.priority = 1
            g.condim = 6
            g.friction = (1.5, 0.02, 0.002)
            g.solref = (0.005, 1.0)
            g.solimp = (0.95, 0.99, 0.001, 0.5, 2.0)


def _add_fixed_visuals(body: mujoco.MjsBody, name: str) -> None:
    """Non-colliding shapes for torso, head and finger bars (for looks)."""

    def vis(gtype, size, pos, rgba=ROBOT_COLOR, quat=None):
        g = body.add_geom()
        g.type, g.size, g.pos, g.rgba = gtype, np.asarray(size, float), np.asarray(pos, float), rgba
        if quat is not None:
            g.quat = quat
        g.contype = g.conaffinity = 0
        g.group = VISUAL_GROUP
        return g

    short = name.removeprefix(PREFIX)
    if short == "torso_link_4":
        # Trunk and shoulder bar stay below the head camera (0.39 m above this link at home pitch).
        vis(mujoco.mjtGeom.mjGEOM_CAPSULE, (0.10, 0.09, 0), (-0.02, 0, 0.17))
        vis(mujoco.mjtGeom.mjGEOM_BOX, (0.05, 0.15, 0.035), (-0.03, 0, 0.325), rgba=ROBOT_DARK)
        vis(mujoco.mjtGeom.mjGEOM_CYLINDER, (0.03, 0.04, 0), (-0.02, 0, 0.40), rgba=ROBOT_DARK)
    elif short == "head_link_2":
        # head_link_2 frame: x forward (camera axis), -y up; the head sits behind the camera.
        vis(mujoco.mjtGeom.mjGEOM_BOX, (0.065, 0.12, 0.09), (-0.015, -0.14, 0.0))
        vis(mujoco.mjtGeom.mjGEOM_BOX, (0.004, 0.03, 0.06), (0.055, -0.21, 0.0), rgba=ROBOT_DARK)
    elif short == "chassis_base":
        vis(mujoco.mjtGeom.mjGEOM_CYLINDER, (0.2, 0.05, 0), (0, 0, 0.0), rgba=ROBOT_DARK)
    elif short.startswith("gripper_") and short.endswith("_base"):
        g = vis(mujoco.mjtGeom.mjGEOM_CYLINDER, (0.032, 0.03, 0), (0, 0, 0.03), rgba=ROBOT_DARK)
        g.contype, g.conaffinity = ROBOT_CONTYPE, ROBOT_CONAFFINITY


def _forward_left_up_camera_quat(rpy) -> np.ndarray:
    """MuJoCo camera quaternion (looks along -z, x right, y up) of a camera whose frame (x forward,
    y left, z up, the paper's convention) has roll-pitch-yaw ``rpy`` in its parent."""
    q = np.zeros(4)
    mujoco.mju_euler2Quat(q, np.asarray(rpy, float), "XYZ")
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, q)
    rot = rot.reshape(3, 3)
    mj = np.stack([-rot[:, 1], rot[:, 2], -rot[:, 0]], axis=1)  # right = -left, up = up, back = -forward
    out = np.zeros(4)
    mujoco.mju_mat2Quat(out, mj.reshape(-1))
    return out


def _add_body(
    parent: mujoco.MjsBody, node: dict, info: RobotSpecInfo, standing: dict[str, float]
) -> mujoco.MjsBody:
    body = parent.add_body()
    body.name = node["name"]
    body.pos = np.asarray(node.get("pos", (0, 0, 0)), float)
    quat = _quat(node.get("quat"))
    if "euler" in node:
        quat = _mul(quat, _euler_quat(node["euler"]))
    for j in node["joints"]:
        if j["name"] in standing:  # baked: rotate the child frame by the fixed angle
            quat = _mul(quat, _axis_quat(j["axis"], standing[j["name"]]))
    body.quat = quat
    body.gravcomp = 1.0  # robot links are gravity compensated, as on the real robot's controller
    info.body_names.append(body.name)
    side = "left" if "_left" in body.name else "right" if "_right" in body.name else None

    for j in node["joints"]:
        if j["name"] in standing:
            continue
        jt = body.add_joint()
        jt.name = j["name"]
        jt.type = mujoco.mjtJoint.mjJNT_HINGE
        jt.axis = np.asarray(j["axis"], float)
        jt.pos = np.asarray(j.get("pos", (0, 0, 0)), float)
        lo, hi = j["range"]
        if j["name"] == TORSO_YAW_JOINT:
            lo, hi = TORSO_YAW_RANGE
        if j["name"] == HEAD_PITCH_JOINT:
            lo, hi = HEAD_PITCH_RANGE
        jt.range = (lo, hi)
        jt.limited = mujoco.mjtLimited.mjLIMITED_TRUE
        if "gripper" in j["name"]:
            jt.armature, jt.damping[0] = 0.002, 0.05
        elif "arm" in j["name"]:
            jt.armature, jt.damping[0] = 0.1, 1.0
        else:
            jt.armature, jt.damping[0] = 0.2, 2.0

    for cam in node["cameras"]:
        c = body.add_camera()
        c.name = cam["name"]
        c.pos = np.asarray(cam["pos"], float)
        c.fovy = float(cam["fovy"][0])
        if cam["name"] == HEAD_CAMERA:
            c.pos, c.quat = (
                np.asarray(HEAD_CAMERA_MOUNT, float),
                _forward_left_up_camera_quat(HEAD_CAMERA_RPY),
            )
        elif "xyaxes" in cam:
            x = np.asarray(cam["xyaxes"][:3], float)
            y = np.asarray(cam["xyaxes"][3:], float)
            z = np.cross(x, y)
            mat = np.stack([x, y, z], axis=1).reshape(-1)
            q = np.zeros(4)
            mujoco.mju_mat2Quat(q, mat)
            c.quat = q
        elif "euler" in cam:
            c.quat = _euler_quat(cam["euler"])
    if body.name.endswith("gripper_left_base") or body.name.endswith("gripper_right_base"):
        s = body.add_site()
        s.name = TCP_SITES[side]
        s.pos = (0.0, 0.0, 0.125)  # between the finger pads
        s.size = (0.006, 0.006, 0.006)
        s.rgba = (1, 0, 0, 0)

    if "gripper" in body.name:
        _add_gripper_geoms(body, node, side)
    _add_bone_geoms(body, node)
    _add_fixed_visuals(body, body.name)
    for child in node["children"]:
        if child["name"].endswith(("_L2", "_R2")):
            continue  # passive parallelogram bars: folded into the pad mimic joints
        _add_body(body, child, info, standing)
    return body


def add_robot(spec: mujoco.MjSpec, base_pos=(0.0, 0.0, 0.097), base_yaw: float = np.pi / 2) -> RobotSpecInfo:
    """Add the robot with its chassis at ``base_pos`` (official scene: 0.097 m up) facing ``base_yaw``."""
    kin = load_kinematics()
    info = RobotSpecInfo()
    spec.compiler.degree = False  # joint ranges below are radians
    # Links without geometry of their own (coincident joint frames) get a small mass and inertia.
    spec.compiler.boundmass = max(spec.compiler.boundmass, 0.05)
    spec.compiler.boundinertia = max(spec.compiler.boundinertia, 1e-5)
    chassis = spec.worldbody.add_body()
    chassis.name = f"{PREFIX}chassis_base"
    chassis.pos = np.asarray(base_pos, float)
    # The official torso chain faces +x of the chassis; rotate so the robot looks along base_yaw.
    chassis.quat = _axis_quat((0, 0, 1), base_yaw)
    _add_fixed_visuals(chassis, chassis.name)
    _add_body(chassis, kin["tree"], info, STANDING_POSE)

    for side in ARMS:
        prefix = f"{PREFIX}gripper_{side}_joint_"
        active = prefix + "L1"
        info.gripper_joints[side] = active
        for follower, coef in GRIPPER_COUPLING:
            eq = spec.add_equality()
            eq.type = mujoco.mjtEq.mjEQ_JOINT
            eq.name1, eq.name2 = prefix + follower, active
            eq.data[:5] = (0.0, coef, 0.0, 0.0, 0.0)
            eq.solref = (0.005, 1.0)
    info.actuated_joints = ARM_JOINTS["left"] + ARM_JOINTS["right"] + [TORSO_YAW_JOINT, HEAD_PITCH_JOINT]
    _add_actuators(spec, info)
    return info


def _position_actuator(spec, name, joint, kp, kv, force=None):
    a = spec.add_actuator()
    a.name = name
    a.target = joint
    a.trntype = mujoco.mjtTrn.mjTRN_JOINT
    a.set_to_position(kp=kp, kv=kv)
    if force is not None:
        a.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
        a.forcerange = (-force, force)
    return a


def _add_actuators(spec: mujoco.MjSpec, info: RobotSpecInfo) -> None:
    for side in ARMS:
        for j in ARM_JOINTS[side]:
            _position_actuator(spec, j, j, *ARM_GAINS)
    # Torso and head drives track the reference's position AND velocity (a PD drive with a velocity
    # target, as SAPIEN's joint drives): a position actuator (stiffness) plus a velocity actuator
    # (damping) whose control is the rate-limited reference's velocity.
    for joint, (kp, _kv) in ((TORSO_YAW_JOINT, TORSO_GAINS), (HEAD_PITCH_JOINT, HEAD_GAINS)):
        _position_actuator(spec, joint, joint, kp, 0.0)
    for side in ARMS:
        _position_actuator(
            spec,
            f"{PREFIX}gripper_{side}",
            info.gripper_joints[side],
            *GRIPPER_GAINS,
            force=GRIPPER_FORCE * GRIPPER_FINGER_LEVER,
        )
    for joint, (_kp, kv) in ((TORSO_YAW_JOINT, TORSO_GAINS), (HEAD_PITCH_JOINT, HEAD_GAINS)):
        a = spec.add_actuator()
        a.name, a.target, a.trntype = f"{joint}_velocity", joint, mujoco.mjtTrn.mjTRN_JOINT
        a.set_to_velocity(kv=kv)
