"""The scene look's building blocks: tabletop slab, materials, lighting (appearance only)."""

import mujoco
import numpy as np
import pytest

from lerobot_activearena.sim.look import DEFAULT_LOOK, draw_look
from lerobot_activearena.sim.look.lighting import ID_LIGHTING, OOD_KELVIN, kelvin_to_rgb
from lerobot_activearena.sim.look.materials import (
    ID_MATERIALS,
    add_surface_material,
    id_families,
    ood_families,
)
from lerobot_activearena.sim.look.room import add_room, add_sky
from lerobot_activearena.sim.look.tabletop import add_tabletop_visual, tabletop_mesh
from lerobot_activearena.sim.workspace import fan_workspace, two_level_workspace


@pytest.mark.parametrize("workspace", [fan_workspace, two_level_workspace])
def test_tabletop_slab_is_closed_outward_facing_and_inside_the_level(workspace):
    for lv in workspace().levels:
        v, f, n, uv = tabletop_mesh(lv)
        r = np.hypot(v[:, 0], v[:, 1])
        assert r.min() >= lv.inner_radius - 1e-9 and r.max() <= lv.outer_radius + 1e-9
        assert v[:, 2].min() >= lv.top_z - lv.thickness - 1e-9 and v[:, 2].max() <= lv.top_z + 1e-9
        a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
        geometric = np.cross(b - a, c - a)
        geometric /= np.linalg.norm(geometric, axis=1, keepdims=True)
        for k in range(3):  # every triangle faces the way its vertices' normals say
            assert np.all(np.einsum("ij,ij->i", geometric, n[f[:, k]]) > 0.999)
        # closed: the signed volume (divergence theorem) is the slab's, to the chords' approximation
        volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
        exact = np.radians(lv.span_deg) / 2 * (lv.outer_radius**2 - lv.inner_radius**2) * lv.thickness
        assert volume == pytest.approx(exact, rel=0.01)
        assert np.array_equal(uv, v[:, :2])


def test_look_compiles_into_a_scene_and_the_room_has_no_contacts():
    spec = mujoco.MjSpec()
    look = draw_look("ood", np.random.default_rng(3))
    for role in ("table", "floor", "wall"):
        add_surface_material(spec, role, getattr(look, role), texture_px=64, uniform=role != "table")
    add_sky(spec)
    add_room(spec, "wall", "wall")
    body = spec.worldbody.add_body()
    body.name = "fan_level_0"
    add_tabletop_visual(spec, body, fan_workspace().levels[0], "fan_top_0", "table")
    model = spec.compile()
    walls = [model.geom(g).id for g in ("wall_front", "wall_back", "wall_left", "wall_right", "ceiling")]
    walls.append(model.geom("fan_top_0").id)
    assert np.all(model.geom_contype[walls] == 0) and np.all(model.geom_conaffinity[walls] == 0)


def test_id_looks_come_from_a_fixed_set_and_ood_from_held_out_families():
    assert id_families().isdisjoint(ood_families())
    rng = np.random.default_rng(0)
    id_looks = [draw_look("id", rng) for _ in range(40)]
    assert all(look.lighting == ID_LIGHTING for look in id_looks)
    for role in ("table", "floor", "wall"):
        assert {getattr(look, role) for look in id_looks} == set(ID_MATERIALS[role])
    ood = [draw_look("ood", rng) for _ in range(40)]
    for look in ood:
        assert not {look.table.family, look.floor.family, look.wall.family} & id_families()
        lt = look.lighting
        assert lt.elevation_deg < ID_LIGHTING.elevation_deg
        assert any(lo <= lt.kelvin <= hi for lo, hi in OOD_KELVIN)
        assert abs(lt.intensity - ID_LIGHTING.intensity) > 0.1
        assert abs(lt.ambient - ID_LIGHTING.ambient) > 0.05
    assert draw_look("ood", np.random.default_rng(7)) == draw_look("ood", np.random.default_rng(7))


def test_colour_temperature_runs_from_warm_to_cold():
    warm, neutral, cold = kelvin_to_rgb(2700), kelvin_to_rgb(6500), kelvin_to_rgb(10000)
    assert warm[0] == 1.0 and warm[2] < 0.5
    assert min(neutral) > 0.9
    assert cold[2] == 1.0 and cold[0] < 0.85
    with pytest.raises(ValueError, match="1500-15000 K"):
        kelvin_to_rgb(500)


def _faces_agree_with_normals(mesh, min_dot: float):
    a, b, c = (mesh.vertices[mesh.faces[:, k]] for k in range(3))
    geometric = np.cross(b - a, c - a)
    keep = np.linalg.norm(geometric, axis=1) > 1e-12
    geometric = geometric[keep] / np.linalg.norm(geometric[keep], axis=1, keepdims=True)
    return all(
        np.all(np.einsum("ij,ij->i", geometric, mesh.normals[mesh.faces[keep, k]]) > min_dot)
        for k in range(3)
    )


