"""Placement relations on typed functional metadata, each on hand-placed scenes where it must hold
and where it must not (poses as placed, contacts from ``mj_forward``), and the metadata's own
validation: every registered asset declares what it refers to, and a wrong declaration is named."""

import mujoco
import numpy as np
import pytest

from lerobot_activearena.sim.assets.functional import Functional, Support
from lerobot_activearena.sim.assets.registry import ASSETS, build_asset
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim
from lerobot_activearena.sim.workspace import TABLE_TOP
from lerobot_activearena.tasks import predicates

Z = TABLE_TOP + 0.0005  # resting on the table, 0.5 mm in contact
AHEAD = np.array([0.0, 0.45, Z])  # straight ahead of the robot, in its arms' band


def _scene(*objects):
    """(kind, name, pos, yaw, params) placed as given -> (sim, {name: ObjectInfo})."""
    builder = SceneBuilder()
    infos = {
        name: builder.add_object_at(kind, name, pos, yaw, static=ASSETS[kind].static, **params)
        for kind, name, pos, yaw, params in objects
    }
    model, info = builder.compile()
    return ActiveArenaSim(model, info), infos


def _at(dx=0.0, dy=0.0, dz=0.0):
    return AHEAD + [dx, dy, dz]


@pytest.mark.parametrize(
    ("shift", "expected"),
    [((0.0, 0.0, 0.0), True), ((0.0, 0.0, 0.03), False), ((0.09, 0.0, 0.0), False)],
)
def test_on_support_needs_the_base_on_the_top_surface(shift, expected):
    sim, o = _scene(
        ("mat", "mat", _at(), 0.0, {}),
        ("mouse", "mouse", _at(shift[0], shift[1], 0.004 + shift[2]), 0.0, {}),
    )
    assert predicates.on_support(sim, o["mouse"], o["mat"]) is expected


def test_on_support_reads_the_footprint_not_a_radius():
    # a shoe centred on a small pad has its centre over the pad but most of its sole off it
    sim, o = _scene(
        ("color_pad", "pad", _at(), 0.0, {"half": 0.03}),
        ("shoe", "shoe", _at(dz=0.004), 0.0, {}),
        ("color_pad", "big_pad", _at(dx=0.3), 0.0, {"half": 0.14}),
        ("shoe", "shoe2", _at(dx=0.3, dz=0.004), 0.0, {}),
    )
    assert not predicates.on_support(sim, o["shoe"], o["pad"])
    assert predicates.on_support(sim, o["shoe2"], o["big_pad"])


def test_on_support_uses_the_disc_shape_of_a_coaster():
    r = 0.05
    corner = r * 0.85  # inside the coaster's bounding square, outside its disc
    sim, o = _scene(
        ("coaster", "coaster", _at(), 0.0, {"radius": r}),
        ("block", "in", _at(dz=0.006), 0.0, {"half": (0.01, 0.01, 0.01)}),
        ("coaster", "coaster2", _at(dx=0.3), 0.0, {"radius": r}),
        ("block", "corner", _at(dx=0.3 + corner, dy=corner, dz=0.006), 0.0, {"half": (0.01, 0.01, 0.01)}),
    )
    assert predicates.on_support(sim, o["in"], o["coaster"])
    assert not predicates.on_support(sim, o["corner"], o["coaster2"])


def test_relations_refuse_objects_without_the_metadata():
    sim, o = _scene(("block", "a", _at(), 0.0, {}), ("block", "b", _at(dx=0.2), 0.0, {}))
    with pytest.raises(ValueError, match="declares no support surface"):
        predicates.on_support(sim, o["a"], o["b"])
    with pytest.raises(ValueError, match="declares no container"):
        predicates.in_container(sim, o["a"], o["b"])
    with pytest.raises(ValueError, match="declares no front"):
        predicates.facing(sim, o["a"])
    with pytest.raises(ValueError, match="declares no tool head"):
        predicates.struck(sim, o["a"], o["b"])


def test_in_container_means_over_the_floor_and_below_the_rim():
    sim, o = _scene(
        ("plastic_box", "box", _at(), 0.0, {}),
        ("can", "inside", _at(dz=0.006), 0.0, {}),
        ("plastic_box", "box2", _at(dx=0.3), 0.0, {}),
        ("can", "on_rim", _at(dx=0.3, dz=0.0705), 0.0, {}),
        ("can", "beside", _at(dx=0.3, dy=-0.15), 0.0, {}),
    )
    assert predicates.in_container(sim, o["inside"], o["box"])
    assert not predicates.in_container(sim, o["on_rim"], o["box2"])
    assert not predicates.in_container(sim, o["beside"], o["box2"])


