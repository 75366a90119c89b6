"""Distractor pool: everyday objects that no task uses (ID clutter draws only from these). Families
group near-duplicates so OOD scenes never hold two of a kind (e.g. an orange and the yellow ball).
The toy car and the bread loaf are built here too but are task objects of ``place_a2b_*`` (role
``"task"``): only OOD clutter, drawn from the full pool, may show them.

None of these resembles a task category: no cups, bottles, cans, plain blocks, printed food boxes,
plates or mouse-like ellipsoids. Most are a few primitives; the donut, scissors rings, pencil and
hourglass use small code-built meshes (< 200 vertices each); fourteen are drawn as code-built meshes
over their primitives, lathed (the round ones) or extruded and textured (a book, a sponge, a tissue
box) (``look=``, ``dressing_clutter.py``). Colours are drawn from plausible
palettes, kept away from the table's tan."""

from __future__ import annotations

import math

import numpy as np

from . import dressing_clutter as looks
from .functional import Functional
from .parts import dress_parts
from .registry import register_asset
from .shapes import compound, quat_axis_angle

X90 = quat_axis_angle([1, 0, 0], np.pi / 2)
Y90 = quat_axis_angle([0, 1, 0], np.pi / 2)
RED, GREEN, YELLOW = (0.8, 0.1, 0.1, 1), (0.2, 0.6, 0.2, 1), (0.95, 0.85, 0.2, 1)
STEM, LEAF, STEEL, DARK = (
    (0.35, 0.25, 0.1, 1),
    (0.2, 0.55, 0.15, 1),
    (0.72, 0.73, 0.76, 1),
    (0.1, 0.1, 0.11, 1),
)
WHITE, WOOD = (0.96, 0.96, 0.95, 1), (0.6, 0.4, 0.2, 1)
PLASTICS = [
    (0.85, 0.12, 0.1),
    (0.1, 0.35, 0.85),
    (0.1, 0.6, 0.25),
    (0.95, 0.8, 0.1),
    (0.95, 0.45, 0.05),
    (0.55, 0.2, 0.7),
    (0.1, 0.7, 0.75),
    (0.9, 0.4, 0.6),
    (0.12, 0.12, 0.13),
    (0.93, 0.93, 0.93),
]


def _jitter(base, rng, amount=0.06):
    return (*(float(np.clip(c + rng.uniform(-amount, amount), 0, 1)) for c in base[:3]), 1.0)


def _pick(palette, amount=0.05):
    """Randomiser: one palette colour, slightly jittered (deterministic given the rng)."""
    return lambda rng: _jitter(palette[int(rng.integers(len(palette)))], rng, amount)


def _simple(
    category, footprint, family, parts, mass, colors=None, functional=None, role="distractor", look=None
):
    """Register an object made of ``parts`` (see ``shapes.compound``); part colours given as
    'main' are replaced by the ``rgba`` parameter, randomised by ``colors(rng)``. A callable part
    ``fn(spec, name)`` returns a part built at build time (meshes need the object's name).
    ``functional``: its metadata where a task uses it (a grasp); ``role="task"`` where some task
    names the category (ID clutter never uses it). ``look``: ``(replaced, fn)``, the part indices
    drawn instead as the meshes ``fn(spec, name, rgba)`` returns (``dressing_clutter.py``)."""
    default = (0.7, 0.7, 0.7, 1) if colors is None else colors(np.random.default_rng(0))

    def build(spec, name, pos, yaw=0.0, rgba=default):
        resolved = []
        for p in parts:
            p = p(spec, name) if callable(p) else p
            resolved.append((p[0], p[1], p[2], rgba if p[3] == "main" else p[3], *p[4:]))
        info = compound(spec, name, category, pos, yaw, resolved, mass, functional=functional)
        if look is not None:
            replaced, draw = look
            dress_parts(spec, name, replaced, draw(spec, name, rgba))
        return info

    register_asset(
        category,
        footprint,
        role,
        family,
        randomize=(lambda rng: {"rgba": colors(rng)}) if colors else None,
    )(build)