def test_lathed_and_extruded_meshes_are_closed_and_outward_facing():
    from lerobot_activearena.sim.look.meshes import extrude, lathe

    r, h = 0.033, 0.12
    can = lathe([(0, 0), (r, 0), (r, h), (0, h)], segments=64)
    polygon_area = 64 / 2 * r * r * np.sin(2 * np.pi / 64)
    assert can.volume() == pytest.approx(polygon_area * h, rel=1e-6)
    lo, hi = can.bounds()
    assert np.allclose(lo, [-r, -r, 0], atol=1e-12) and np.allclose(hi, [r, r, h], atol=1e-12)
    assert _faces_agree_with_normals(can, 0.99)  # all edges of a can are creases: flat normals
    assert can.texcoords.min() >= 0 and can.texcoords.max() <= 1
    # a bell: a curved profile is shaded smooth, so normals only roughly follow each face
    t = np.linspace(0, np.pi / 2, 12)
    bell = lathe([(0, 0), *zip(0.04 * np.cos(t) + 1e-3, 0.05 * np.sin(t), strict=True), (0, 0.05)])
    assert bell.volume() > 0 and _faces_agree_with_normals(bell, 0.8)
    # an L-shaped (non-convex) outline
    outline = [(0, 0), (0.1, 0), (0.1, 0.03), (0.04, 0.03), (0.04, 0.08), (0, 0.08)]
    block = extrude(outline, 0.02)
    assert block.volume() == pytest.approx((0.1 * 0.03 + 0.04 * 0.05) * 0.02, rel=1e-9)
    assert _faces_agree_with_normals(block, 0.99)
    with pytest.raises(ValueError, match="counter-clockwise"):
        extrude(outline[::-1], 0.02)
    with pytest.raises(ValueError, match="r >= 0"):
        lathe([(-0.01, 0), (0.02, 0.1)])
    # turned: a can laid along x keeps its volume, bounds follow, normals still face outward
    from lerobot_activearena.sim.look.meshes import rotated

    laid = rotated(can, (0, 1, 0), np.pi / 2)
    assert laid.volume() == pytest.approx(can.volume(), rel=1e-9)
    lo, hi = laid.bounds()
    assert np.allclose(lo, [0, -r, -r], atol=1e-9) and np.allclose(hi, [h, r, r], atol=1e-9)
    assert _faces_agree_with_normals(laid, 0.99)


def _seen_ids(model, data, cam: str, size=(96, 128)) -> np.ndarray:
    """Per pixel, the geom the head camera sees (-1: nothing, the void)."""
    with mujoco.Renderer(model, *size) as r:
        r.enable_segmentation_rendering()
        r.update_scene(data, camera=cam)
        return r.render()[..., 0]


@pytest.mark.parametrize("workspace", ["fan", "two_level"])
@pytest.mark.parametrize("split", ["id", "ood"])
def test_no_view_the_robot_can_take_shows_the_void(workspace, split):
    """Torso yaw and head pitch at their limits (and home): every pixel is a wall, the floor, the
    ceiling, the table, the robot or an object, never the empty background."""
    from lerobot_activearena.sim import embodiment
    from lerobot_activearena.sim.scene import SceneBuilder
    from lerobot_activearena.sim.workspace import WORKSPACES

    look = draw_look(split, np.random.default_rng(11))
    model, _ = SceneBuilder(workspace=WORKSPACES[workspace](), look=look).compile()
    data = mujoco.MjData(model)
    yaw, pitch = model.joint(embodiment.TORSO_YAW_JOINT), model.joint(embodiment.HEAD_PITCH_JOINT)
    for y in (*yaw.range, embodiment.HOME_TORSO_YAW):
        for p in (*pitch.range, embodiment.HOME_HEAD_PITCH):
            data.qpos[yaw.qposadr[0]], data.qpos[pitch.qposadr[0]] = y, p
            mujoco.mj_forward(model, data)
            void = int((_seen_ids(model, data, embodiment.HEAD_CAMERA) < 0).sum())
            assert void == 0, f"yaw {y:.2f}, pitch {p:.2f}: {void} pixels of void"


def test_the_look_never_moves_an_object(monkeypatch):
    """The look is drawn from a stream of its own: an OOD scene with the ID look instead has the
    same objects at the same poses."""
    from lerobot_activearena.tasks import draft as draft_module, get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    task = get_task("place_a2b_left_rotate_view")

    def poses(scene):
        return {
            o.name: (o.category, *np.round(scene.model.body(o.body).pos, 9))
            for o in scene.info.objects + scene.info.clutter
        }

    drawn = [sample_scene(task, seed, "ood") for seed in range(3)]
    monkeypatch.setattr(draft_module, "draw_look", lambda split, rng: DEFAULT_LOOK)
    plain = [sample_scene(task, seed, "ood") for seed in range(3)]
    for a, b in zip(drawn, plain, strict=True):
        assert poses(a) == poses(b) and a.params == b.params
        assert not np.array_equal(a.model.light("key_light").diffuse, b.model.light("key_light").diffuse)
