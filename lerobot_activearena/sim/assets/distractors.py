"""Distractor pool: everyday objects that no task uses (ID clutter draws only from these). Families
group near-duplicates so OOD scenes never hold two of a kind."""

from __future__ import annotations

import numpy as np

from .registry import register_asset
from .shapes import compound, cone_mesh, quat_axis_angle, text_texture

X90 = quat_axis_angle([1, 0, 0], np.pi / 2)
Y90 = quat_axis_angle([0, 1, 0], np.pi / 2)


def _c(rng, lo=0.15, hi=0.9):
    return (*(float(x) for x in rng.uniform(lo, hi, 3)), 1.0)


def _jitter(base, rng, amount=0.08):
    return (*(float(np.clip(c + rng.uniform(-amount, amount), 0, 1)) for c in base[:3]), 1.0)


def _simple(category, footprint, family, parts, mass, colors=None):
    """Register a distractor made of ``parts`` (see ``shapes.compound``); part colours given as
    'main' are replaced by the ``rgba`` parameter, randomised from ``colors(rng)``."""

    def build(spec, name, pos, yaw=0.0, rgba=(0.7, 0.7, 0.7, 1)):
        main = rgba
        resolved = [(p[0], p[1], p[2], main if p[3] == "main" else p[3], *p[4:]) for p in parts]
        return compound(spec, name, category, pos, yaw, resolved, mass)

    register_asset(category, footprint, "distractor", family, randomize=(lambda rng: {"rgba": colors(rng)}) if colors else None)(build)


RED, GREEN, YELLOW, BROWN = (0.8, 0.1, 0.1, 1), (0.2, 0.6, 0.2, 1), (0.95, 0.85, 0.2, 1), (0.45, 0.3, 0.15, 1)
STEM = (0.35, 0.25, 0.1, 1)

_simple("apple", 0.04, "apple", [("sph", (0.036,), (0, 0, 0.036), "main"), ("cyl", (0.003, 0.008, 0), (0, 0, 0.076), STEM)],
        0.18, lambda r: _jitter(RED if r.random() < 0.6 else (0.5, 0.8, 0.2, 1), r))
_simple("orange", 0.04, "citrus", [("sph", (0.037,), (0, 0, 0.037), (0.98, 0.55, 0.05, 1))], 0.2)
_simple("lemon", 0.035, "lemon", [("ell", (0.04, 0.028, 0.028), (0, 0, 0.028), (0.98, 0.9, 0.2, 1))], 0.1)
_simple("pear", 0.04, "pear", [("sph", (0.035,), (0, 0, 0.035), "main"), ("sph", (0.024,), (0, 0, 0.075), "main"),
                               ("cyl", (0.003, 0.008, 0), (0, 0, 0.105), STEM)], 0.18, lambda r: _jitter((0.7, 0.8, 0.25, 1), r))
_simple("tomato", 0.035, "tomato", [("ell", (0.034, 0.034, 0.028), (0, 0, 0.028), (0.9, 0.15, 0.1, 1)),
                                    ("cyl", (0.012, 0.002, 0), (0, 0, 0.056), (0.2, 0.55, 0.15, 1))], 0.12)
_simple("banana", 0.1, "banana", [("cap", (0.017, 0.06, 0), (0, 0, 0.017), "main", {"quat": Y90}),
                                  ("cap", (0.015, 0.03, 0), (0.08, 0.02, 0.02), "main",
                                   {"quat": quat_axis_angle([-0.3, 1, 0], np.pi / 2 + 0.3)})], 0.15,
        lambda r: _jitter(YELLOW, r, 0.05))
_simple("carrot", 0.09, "carrot", [("cap", (0.014, 0.06, 0), (0, 0, 0.014), (0.95, 0.45, 0.05, 1), {"quat": Y90}),
                                   ("cyl", (0.01, 0.015, 0), (-0.085, 0, 0.014), (0.2, 0.6, 0.15, 1), {"quat": Y90})], 0.08)
_simple("eggplant", 0.09, "eggplant", [("ell", (0.075, 0.03, 0.03), (0, 0, 0.03), (0.35, 0.1, 0.4, 1)),
                                       ("cyl", (0.01, 0.012, 0), (0.085, 0, 0.03), (0.2, 0.5, 0.15, 1), {"quat": Y90})], 0.25)
