import os
import subprocess
import sys

CODE = (
    "import lerobot_activearena, os, mujoco; from lerobot_activearena.sim.scene import SceneBuilder; "
    "from lerobot_activearena.sim.simulator import ActiveArenaSim; m, i = SceneBuilder().compile(); "
    "img = ActiveArenaSim(m, i).render_head(); print(os.environ['MUJOCO_GL'], img.mean() > 5)"
)


def _run(env):
    return subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, env=env, timeout=300)


def test_backend_chosen_automatically_when_unset():
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM")}
    out = _run(env)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["egl", "True"]


def test_osmesa_fallback_renders():
    env = {**os.environ, "MUJOCO_GL": "osmesa", "PYOPENGL_PLATFORM": "osmesa"}
    out = _run(env)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["osmesa", "True"]
