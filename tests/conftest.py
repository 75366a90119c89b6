import os

os.environ.setdefault("MUJOCO_GL", "egl")

import lerobot_activearena  # noqa: E402,F401  (selects the GL backend before mujoco loads)