_simple("corn", 0.1, "corn", [("ell", (0.085, 0.024, 0.024), (0, 0, 0.024), (0.95, 0.8, 0.2, 1)),
                              ("ell", (0.06, 0.02, 0.012), (0.02, 0.012, 0.034), (0.4, 0.65, 0.2, 1), {"visual": True})], 0.2)
_simple("bread_loaf", 0.1, "bread", [("ell", (0.09, 0.05, 0.04), (0, 0, 0.035), (0.78, 0.55, 0.25, 1))], 0.3)
_simple("donut", 0.05, "donut", [("cyl", (0.045, 0.014, 0), (0, 0, 0.014), (0.8, 0.6, 0.35, 1)),
                                 ("cyl", (0.04, 0.002, 0), (0, 0, 0.029), "main", {"visual": True}),
                                 ("cyl", (0.015, 0.0025, 0), (0, 0, 0.0305), (0.25, 0.15, 0.1, 1), {"visual": True})], 0.06,
        lambda r: _c(r, 0.4, 1.0))
_simple("teapot", 0.08, "teapot", [("ell", (0.06, 0.06, 0.05), (0, 0, 0.05), "main"),
                                   ("cap", (0.01, 0.03, 0), (0.075, 0, 0.06), "main", {"quat": quat_axis_angle([0, 1, 0], 0.8)}),
                                   ("cyl", (0.02, 0.008, 0), (0, 0, 0.105), "main"),
                                   ("cap", (0.007, 0.025, 0), (-0.07, 0, 0.06), "main", {"quat": X90, "visual": True})], 0.4,
        lambda r: _c(r, 0.3, 0.95))
_simple("kettle", 0.08, "kettle", [("cyl", (0.065, 0.07, 0), (0, 0, 0.07), (0.78, 0.79, 0.8, 1)),
                                   ("box", (0.012, 0.01, 0.05), (-0.075, 0, 0.09), (0.1, 0.1, 0.1, 1))], 0.6)
_simple("book", 0.11, "book", [("box", (0.1, 0.07, 0.015), (0, 0, 0.015), "main"),
                               ("box", (0.097, 0.068, 0.0135), (0.004, 0, 0.015), (0.95, 0.93, 0.88, 1), {"visual": True})],
        0.4, lambda r: _c(r, 0.1, 0.8))
_simple("remote_control", 0.09, "remote", [("box", (0.08, 0.022, 0.01), (0, 0, 0.01), (0.12, 0.12, 0.13, 1)),
                                           ("cyl", (0.006, 0.002, 0), (0.05, 0, 0.021), (0.85, 0.1, 0.1, 1), {"visual": True}),
                                           ("box", (0.03, 0.015, 0.0015), (-0.01, 0, 0.0205), (0.5, 0.5, 0.52, 1), {"visual": True})],
        0.1)
_simple("toy_car", 0.07, "toy_car", [("box", (0.06, 0.03, 0.015), (0, 0, 0.025), "main"),
                                     ("box", (0.03, 0.027, 0.014), (-0.005, 0, 0.052), (0.7, 0.85, 0.95, 1)),
                                     *[("cyl", (0.012, 0.006, 0), (x, y, 0.012), (0.05, 0.05, 0.05, 1), {"quat": X90})
                                       for x in (-0.035, 0.035) for y in (-0.03, 0.03)]], 0.15, lambda r: _c(r))
_simple("rubber_duck", 0.05, "duck", [("ell", (0.045, 0.033, 0.028), (0, 0, 0.028), (0.98, 0.85, 0.1, 1)),
                                      ("sph", (0.022,), (0.025, 0, 0.068), (0.98, 0.85, 0.1, 1)),
                                      ("ell", (0.012, 0.008, 0.004), (0.05, 0, 0.066), (0.95, 0.45, 0.05, 1), {"visual": True})],
        0.05)
_simple("alarm_clock", 0.05, "clock", [("cyl", (0.045, 0.02, 0), (0, 0, 0.047), "main", {"quat": Y90}),
                                       ("cyl", (0.038, 0.001, 0), (-0.021, 0, 0.047), (0.97, 0.97, 0.95, 1), {"quat": Y90, "visual": True}),
                                       ("box", (0.015, 0.03, 0.003), (0, 0, 0.003), (0.2, 0.2, 0.2, 1))], 0.2, lambda r: _c(r))
