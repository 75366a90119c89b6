"""Same seed and actions give bit-identical images and states in fresh processes; the package pins
numpy's BLAS kernels so that holds across x86-64 CPUs too."""

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
first = sys.argv[1]
if first == "numpy":
    import numpy
import lerobot_activearena, numpy
from lerobot_activearena.sim.blas_kernels import kernels_mismatch, openblas_kernels
print(openblas_kernels(), os.environ.get("OPENBLAS_CORETYPE"), kernels_mismatch() is not None)
"""


def _kernels(first: str, **env) -> list[str]:
    environ = {k: v for k, v in os.environ.items() if k != "OPENBLAS_CORETYPE"} | env
    out = subprocess.run(
        [sys.executable, "-c", KERNELS, first], capture_output=True, text=True, timeout=120, env=environ
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.split()


def test_the_package_pins_numpys_blas_kernels_before_numpy_loads():
    """The shipped manifests were made with OpenBLAS's Haswell kernels; other kernels (an AVX-512
    CPU's) change the expert's IK in the last bits and its episodes with them."""
    if not cpu_runs_pinned_kernels():  # not x86-64 with AVX2/FMA: OpenBLAS keeps its own choice
        assert _kernels("package")[1] == "None"
        return
    assert _kernels("package") == [PINNED, PINNED, "False"]
    assert _kernels("package", OPENBLAS_CORETYPE="Sandybridge") == ["Sandybridge", "Sandybridge", "False"]
    # numpy loaded first keeps the CPU's own kernels; the simulator warns when they are not the pinned ones
    have, want, mismatch = _kernels("numpy")
    assert want == PINNED and mismatch == str(have != PINNED)