# ---- code-built meshes ------------------------------------------------------------------------
def _mesh(spec, name, verts, faces=None):
    mesh = spec.add_mesh()
    mesh.name = name
    mesh.uservert = np.asarray(verts, float).reshape(-1)
    if faces is not None:
        mesh.userface = np.asarray(faces, np.int32).reshape(-1)
    return name


def torus_mesh(spec, name, major, minor, n_major=16, n_minor=8, z_scale=1.0):
    """Closed torus around z (outward-facing triangles); ``z_scale`` flattens the tube."""
    verts = [
        [
            (major + minor * math.cos(v)) * math.cos(u),
            (major + minor * math.cos(v)) * math.sin(u),
            z_scale * minor * math.sin(v),
        ]
        for u in np.linspace(0, 2 * np.pi, n_major, endpoint=False)
        for v in np.linspace(0, 2 * np.pi, n_minor, endpoint=False)
    ]
    faces = []
    for i in range(n_major):
        for j in range(n_minor):
            a, b = i * n_minor + j, ((i + 1) % n_major) * n_minor + j
            c, d = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor, i * n_minor + (j + 1) % n_minor
            faces += [[a, b, c], [a, c, d]]
    return _mesh(spec, name, verts, faces)


def cone(spec, name, radius, height, n=12):
    """Cone along z centred on its mid-height (apex at +height/2), so its part bbox is exact."""
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return _mesh(
        spec,
        name,
        [[radius * math.cos(t), radius * math.sin(t), -height / 2] for t in a] + [[0, 0, height / 2]],
    )


def prism_mesh(spec, name, radius, length, sides=6):
    """Regular prism along x with a flat side down (``sides`` = 6: a hexagonal pencil)."""
    a = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    return _mesh(
        spec,
        name,
        [[x, radius * math.cos(t), radius * math.sin(t)] for x in (-length / 2, length / 2) for t in a],
    )


def _mesh_part(tag, kind_fn, extent, pos, rgba, **opt):
    """A part whose mesh ``<name>_<tag>`` is built per object by ``kind_fn(spec, mesh_name)``;
    ``extent``: the mesh's half extents about ``pos`` in the geom frame."""

    def part(spec, name):
        mname = f"{name}_{tag}"
        return ("mesh", extent, pos, rgba, {"mesh": kind_fn(spec, mname), "extent": extent, **opt})

    return part


def _ring(tag, major, minor, pos, rgba):
    """A visual torus standing upright in the body's xz plane (handles, loops)."""
    return _mesh_part(
        tag,
        lambda s, n: torus_mesh(s, n, major, minor, 12, 6),
        (major + minor, major + minor, minor),
        pos,
        rgba,
        visual=True,
        quat=X90,
    )


