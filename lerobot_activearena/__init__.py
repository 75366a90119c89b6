"""ActiveArena for LeRobot: active-perception manipulation benchmark on MuJoCo."""

from .sim.gl_backend import select_gl_backend

select_gl_backend()  # MuJoCo reads MUJOCO_GL once, at its first import

__version__ = "0.1.0"
