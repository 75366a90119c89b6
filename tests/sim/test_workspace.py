import numpy as np
import pytest

from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim
from lerobot_activearena.sim.workspace import fan_workspace, two_level_workspace


def test_fan_dimensions_and_cylindrical_placement():
    ws = fan_workspace()
    lv = ws.level(0)
    assert (lv.inner_radius, lv.outer_radius, lv.span_deg, lv.center_deg, lv.top_z, lv.thickness) == (
        0.30,
        1.08,
        180.0,
        90.0,
        0.74,
        0.05,
    )
    assert ws.placement_span_deg(0) == (20.0, 160.0)
    np.testing.assert_allclose(ws.place(0.5, 90.0), [0.0, 0.5, 0.74], atol=1e-12)
    np.testing.assert_allclose(ws.place(1.0, 30.0), [np.cos(np.pi / 6), 0.5, 0.74], atol=1e-12)


@pytest.mark.parametrize(
    "args, msg", [((0.2, 90.0), "radius"), ((0.5, 10.0), "margin"), ((0.5, 90.0, 1), "level 1")]
)
def test_placement_errors_name_the_problem(args, msg):
    with pytest.raises(ValueError, match=msg):
        fan_workspace().place(*args)


def test_two_level_geometry():
    ws = two_level_workspace(shift_deg=20.0)
    up = ws.level(1)
    assert (up.inner_radius, up.outer_radius, up.top_z, up.center_deg) == (0.60, 0.80, 1.09, 110.0)
    assert up.top_z - ws.level(0).top_z == pytest.approx(0.35)
    with pytest.raises(ValueError, match="shift"):
        two_level_workspace(shift_deg=10.0)


def test_objects_rest_on_both_levels_and_the_column_stands():
    b = SceneBuilder(workspace=two_level_workspace())
    b.add_object("block", "low", 0.5, 60.0)
    b.add_object("block", "low_edge", 1.05, 100.0)
    b.add_object("block", "high", 0.70, 60.0, level=1)
    model, info = b.compile()
    sim = ActiveArenaSim(model, info)
    for _ in range(20):
        sim.step(sim.home_action())
    d = sim.data
    assert d.body("low").xpos[2] == pytest.approx(0.74, abs=0.003)
    assert d.body("low_edge").xpos[2] == pytest.approx(0.74, abs=0.003)
    assert d.body("high").xpos[2] == pytest.approx(1.09, abs=0.003)
    column = model.geom("fan_support_column")
    assert column.contype == 1 and np.allclose(column.size[:2], 0.025)
    assert np.allclose(d.geom("fan_support_column").xpos[:2], [0.0, 0.775], atol=1e-9)
