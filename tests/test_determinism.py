"""Same seed and actions give bit-identical images and states in fresh processes."""

import subprocess
import sys

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
