"""ActiveArena for LeRobot: active-perception manipulation benchmark on MuJoCo.

Importing the package selects MuJoCo's GL backend (it reads ``MUJOCO_GL`` once, at its first
import; an explicit ``MUJOCO_GL`` wins) and registers the gymnasium IDs ``ActiveArena/<task>-v0``
from a static table (``envs/gym_ids.py``): it loads neither the tasks, MuJoCo, mink, torch nor
LeRobot, and leaves numpy's BLAS alone (episode producers pin its kernels: ``sim/blas_kernels.py``). The LeRobot types (the
``activearena`` env and the project's policies) are registered by the discovery shim
``lerobot_env_activearena``, which LeRobot's CLIs import (``register_third_party_plugins``).
"""

from .sim.gl_backend import select_gl_backend

select_gl_backend()
__version__ = "0.1.0"

from .envs.gym_ids import register_gym_envs  # noqa: E402  (after the GL backend is chosen)

register_gym_envs()
