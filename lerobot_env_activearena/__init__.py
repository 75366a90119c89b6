"""Discovery shim: LeRobot imports installed ``lerobot_env_*`` distributions by name; this imports
``lerobot_activearena``, which registers the ``activearena`` env and the project's policy types."""

import lerobot_activearena  # noqa: F401