def _lay_down(sim, body: str, centre, roll: float):
    """Put a free body's axis horizontal (along world x), rolled ``roll`` rad about it, its centre at
    ``centre``."""
    jnt = sim.model.body(body).jntadr[0]
    adr = sim.model.jnt_qposadr[jnt]
    lie, spin = np.zeros(4), np.zeros(4)
    mujoco.mju_axisAngle2Quat(lie, [0.0, 1.0, 0.0], np.pi / 2)  # body z -> world x
    mujoco.mju_axisAngle2Quat(spin, [0.0, 0.0, 1.0], roll)  # about the can's own axis
    quat = np.zeros(4)
    mujoco.mju_mulQuat(quat, lie, spin)
    sim.data.qpos[adr : adr + 3] = centre
    sim.data.qpos[adr + 3 : adr + 7] = quat
    mujoco.mj_forward(sim.model, sim.data)


@pytest.mark.parametrize("roll", [0.0, np.pi / 4])
def test_in_container_reads_the_lowest_point_of_a_can_on_its_side(roll):
    """A can lying in the bread basket, rolled any way about its axis: its lowest point is its
    cylinder's, not the corner of its bounding box (which hangs below the floor at 45 deg)."""
    sim, o = _scene(("bread_basket", "basket", _at(), 0.0, {}), ("can", "can", _at(dx=0.3), 0.0, {}))
    can, basket = o["can"], o["basket"]
    radius = 0.033
    floor = sim.data.body("basket").xpos[2] + basket.functional.container.floor
    body_centre = np.array([AHEAD[0], AHEAD[1], floor + radius + 0.0005])
    # the can's body origin is its bottom; its centre is half its length further along the axis
    _lay_down(sim, "can", body_centre - [can.center_offset[2], 0.0, 0.0], roll)
    assert predicates.lowest_z(sim, can) == pytest.approx(floor + 0.0005, abs=1e-6)
    assert predicates.in_container(sim, can, basket, any_face=True)
    overshoot = predicates.footprint_points(sim, can, lowest_face=True)[:, 2].min() - floor
    assert (overshoot < -0.01) == (roll > 0)  # the box's estimate, the reason for any_face
    _lay_down(sim, "can", body_centre + [-can.center_offset[2], 0.0, 0.06], roll)  # lying on the rim
    assert not predicates.in_container(sim, can, basket, any_face=True)


def test_stacked_on_needs_the_top_block_centred_on_the_lower_one():
    h = 0.025
    sim, o = _scene(
        ("block", "red", _at(), 0.0, {}),
        ("block", "green", _at(dz=2 * h), 0.0, {}),
        ("block", "red2", _at(dx=0.3), 0.0, {}),
        ("block", "green2", _at(dx=0.34, dz=2 * h), 0.0, {}),
        ("block", "green3", _at(dx=-0.2), 0.0, {}),
    )
    assert predicates.stacked_on(sim, o["green"], o["red"])
    assert not predicates.stacked_on(sim, o["red"], o["green"])
    assert not predicates.stacked_on(sim, o["green2"], o["red2"])  # 4 cm off centre
    assert not predicates.stacked_on(sim, o["green3"], o["red"])  # beside it on the table


def _polar(r, deg, dz=0.0):
    t = np.radians(deg)
    return np.array([r * np.cos(t), r * np.sin(t), Z + dz])


def test_beside_reads_angular_order_gap_and_distance_from_the_base():
    sim, o = _scene(
        ("block", "a", _polar(0.45, 105), 0.0, {}),
        ("block", "b", _polar(0.45, 90), 0.0, {}),
        ("block", "far_out", _polar(0.56, 105), 0.0, {}),
        ("block", "too_far", _polar(0.45, 125), 0.0, {}),
    )
    assert predicates.beside(sim, o["a"], o["b"], "left")
    assert not predicates.beside(sim, o["a"], o["b"], "right")
    assert predicates.beside(sim, o["b"], o["a"], "right")
    assert not predicates.beside(sim, o["far_out"], o["b"], "left")  # 11 cm further out
    assert not predicates.beside(sim, o["too_far"], o["b"], "left")  # 27 cm apart
    with pytest.raises(ValueError, match="side must be"):
        predicates.beside(sim, o["a"], o["b"], "behind")