def _segment(p0, p1, radius, rgba, **opt):
    """A capsule from ``p0`` to ``p1`` as a compound part."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    d = p1 - p0
    axis = np.cross([0, 0, 1], d)
    n = np.linalg.norm(axis)
    q = quat_axis_angle(axis / n if n > 1e-9 else [1, 0, 0], math.atan2(n, d[2]))
    return ("cap", (radius, np.linalg.norm(d) / 2, 0), tuple((p0 + p1) / 2), rgba, {"quat": q, **opt})


# ---- fruit and vegetables ---------------------------------------------------------------------
_simple(
    "apple",
    0.04,
    "red_round_fruit",
    [
        ("sph", (0.036,), (0, 0, 0.036), "main"),
        ("cyl", (0.003, 0.008, 0), (0, 0, 0.076), STEM),
        ("ell", (0.012, 0.005, 0.002), (0.01, 0, 0.073), LEAF, {"visual": True}),
    ],
    0.18,
    _pick([(0.8, 0.1, 0.1), (0.75, 0.15, 0.1), (0.55, 0.8, 0.2)]),
)
_simple(
    "orange",
    0.04,
    "ball",
    [
        ("sph", (0.037,), (0, 0, 0.037), (0.98, 0.55, 0.05, 1)),
        ("cyl", (0.006, 0.002, 0), (0, 0, 0.073), LEAF, {"visual": True}),
    ],
    0.2,
)
_simple(
    "lemon",
    0.035,
    "lemon",
    [
        ("ell", (0.04, 0.028, 0.028), (0, 0, 0.028), (0.98, 0.9, 0.2, 1)),
        ("sph", (0.006,), (0.039, 0, 0.028), (0.9, 0.85, 0.2, 1), {"visual": True}),
    ],
    0.1,
)
_simple(
    "pear",
    0.04,
    "pear",
    [
        ("sph", (0.035,), (0, 0, 0.035), "main"),
        ("sph", (0.024,), (0, 0, 0.075), "main"),
        ("cyl", (0.003, 0.008, 0), (0, 0, 0.105), STEM),
    ],
    0.18,
    _pick([(0.7, 0.8, 0.25)]),
    look=((0, 1), looks.pear),
)
_simple(
    "tomato",
    0.035,
    "red_round_fruit",
    [
        ("ell", (0.034, 0.034, 0.028), (0, 0, 0.028), (0.9, 0.15, 0.1, 1)),
        ("cyl", (0.012, 0.002, 0), (0, 0, 0.056), LEAF),
    ],
    0.12,
)
_simple(
    "banana",
    0.1,
    "banana",
    [
        ("cap", (0.017, 0.06, 0), (0, 0, 0.017), "main", {"quat": Y90}),
        (
            "cap",
            (0.015, 0.03, 0),
            (0.08, 0.02, 0.02),
            "main",
            {"quat": quat_axis_angle([-0.3, 1, 0], np.pi / 2 + 0.3)},
        ),
    ],
    0.15,
    _pick([YELLOW, (0.85, 0.85, 0.3)]),
)
_simple(
    "carrot",
    0.09,
    "carrot",
    [
        ("cap", (0.014, 0.06, 0), (0, 0, 0.014), (0.95, 0.45, 0.05, 1), {"quat": Y90}),
        ("cyl", (0.01, 0.015, 0), (-0.085, 0, 0.014), LEAF, {"quat": Y90}),
    ],
    0.08,
)
_simple(
    "eggplant",
    0.09,
    "eggplant",
    [
        ("ell", (0.075, 0.031, 0.027), (0, 0, 0.027), (0.35, 0.1, 0.4, 1)),
        ("cyl", (0.01, 0.012, 0), (0.085, 0, 0.027), LEAF, {"quat": Y90}),
    ],
    0.25,
)
_simple(
    "corn",
    0.1,
    "corn",
    [
        ("ell", (0.085, 0.025, 0.021), (0, 0, 0.021), (0.95, 0.8, 0.2, 1)),
        ("ell", (0.06, 0.02, 0.012), (0.02, 0.012, 0.03), (0.4, 0.65, 0.2, 1), {"visual": True}),
    ],
    0.2,
)
_simple(
    "bread_loaf",
    0.1,
    "bread",
    [
        ("ell", (0.09, 0.05, 0.04), (0, 0, 0.04), (0.78, 0.55, 0.25, 1)),
        *[
            ("ell", (0.008, 0.04, 0.004), (x, 0, 0.079), (0.9, 0.75, 0.5, 1), {"visual": True})
            for x in (-0.045, 0, 0.045)
        ],
    ],
    0.3,
    role="task",  # place_a2b_*'s reference object
)
_simple(
    "donut",
    0.05,
    "donut",
    [
        _mesh_part(
            "dough",
            lambda s, n: torus_mesh(s, n, 0.031, 0.014),
            (0.045, 0.045, 0.014),
            (0, 0, 0.014),
            (0.82, 0.6, 0.32, 1),
        ),
        _mesh_part(
            "icing",
            lambda s, n: torus_mesh(s, n, 0.031, 0.0145, z_scale=0.8),
            (0.0455, 0.0455, 0.0116),
            (0, 0, 0.0175),
            "main",
            visual=True,
        ),
    ],
    0.06,
    _pick([(0.95, 0.55, 0.7), (0.35, 0.2, 0.12), (0.97, 0.95, 0.9)]),
)

# ---- kitchen ----------------------------------------------------------------------------------
_simple(
    "teapot",
    0.08,
    "teapot",
    [
        ("ell", (0.06, 0.06, 0.05), (0, 0, 0.052), "main"),
        ("cyl", (0.04, 0.004, 0), (0, 0, 0.004), "main"),
        ("cap", (0.01, 0.03, 0), (0.075, 0, 0.06), "main", {"quat": quat_axis_angle([0, 1, 0], 0.8)}),
        ("cyl", (0.02, 0.008, 0), (0, 0, 0.105), "main"),
        ("sph", (0.007,), (0, 0, 0.118), "main"),
        _ring("handle", 0.024, 0.006, (-0.066, 0, 0.06), "main"),
    ],
    0.4,
    _pick([(0.95, 0.95, 0.93), (0.2, 0.45, 0.7), (0.75, 0.2, 0.15), (0.3, 0.55, 0.4)]),
    look=((0, 1, 3, 4), looks.teapot),
)
_simple(
    "kettle",
    0.08,
    "kettle",
    [
        ("cyl", (0.055, 0.058, 0), (0, 0, 0.066), "main"),
        ("cyl", (0.058, 0.006, 0), (0, 0, 0.006), DARK),
        ("box", (0.008, 0.01, 0.04), (-0.066, 0, 0.08), DARK),
        ("box", (0.012, 0.01, 0.005), (-0.058, 0, 0.117), DARK),
        ("cyl", (0.012, 0.006, 0), (0, 0, 0.128), DARK),
        ("cap", (0.008, 0.022, 0), (0.062, 0, 0.095), "main", {"quat": quat_axis_angle([0, 1, 0], 0.8)}),
    ],
    0.6,
    _pick([STEEL, (0.93, 0.93, 0.9), (0.8, 0.15, 0.12), (0.15, 0.15, 0.16)], 0.03),
    look=((0, 1, 4), looks.kettle),
)
_simple(
    "pepper_grinder",
    0.03,
    "grinder",
    [
        ("cyl", (0.024, 0.012, 0), (0, 0, 0.012), "main"),
        ("cyl", (0.018, 0.045, 0), (0, 0, 0.068), "main"),
        ("cyl", (0.024, 0.012, 0), (0, 0, 0.124), "main"),
        ("sph", (0.008,), (0, 0, 0.14), STEEL),
    ],
    0.25,
    _pick([(0.45, 0.28, 0.12), (0.25, 0.15, 0.08), (0.1, 0.1, 0.1)]),
    look=((0, 1, 2, 3), looks.pepper_grinder),
)
_simple(
    "rolling_pin",
    0.14,
    "rolling_pin",
    [
        ("cyl", (0.025, 0.09, 0), (0, 0, 0.025), (0.85, 0.7, 0.48, 1), {"quat": Y90}),
        ("cyl", (0.01, 0.03, 0), (0.12, 0, 0.025), WOOD, {"quat": Y90}),
        ("cyl", (0.01, 0.03, 0), (-0.12, 0, 0.025), WOOD, {"quat": Y90}),
    ],
    0.35,
)

# ---- office, home and toys --------------------------------------------------------------------
_simple(
    "book",
    0.11,
    "book",
    [
        ("box", (0.1, 0.07, 0.015), (0, 0, 0.015), "main"),
        ("box", (0.097, 0.068, 0.0135), (0.004, 0, 0.015), (0.95, 0.93, 0.88, 1), {"visual": True}),
    ],
    0.4,
    _pick(PLASTICS[:8] + [(0.35, 0.1, 0.1), (0.1, 0.15, 0.35)]),
    look=((0, 1), looks.book),
)
_simple(
    "remote_control",
    0.09,
    "remote",
    [
        ("box", (0.08, 0.022, 0.01), (0, 0, 0.01), (0.12, 0.12, 0.13, 1)),
        ("cyl", (0.006, 0.002, 0), (0.05, 0, 0.021), (0.85, 0.1, 0.1, 1), {"visual": True}),
        ("box", (0.03, 0.015, 0.0015), (-0.01, 0, 0.0205), (0.5, 0.5, 0.52, 1), {"visual": True}),
    ],
    0.1,
)
_simple(
    "toy_car",
    0.07,
    "toy_car",
    [
        ("box", (0.06, 0.03, 0.015), (0, 0, 0.025), "main"),
        ("box", (0.03, 0.027, 0.014), (-0.005, 0, 0.052), (0.7, 0.85, 0.95, 1)),
        *[
            ("cyl", (0.012, 0.006, 0), (x, y, 0.012), (0.05, 0.05, 0.05, 1), {"quat": X90})
            for x in (-0.035, 0.035)
            for y in (-0.03, 0.03)
        ],
    ],
    0.15,
    _pick(PLASTICS[:8]),
    # Held across its 6 cm body, low enough that the palm clears the cabin (place_a2b_*).
    functional=Functional(grasp=((0.0, 0.0, 0.035),), grasp_axis=(0.0, 1.0, 0.0)),
    role="task",
)
_simple(
    "rubber_duck",
    0.05,
    "duck",
    [
        ("ell", (0.045, 0.033, 0.028), (0, 0, 0.03), (0.98, 0.85, 0.1, 1)),
        ("cyl", (0.03, 0.003, 0), (0.005, 0, 0.003), (0.98, 0.85, 0.1, 1)),
        ("sph", (0.022,), (0.025, 0, 0.07), (0.98, 0.85, 0.1, 1)),
        ("ell", (0.012, 0.008, 0.004), (0.05, 0, 0.068), (0.95, 0.45, 0.05, 1), {"visual": True}),
    ],
    0.05,
)
_simple(
    "alarm_clock",
    0.05,
    "clock",
    [
        ("cyl", (0.045, 0.02, 0), (0, 0, 0.05), "main", {"quat": Y90}),
        ("cyl", (0.038, 0.001, 0), (-0.021, 0, 0.05), WHITE, {"quat": Y90, "visual": True}),
        ("box", (0.001, 0.0015, 0.014), (-0.0225, 0, 0.062), DARK, {"visual": True}),
        ("box", (0.001, 0.011, 0.0015), (-0.0225, -0.01, 0.05), DARK, {"visual": True}),
        ("sph", (0.013,), (0, 0.028, 0.088), STEEL, {"visual": True}),
        ("sph", (0.013,), (0, -0.028, 0.088), STEEL, {"visual": True}),
        ("box", (0.015, 0.03, 0.003), (0, 0, 0.003), DARK),
    ],
    0.2,
    _pick(PLASTICS[:8]),
)
_simple(
    "calculator",
    0.07,
    "calculator",
    [
        ("box", (0.055, 0.04, 0.008), (0, 0, 0.008), (0.2, 0.2, 0.22, 1)),
        ("box", (0.015, 0.032, 0.001), (0.035, 0, 0.0165), (0.6, 0.7, 0.6, 1), {"visual": True}),
        *[
            ("box", (0.006, 0.006, 0.0008), (x, y, 0.0165), (0.8, 0.8, 0.82, 1), {"visual": True})
            for x in (-0.035, -0.017, 0.001)
            for y in (-0.022, -0.007, 0.008, 0.023)
        ],
    ],
    0.12,
)
_simple(
    "tape_roll",
    0.045,
    "tape",
    [
        ("cyl", (0.042, 0.013, 0), (0, 0, 0.013), "main"),
        ("cyl", (0.028, 0.0005, 0), (0, 0, 0.0265), (0.55, 0.45, 0.35, 1), {"visual": True}),
    ],
    0.08,
    _pick([(0.85, 0.85, 0.8), (0.2, 0.45, 0.85), (0.1, 0.1, 0.1), (0.85, 0.15, 0.1), (0.95, 0.85, 0.1)]),
    look=((0, 1), looks.tape_roll),
)
_simple(
    "sponge",
    0.06,
    "sponge",
    [
        ("box", (0.05, 0.032, 0.012), (0, 0, 0.012), (0.95, 0.85, 0.2, 1)),
        ("box", (0.05, 0.032, 0.005), (0, 0, 0.029), (0.1, 0.55, 0.2, 1)),
    ],
    0.03,
    look=((0, 1), looks.sponge),
)
_simple(
    "candle",
    0.05,
    "candle",
    [
        ("cyl", (0.024, 0.04, 0), (0, 0, 0.048), "main"),
        ("cyl", (0.045, 0.004, 0), (0, 0, 0.004), (0.8, 0.65, 0.25, 1)),
        ("cyl", (0.0015, 0.004, 0), (0, 0, 0.092), DARK, {"visual": True}),
        ("ell", (0.006, 0.006, 0.012), (0, 0, 0.106), (1.0, 0.75, 0.15, 1), {"visual": True}),
    ],
    0.2,
    _pick([(0.97, 0.95, 0.88), (0.85, 0.15, 0.15), (0.95, 0.6, 0.75), (0.6, 0.3, 0.7)], 0.03),
    look=((0, 1), looks.candle),
)
_simple(
    "flower_pot",
    0.05,
    "pot",
    [
        ("cyl", (0.045, 0.04, 0), (0, 0, 0.04), (0.75, 0.38, 0.2, 1)),
        ("sph", (0.035,), (0, 0, 0.1), LEAF),
        ("sph", (0.02,), (0.02, 0.01, 0.13), "main", {"visual": True}),
    ],
    0.5,
    _pick([(0.9, 0.3, 0.5), (0.95, 0.85, 0.15), (0.85, 0.15, 0.15), (0.6, 0.3, 0.8)]),
    look=((0,), looks.flower_pot),
)
_simple(
    "cactus",
    0.04,
    "cactus",
    [
        ("cyl", (0.035, 0.025, 0), (0, 0, 0.025), (0.85, 0.8, 0.7, 1)),
        ("cap", (0.018, 0.04, 0), (0, 0, 0.09), (0.2, 0.55, 0.25, 1)),
        (
            "cap",
            (0.01, 0.015, 0),
            (0.028, 0, 0.1),
            (0.2, 0.55, 0.25, 1),
            {"quat": quat_axis_angle([0, 1, 0], 0.6)},
        ),
    ],
    0.35,
    look=((0,), looks.cactus_pot),
)
_simple(
    "glasses_case",
    0.08,
    "glasses",
    [
        ("box", (0.05, 0.028, 0.02), (0, 0, 0.02), "main"),
        ("cyl", (0.028, 0.02, 0), (0.05, 0, 0.02), "main"),
        ("cyl", (0.028, 0.02, 0), (-0.05, 0, 0.02), "main"),
        ("box", (0.05, 0.0285, 0.0015), (0, 0, 0.026), STEEL, {"visual": True}),
        ("box", (0.008, 0.003, 0.004), (0, -0.028, 0.028), STEEL, {"visual": True}),
    ],
    0.08,
    _pick([(0.1, 0.1, 0.12), (0.15, 0.2, 0.45), (0.55, 0.1, 0.15), (0.2, 0.4, 0.3)], 0.03),
)
_simple(
    "toothpaste_tube",
    0.1,
    "toothpaste",
    [
        ("ell", (0.08, 0.024, 0.014), (0, 0, 0.014), "main"),
        ("cyl", (0.01, 0.01, 0), (0.09, 0, 0.014), WHITE, {"quat": Y90}),
        ("box", (0.005, 0.026, 0.002), (-0.079, 0, 0.014), WHITE, {"visual": True}),
    ],
    0.1,
    _pick([(0.85, 0.1, 0.1), (0.1, 0.35, 0.85), (0.1, 0.6, 0.3)]),
)
_simple(
    "milk_carton",
    0.045,
    "carton",
    [
        ("box", (0.035, 0.035, 0.07), (0, 0, 0.07), WHITE),
        ("box", (0.035, 0.025, 0.012), (0, 0, 0.152), WHITE, {"quat": quat_axis_angle([1, 0, 0], 0.9)}),
        ("box", (0.0355, 0.0355, 0.02), (0, 0, 0.09), (0.2, 0.45, 0.85, 1), {"visual": True}),
    ],
    0.3,
)
_simple(
    "dice",
    0.03,
    "dice",
    [
        ("box", (0.02, 0.02, 0.02), (0, 0, 0.02), WHITE),
        *[
            ("sph", (0.004,), p, DARK, {"visual": True})
            for p in ((0, 0, 0.0405), (0.0205, 0.008, 0.028), (0.0205, -0.008, 0.012), (0, -0.0205, 0.02))
        ],
    ],
    0.02,
)
_simple(
    "chess_pawn",
    0.03,
    "chess",
    [
        ("cyl", (0.022, 0.006, 0), (0, 0, 0.006), "main"),
        ("cyl", (0.011, 0.025, 0), (0, 0, 0.035), "main"),
        ("cyl", (0.016, 0.003, 0), (0, 0, 0.057), "main"),
        ("sph", (0.016,), (0, 0, 0.07), "main"),
    ],
    0.05,
    _pick([(0.95, 0.95, 0.92), (0.08, 0.08, 0.08)], 0.02),
    look=((0, 1, 2, 3), looks.chess_pawn),
)
_simple(
    "lightbulb",
    0.035,
    "bulb",
    [
        ("sph", (0.03,), (0, 0, 0.05), (0.98, 0.98, 0.85, 0.9)),
        ("cyl", (0.013, 0.013, 0), (0, 0, 0.013), STEEL),
    ],
    0.05,
    look=((0, 1), looks.lightbulb),
)
_simple("tennis_ball", 0.035, "ball", [("sph", (0.033,), (0, 0, 0.033), (0.8, 0.95, 0.2, 1))], 0.06)
_simple(
    "tissue_box",
    0.08,
    "tissue",
    [
        ("box", (0.065, 0.05, 0.045), (0, 0, 0.045), "main"),
        ("ell", (0.025, 0.03, 0.015), (0, 0, 0.092), WHITE, {"visual": True}),
    ],
    0.15,
    _pick([(0.4, 0.65, 0.9), (0.95, 0.6, 0.75), (0.5, 0.8, 0.5), (0.6, 0.45, 0.8)]),
    look=((0,), looks.tissue_box),
)
_simple(
    "trophy",
    0.04,
    "trophy",
    [
        ("box", (0.03, 0.03, 0.012), (0, 0, 0.012), (0.2, 0.15, 0.1, 1)),
        ("cyl", (0.006, 0.025, 0), (0, 0, 0.049), (0.9, 0.75, 0.2, 1)),
        ("cyl", (0.03, 0.025, 0), (0, 0, 0.099), (0.9, 0.75, 0.2, 1)),
        _ring("handle1", 0.013, 0.003, (0.035, 0, 0.1), (0.9, 0.75, 0.2, 1)),
        _ring("handle2", 0.013, 0.003, (-0.035, 0, 0.1), (0.9, 0.75, 0.2, 1)),
    ],
    0.3,
    look=((1, 2), looks.trophy_cup),
)
_simple(
    "toy_robot",
    0.04,
    "robot_toy",
    [
        ("box", (0.025, 0.02, 0.03), (0, 0, 0.05), "main"),
        ("box", (0.018, 0.016, 0.016), (0, 0, 0.096), STEEL),
        ("box", (0.008, 0.008, 0.01), (0, 0.01, 0.01), (0.3, 0.3, 0.3, 1)),
        ("box", (0.008, 0.008, 0.01), (0, -0.01, 0.01), (0.3, 0.3, 0.3, 1)),
        *[("sph", (0.004,), (0.0185, y, 0.1), (0.1, 0.8, 0.9, 1), {"visual": True}) for y in (-0.007, 0.007)],
    ],
    0.1,
    _pick(PLASTICS[:8]),
)
_simple(
    "headphones",
    0.08,
    "headphones",
    [
        ("cyl", (0.03, 0.012, 0), (0.065, 0, 0.012), "main"),
        ("cyl", (0.03, 0.012, 0), (-0.065, 0, 0.012), "main"),
        ("cyl", (0.022, 0.001, 0), (0.065, 0, 0.025), DARK, {"visual": True}),
        ("cyl", (0.022, 0.001, 0), (-0.065, 0, 0.025), DARK, {"visual": True}),
        *[
            _segment(
                (0.065 * math.cos(a0), 0.03 + 0.065 * math.sin(a0), 0.008),
                (0.065 * math.cos(a1), 0.03 + 0.065 * math.sin(a1), 0.008),
                0.007,
                DARK,
            )
            for a0, a1 in zip(np.linspace(0, np.pi, 5)[:-1], np.linspace(0, np.pi, 5)[1:], strict=True)
        ],
    ],
    0.2,
    _pick([(0.12, 0.12, 0.13), (0.93, 0.93, 0.93), (0.85, 0.12, 0.1), (0.1, 0.35, 0.85)]),
)
_simple(
    "traffic_cone",
    0.05,
    "cone",
    [
        ("box", (0.045, 0.045, 0.004), (0, 0, 0.004), "main"),
        _mesh_part(
            "cone", lambda s, n: cone(s, n, 0.035, 0.11, 16), (0.035, 0.035, 0.055), (0, 0, 0.063), "main"
        ),
        ("cyl", (0.023, 0.008, 0), (0, 0, 0.05), WHITE, {"visual": True}),
    ],
    0.1,
    _pick([(0.98, 0.45, 0.05)], 0.03),
)
_simple(
    "scissors",
    0.08,
    "scissors",
    [
        (
            "box",
            (0.045, 0.004, 0.0015),
            (0.035, 0.004, 0.0015),
            STEEL,
            {"quat": quat_axis_angle([0, 0, 1], 0.06)},
        ),
        (
            "box",
            (0.045, 0.004, 0.0015),
            (0.035, -0.004, 0.0015),
            STEEL,
            {"quat": quat_axis_angle([0, 0, 1], -0.06)},
        ),
        _mesh_part(
            "ring1",
            lambda s, n: torus_mesh(s, n, 0.014, 0.004, 12, 6),
            (0.018, 0.018, 0.004),
            (-0.026, 0.02, 0.004),
            "main",
        ),
        _mesh_part(
            "ring2",
            lambda s, n: torus_mesh(s, n, 0.014, 0.004, 12, 6),
            (0.018, 0.018, 0.004),
            (-0.026, -0.02, 0.004),
            "main",
        ),
        ("cyl", (0.004, 0.003, 0), (-0.004, 0, 0.003), DARK, {"visual": True}),
    ],
    0.06,
    _pick(PLASTICS[:8]),
)
_simple(
    "pencil",
    0.09,
    "pencil",
    [
        _mesh_part(
            "shaft",
            lambda s, n: prism_mesh(s, n, 0.0055, 0.15),
            (0.075, 0.0055, 0.0048),
            (0, 0, 0.0048),
            "main",
        ),
        _mesh_part(
            "tip",
            lambda s, n: cone(s, n, 0.0048, 0.022, 8),
            (0.0048, 0.0048, 0.011),
            (0.086, 0, 0.0048),
            (0.9, 0.75, 0.55, 1),
            visual=True,
            quat=Y90,
        ),
        ("cyl", (0.0047, 0.005, 0), (-0.08, 0, 0.0048), STEEL, {"quat": Y90, "visual": True}),
        ("cyl", (0.0047, 0.006, 0), (-0.091, 0, 0.0048), (0.95, 0.55, 0.6, 1), {"quat": Y90, "visual": True}),
    ],
    0.02,
    _pick([(0.98, 0.8, 0.1), (0.1, 0.35, 0.85), (0.85, 0.12, 0.1), (0.1, 0.6, 0.25)], 0.02),
)
_simple(
    "hourglass",
    0.04,
    "hourglass",
    [
        ("cyl", (0.035, 0.005, 0), (0, 0, 0.005), "main"),
        ("cyl", (0.035, 0.005, 0), (0, 0, 0.115), "main"),
        *[
            ("cyl", (0.003, 0.05, 0), (0.03 * math.cos(a), 0.03 * math.sin(a), 0.06), "main")
            for a in (0.5, 2.6, 4.7)
        ],
        _mesh_part(
            "glass1",
            lambda s, n: cone(s, n, 0.024, 0.05),
            (0.024, 0.024, 0.025),
            (0, 0, 0.035),
            (0.85, 0.9, 0.95, 0.45),
            visual=True,
        ),
        _mesh_part(
            "glass2",
            lambda s, n: cone(s, n, 0.024, 0.05),
            (0.024, 0.024, 0.025),
            (0, 0, 0.085),
            (0.85, 0.9, 0.95, 0.45),
            visual=True,
            quat=(0, 1, 0, 0),
        ),
        _mesh_part(
            "sand",
            lambda s, n: cone(s, n, 0.016, 0.02),
            (0.016, 0.016, 0.01),
            (0, 0, 0.02),
            (0.95, 0.8, 0.45, 1),
            visual=True,
        ),
    ],
    0.3,
    _pick([(0.45, 0.28, 0.12), (0.2, 0.12, 0.06), (0.75, 0.6, 0.3)]),
)