_simple("calculator", 0.07, "calculator", [("box", (0.055, 0.04, 0.008), (0, 0, 0.008), (0.2, 0.2, 0.22, 1)),
                                           ("box", (0.015, 0.032, 0.001), (0.035, 0, 0.0165), (0.6, 0.7, 0.6, 1), {"visual": True}),
                                           ("box", (0.03, 0.033, 0.0008), (-0.015, 0, 0.0165), (0.75, 0.75, 0.78, 1), {"visual": True})],
        0.12)
_simple("tape_roll", 0.045, "tape", [("cyl", (0.042, 0.013, 0), (0, 0, 0.013), "main"),
                                     ("cyl", (0.028, 0.0005, 0), (0, 0, 0.0265), (0.55, 0.45, 0.35, 1), {"visual": True})],
        0.08, lambda r: _c(r, 0.3, 0.95))
_simple("sponge", 0.06, "sponge", [("box", (0.05, 0.032, 0.012), (0, 0, 0.012), (0.95, 0.85, 0.2, 1)),
                                   ("box", (0.05, 0.032, 0.005), (0, 0, 0.029), (0.1, 0.55, 0.2, 1))], 0.03)
_simple("candle", 0.035, "candle", [("cyl", (0.028, 0.045, 0), (0, 0, 0.045), "main"),
                                    ("cyl", (0.0015, 0.006, 0), (0, 0, 0.096), (0.1, 0.1, 0.1, 1), {"visual": True})],
        0.2, lambda r: _c(r, 0.6, 1.0))
_simple("flower_pot", 0.05, "pot", [("cyl", (0.045, 0.04, 0), (0, 0, 0.04), (0.75, 0.38, 0.2, 1)),
                                    ("sph", (0.035,), (0, 0, 0.1), (0.2, 0.6, 0.2, 1)),
                                    ("sph", (0.02,), (0.02, 0.01, 0.13), (0.9, 0.3, 0.5, 1), {"visual": True})], 0.5)
_simple("cactus", 0.04, "cactus", [("cyl", (0.035, 0.025, 0), (0, 0, 0.025), (0.85, 0.8, 0.7, 1)),
                                   ("cap", (0.018, 0.04, 0), (0, 0, 0.09), (0.2, 0.55, 0.25, 1)),
                                   ("cap", (0.01, 0.015, 0), (0.028, 0, 0.1), (0.2, 0.55, 0.25, 1), {"quat": quat_axis_angle([0, 1, 0], 0.6)})],
        0.35)
_simple("glasses_case", 0.08, "glasses", [("ell", (0.075, 0.028, 0.02), (0, 0, 0.02), "main")], 0.08, lambda r: _c(r, 0.05, 0.7))
_simple("toothpaste_tube", 0.1, "toothpaste", [("ell", (0.08, 0.024, 0.014), (0, 0, 0.014), (0.95, 0.95, 0.97, 1)),
                                               ("cyl", (0.01, 0.01, 0), (0.09, 0, 0.014), "main", {"quat": Y90})],
        0.1, lambda r: _c(r, 0.2, 0.9))
_simple("milk_carton", 0.045, "carton", [("box", (0.035, 0.035, 0.07), (0, 0, 0.07), (0.96, 0.96, 0.97, 1)),
                                         ("box", (0.035, 0.025, 0.012), (0, 0, 0.152), (0.96, 0.96, 0.97, 1),
                                          {"quat": quat_axis_angle([1, 0, 0], 0.9)}),
                                         ("box", (0.0355, 0.0355, 0.02), (0, 0, 0.09), (0.2, 0.45, 0.85, 1), {"visual": True})], 0.3)
_simple("dice", 0.03, "dice", [("box", (0.02, 0.02, 0.02), (0, 0, 0.02), (0.96, 0.96, 0.96, 1)),
                               *[("sph", (0.004,), p, (0.1, 0.1, 0.1, 1), {"visual": True})
                                 for p in ((0, 0, 0.0405), (0.0205, 0.008, 0.028), (0.0205, -0.008, 0.012), (0, -0.0205, 0.02))]],
        0.02)
