"""Same seed and actions give bit-identical images and states in fresh processes; the episode
producers switch numpy's BLAS kernels to one family so that holds across x86-64 CPUs too, whatever
was imported first."""

import os
import subprocess
import sys

from lerobot_activearena.sim.blas_kernels import KERNELS as PINNED, cpu_runs_pinned_kernels

SCRIPT = r"""
import hashlib, numpy as np, lerobot_activearena
from lerobot_activearena.sim.scene import reference_scene
from lerobot_activearena.sim.simulator import ActiveArenaSim
model, info = reference_scene(SEED, n_objects=12).compile()
sim = ActiveArenaSim(model, info)
h = hashlib.sha256()
a = sim.home_action()
for i in range(20):
    a[16] = 0.8 * np.sin(i / 4); a[2] = -1.0 + 0.3 * np.sin(i / 3)
    sim.step(a)
    h.update(sim.state().tobytes()); h.update(sim.data.qpos.tobytes())
    if i % 5 == 0:
        h.update(sim.render_head().tobytes()); h.update(sim.visibility().visible_fraction.tobytes())
print(h.hexdigest())
"""


def _run(seed):
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT.replace("SEED", str(seed))], capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.strip().splitlines()[-1]


def test_same_seed_same_bits_across_processes():
    assert _run(3) == _run(3)


def test_different_seed_different_scene():
    assert _run(3) != _run(4)


KERNELS = r"""
import os, sys
if sys.argv[1] == "numpy":
    import numpy
if sys.argv[1] == "numpy-on-other-kernels":  # as numpy on a CPU where OpenBLAS picks another family
    os.environ["OPENBLAS_CORETYPE"] = "Sandybridge"
    import numpy
    del os.environ["OPENBLAS_CORETYPE"]
import lerobot_activearena, numpy
from lerobot_activearena.sim.blas_kernels import openblas_kernels
before = openblas_kernels()
from lerobot_activearena.tasks import get_task
from lerobot_activearena.tasks.sampling import sample_scene
sample_scene(get_task("click_bell_rotate_view"), 0)
print(before, openblas_kernels(), os.environ.get("OPENBLAS_CORETYPE"))
"""


def _kernels(first: str, **env) -> list[str]:
    environ = {k: v for k, v in os.environ.items() if k != "OPENBLAS_CORETYPE"} | env
    out = subprocess.run(
        [sys.executable, "-c", KERNELS, first], capture_output=True, text=True, timeout=300, env=environ
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert "WARNING" not in out.stderr, out.stderr[-2000:]
    return out.stdout.split()


def test_scene_sampling_runs_the_pinned_kernels_whatever_was_imported_first():
    """The shipped manifests were made with OpenBLAS's Haswell kernels; other kernels (an AVX-512
    CPU's) change the expert's IK in the last bits and its episodes with them."""
    if not cpu_runs_pinned_kernels():  # not x86-64 with AVX2/FMA: OpenBLAS keeps its own choice
        before, after, _ = _kernels("package")
        assert after == before
        return
    # numpy first, started on other kernels (as an AVX-512 CPU would choose): switched when a scene is made
    assert _kernels("numpy-on-other-kernels") == ["Sandybridge", PINNED, PINNED]
    assert _kernels("numpy")[1:] == [PINNED, PINNED]
    assert _kernels("package")[1:] == [PINNED, PINNED]
    # the user's own choice, made before numpy loaded, is kept
    assert _kernels("numpy", OPENBLAS_CORETYPE="Sandybridge") == ["Sandybridge"] * 3


SWITCH = r"""
import sys, hashlib, numpy as np
from lerobot_activearena.sim.blas_kernels import openblas_kernels, switch_kernels
if len(sys.argv) > 1:
    switch_kernels(sys.argv[1])
rng = np.random.default_rng(0)
a, b = rng.normal(size=(40, 37)), rng.normal(size=(37, 29))
print(openblas_kernels(), hashlib.sha256((a @ b).tobytes() + (a.T @ a).tobytes() + (a @ b[:, 0]).tobytes()).hexdigest())
"""


def _products(start: str, *switch: str) -> list[str]:
    environ = os.environ | {"OPENBLAS_CORETYPE": start}
    out = subprocess.run(
        [sys.executable, "-c", SWITCH, *switch], capture_output=True, text=True, timeout=120, env=environ
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.split()


def test_switching_kernels_gives_the_bits_of_a_process_started_on_them():
    if not cpu_runs_pinned_kernels():
        return
    native = _products(PINNED)
    other = _products("Sandybridge")  # no FMA: its products differ from Haswell's in the last bits
    assert native[0] == PINNED and other[0] == "Sandybridge" and other[1] != native[1]
    assert _products("Sandybridge", PINNED) == native
