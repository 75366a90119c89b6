"""MuJoCo simulator core: embodiment, workspaces, objects, scene assembly, control, sensing."""

from .blas_kernels import pin_blas_kernels

pin_blas_kernels()  # before numpy loads OpenBLAS: the same kernels on every x86-64 CPU

from .gl_backend import select_gl_backend  # noqa: E402

select_gl_backend()  # must run before mujoco is imported anywhere