_simple("chess_pawn", 0.03, "chess", [("cyl", (0.022, 0.006, 0), (0, 0, 0.006), "main"),
                                      ("cyl", (0.011, 0.025, 0), (0, 0, 0.035), "main"),
                                      ("sph", (0.016,), (0, 0, 0.07), "main")], 0.05,
        lambda r: (0.95, 0.95, 0.92, 1) if r.random() < 0.5 else (0.08, 0.08, 0.08, 1))
_simple("lightbulb", 0.035, "bulb", [("sph", (0.03,), (0, 0, 0.05), (0.98, 0.98, 0.85, 0.9)),
                                     ("cyl", (0.013, 0.013, 0), (0, 0, 0.013), (0.7, 0.7, 0.72, 1))], 0.05)
_simple("pepper_grinder", 0.03, "grinder", [("cyl", (0.022, 0.06, 0), (0, 0, 0.06), "main"),
                                            ("sph", (0.018,), (0, 0, 0.125), "main")], 0.25, lambda r: _c(r, 0.1, 0.6))
_simple("tennis_ball", 0.035, "ball", [("sph", (0.033,), (0, 0, 0.033), (0.8, 0.95, 0.2, 1))], 0.06)
_simple("tissue_box", 0.08, "tissue", [("box", (0.065, 0.05, 0.045), (0, 0, 0.045), "main"),
                                       ("box", (0.02, 0.03, 0.008), (0, 0, 0.095), (0.98, 0.98, 0.98, 1), {"visual": True})],
        0.15, lambda r: _c(r, 0.4, 0.95))
_simple("trophy", 0.04, "trophy", [("box", (0.03, 0.03, 0.012), (0, 0, 0.012), (0.2, 0.15, 0.1, 1)),
                                   ("cyl", (0.006, 0.025, 0), (0, 0, 0.049), (0.9, 0.75, 0.2, 1)),
                                   ("cyl", (0.03, 0.025, 0), (0, 0, 0.099), (0.9, 0.75, 0.2, 1))], 0.3)
_simple("toy_robot", 0.04, "robot_toy", [("box", (0.025, 0.02, 0.03), (0, 0, 0.05), "main"),
                                         ("box", (0.018, 0.016, 0.016), (0, 0, 0.096), (0.8, 0.8, 0.82, 1)),
                                         ("box", (0.008, 0.008, 0.01), (0, 0.01, 0.01), (0.3, 0.3, 0.3, 1)),
                                         ("box", (0.008, 0.008, 0.01), (0, -0.01, 0.01), (0.3, 0.3, 0.3, 1))], 0.1,
        lambda r: _c(r, 0.2, 0.95))
_simple("headphones", 0.07, "headphones", [("box", (0.06, 0.012, 0.008), (0, 0, 0.008), (0.1, 0.1, 0.11, 1)),
                                           ("cyl", (0.03, 0.012, 0), (0.055, 0, 0.03), "main", {"quat": Y90}),
                                           ("cyl", (0.03, 0.012, 0), (-0.055, 0, 0.03), "main", {"quat": Y90})], 0.2,
        lambda r: _c(r, 0.05, 0.8))


def _register_cone():
    def build(spec, name, pos, yaw=0.0, rgba=(0.98, 0.45, 0.05, 1)):
        mesh = cone_mesh(spec, f"{name}_cone", 0.035, 0.11)
        return compound(spec, name, "traffic_cone", pos, yaw, [
            ("box", (0.045, 0.045, 0.004), (0, 0, 0.004), rgba),
            ("mesh", (0.035, 0.035, 0.055), (0, 0, 0.008), rgba, {"mesh": mesh, "extent": (0.035, 0.035, 0.11)}),
        ], 0.1)

    register_asset("traffic_cone", 0.05, "distractor", "cone")(build)


def _register_cereal():
    def build(spec, name, pos, yaw=0.0):
        mat = text_texture(spec, f"{name}_print", "CEREAL", bg=(230, 180, 40), fg=(160, 20, 20))
        return compound(spec, name, "cereal_box", pos, yaw, [("box", (0.02, 0.06, 0.08), (0, 0, 0.08), (1, 1, 1, 1),
                                                               {"material": mat})], 0.3)

    register_asset("cereal_box", 0.065, "distractor", "cereal")(build)


_register_cone()
_register_cereal()
