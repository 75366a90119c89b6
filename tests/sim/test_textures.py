"""Procedural textures: deterministic, seamless when repeated, distinct per family."""

import numpy as np
import pytest

from lerobot_activearena.sim.look.textures import FAMILIES, make_texture

GREY = (0.6, 0.55, 0.5)


def _step(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a.astype(float) - b.astype(float)).mean())


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_texture_is_deterministic_and_seamless(family):
    tex = make_texture(family, 3, GREY, 128)
    assert tex.shape == (128, 128, 3) and tex.dtype == np.uint8
    assert np.array_equal(tex, make_texture(family, 3, GREY, 128))
    assert not np.array_equal(tex, make_texture(family, 4, GREY, 128))
    # across the wrap-around seam the image changes no more than between neighbouring rows / columns
    inner_x = np.mean([_step(tex[:, k], tex[:, k + 1]) for k in range(127)])
    inner_y = np.mean([_step(tex[k], tex[k + 1]) for k in range(127)])
    assert _step(tex[:, -1], tex[:, 0]) <= 2.0 * inner_x + 1.0
    assert _step(tex[-1], tex[0]) <= 2.0 * inner_y + 1.0


def test_texture_follows_the_base_colour():
    for family in FAMILIES:
        red = make_texture(family, 0, (0.8, 0.2, 0.2), 64).reshape(-1, 3).mean(0)
        blue = make_texture(family, 0, (0.2, 0.2, 0.8), 64).reshape(-1, 3).mean(0)
        assert red[0] > red[2] + 40 and blue[2] > blue[0] + 40, family


def test_bad_requests_are_refused():
    with pytest.raises(ValueError, match="unknown texture family 'velvet'"):
        make_texture("velvet", 0, GREY)
    with pytest.raises(ValueError, match="power of two"):
        make_texture("wood", 0, GREY, 100)