def test_facing_the_robot_within_the_tolerance():
    # the fan's front is its body's -x: yawed +90 deg it points to -y, at the robot straight ahead
    sim, o = _scene(
        ("fan", "facing", _at(), np.pi / 2, {}),
        ("fan", "turned", _at(dx=0.3), np.pi / 2 + np.radians(40), {}),
        ("fan", "sideways", _at(dx=-0.3), 0.0, {}),
    )
    assert predicates.facing(sim, o["facing"])
    assert not predicates.facing(sim, o["turned"])  # 40 deg off (the fan at x 0.3 adds a few more)
    assert not predicates.facing(sim, o["sideways"])
    assert predicates.facing(sim, o["sideways"], direction=(-1.0, 0.0))


def test_touching_reads_the_contacts_between_two_objects():
    sim, o = _scene(
        ("block", "low", _at(), 0.0, {}),
        ("block", "high", _at(dz=0.0495), 0.0, {}),  # 0.5 mm into the lower block
        ("block", "apart", _at(dx=0.2), 0.0, {}),
    )
    assert predicates.touching(sim, o["high"], o["low"]) and predicates.touching(sim, o["low"], o["high"])
    assert not predicates.touching(sim, o["apart"], o["low"])


def test_struck_needs_the_head_on_the_top_of_the_target():
    top = 0.0495  # the block's height, less 0.5 mm of contact
    sim, o = _scene(
        ("block", "block", _at(), 0.0, {}),
        # hammer origin 0.11 m behind its head centre: the head rests on the block's top
        ("hammer", "hammer", _at(dx=-0.11, dz=top), 0.0, {}),
        ("block", "block2", _at(dx=0.3), 0.0, {}),
        # the head against the block's side, on the table
        ("hammer", "hammer2", _at(dx=0.3 - 0.11 - 0.043), 0.0, {}),
        ("block", "block3", _at(dx=-0.3), 0.0, {}),
        # the handle on the block's top, the head off it
        ("hammer", "hammer3", _at(dx=-0.3 + 0.03, dz=top), 0.0, {}),
    )
    assert predicates.struck(sim, o["hammer"], o["block"])
    assert predicates.touching(sim, o["hammer2"], o["block2"]) and not predicates.struck(
        sim, o["hammer2"], o["block2"]
    )
    assert predicates.touching(sim, o["hammer3"], o["block3"]) and not predicates.struck(
        sim, o["hammer3"], o["block3"]
    )


def test_every_asset_declares_metadata_its_model_has():
    builder = SceneBuilder()
    infos = [
        build_asset(builder.spec, kind, f"{kind}_0", (0.0, 0.5 + 0.0 * k, TABLE_TOP), 0.0)
        for k, kind in enumerate(sorted(ASSETS))
    ]
    model, _ = builder.compile()
    assert {
        i.category: i.functional.missing_names(model) for i in infos if i.functional.missing_names(model)
    } == {}
    declared = {i.category for i in infos if i.functional != Functional()}
    assert {
        "mat",
        "coaster",
        "color_pad",
        "plate",
        "plastic_box",
        "bread_basket",
        "hammer",
        "fan",
    } <= declared
    assert {"bell", "button", "stapler", "switch"} <= {i.category for i in infos if i.functional.press}


def test_a_wrong_declaration_names_the_asset_and_the_field():
    with pytest.raises(ValueError, match="pad: support top 0.05 m is outside its height"):
        Functional(support=Support(0.05, (0.03, 0.03))).validate("pad", (0.03, 0.03, 0.002), (0, 0, 0.002))
    with pytest.raises(ValueError, match="mat: support shape must be one of"):
        Functional(support=Support(0.004, (0.03, 0.03), "ring")).validate(
            "mat", (0.03, 0.03, 0.002), (0, 0, 0.002)
        )
    with pytest.raises(ValueError, match="cup: grasp point 0 .* lies outside its bounding box"):
        Functional(grasp=((0.0, 0.0, 0.2),)).validate("cup", (0.03, 0.03, 0.05), (0, 0, 0.05))
