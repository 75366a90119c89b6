"""analysis/policies/count_press_offsets.py: where the arm came lowest, measured against the buttons."""

import numpy as np
import pytest
from helpers.analysis_scripts import load


def _record(lowest, count=2):
    # buttons at 0.4 m from the base: button 1 straight ahead (+y), 2 at 40 deg to the left, 3 at 40 to the right
    ahead = np.radians(90.0)
    points = {
        n: np.array([0.4 * np.cos(ahead + np.radians(a)), 0.4 * np.sin(ahead + np.radians(a)), 0.05])
        for n, a in ((1, 0.0), (2, 40.0), (3, -40.0))
    }
    return {"lowest": np.asarray(lowest, float), "count": count, "points": points}


def test_a_press_on_the_matching_button_has_no_offset():
    offsets = load("analysis/policies/count_press_offsets.py").offsets
    r = _record(lowest=[0.0, 0.0, 0.0], count=2)
    r["lowest"] = r["points"][2] + [0.0, 0.0, 0.035]
    o = offsets(r)
    assert o["nearest"] == 2
    assert o["to_matching"] == pytest.approx(0.0, abs=1e-9)
    assert o["azimuth"] == pytest.approx(0.0, abs=1e-6)
    assert o["radial"] == pytest.approx(0.0, abs=1e-9)
    assert o["height"] == pytest.approx(0.035)
    assert o["target_bearing"] == pytest.approx(40.0)


def test_coming_down_straight_ahead_misses_a_button_to_the_side_by_its_bearing():
    offsets = load("analysis/policies/count_press_offsets.py").offsets
    o = offsets(_record(lowest=[0.0, 0.35, 0.08], count=2))
    assert o["nearest"] == 1
    assert o["azimuth"] == pytest.approx(-40.0)
    assert o["radial"] == pytest.approx(-0.05)
    assert o["to_matching"] > o["to_nearest"]
    # between the buttons' centroid and button 1: the centroid sits nearer the base than button 1
    assert o["to_centroid"] < o["to_matching"]
