"""Pick a headless OpenGL backend for MuJoCo before `mujoco` is imported.

MuJoCo reads ``MUJOCO_GL`` once, at import. We honour a value the user set; otherwise we use
EGL (Mesa llvmpipe on a CPU machine, the GPU where there is one) and fall back to OSMesa.
"""

from __future__ import annotations

import ctypes.util
import os

_CANDIDATES = (("egl", "EGL"), ("osmesa", "OSMesa"))


def select_gl_backend() -> str | None:
    """Set ``MUJOCO_GL`` (and PyOpenGL's platform) if unset; return the backend in force."""
    chosen = os.environ.get("MUJOCO_GL")
    if not chosen:
        for backend, lib in _CANDIDATES:
            if ctypes.util.find_library(lib):
                chosen = backend
                break
        if chosen:
            os.environ["MUJOCO_GL"] = chosen
    if chosen in ("egl", "osmesa"):
        os.environ.setdefault("PYOPENGL_PLATFORM", chosen)
    return chosen


def rendering_error(exc: BaseException) -> RuntimeError:
    """A clear error for a failed GL context, naming the fix."""
    backend = os.environ.get("MUJOCO_GL", "<unset>")
    return RuntimeError(
        f"MuJoCo could not create an offscreen OpenGL context with MUJOCO_GL={backend} ({exc}). "
        "Install Mesa's EGL or OSMesa (Debian: apt-get install libegl1 libgl1-mesa-dri libosmesa6) "
        "and set MUJOCO_GL=egl or MUJOCO_GL=osmesa before starting Python."
    )
