"""ActiveArena for LeRobot: active-perception manipulation benchmark on MuJoCo.

Importing the package registers the ``activearena`` env type with LeRobot.
"""

from .sim.gl_backend import select_gl_backend

select_gl_backend()  # MuJoCo reads MUJOCO_GL once, at its first import

from .envs import configs as _env_configs  # noqa: E402,F401  (registers --env.type=activearena)
from .policies import (
    activearena_expert as _expert_policy,  # noqa: E402,F401  (--policy.type=activearena_expert)
    activearena_oft as _oft_policy,  # noqa: E402,F401  (--policy.type=activearena_oft)
)

__version__ = "0.1.0"
