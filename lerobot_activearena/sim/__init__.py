"""MuJoCo simulator core: embodiment, workspaces, objects, scene assembly, control, sensing."""

from .gl_backend import select_gl_backend

select_gl_backend()  # must run before mujoco is imported anywhere
