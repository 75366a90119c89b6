"""Pin numpy's OpenBLAS to one kernel family, so episodes are bit-identical across x86-64 CPUs.

OpenBLAS picks its kernels by CPU when numpy loads it (Haswell, SkylakeX, Zen, ...), and their
results differ in the last bits. The expert's IK (mink: small matrix products in numpy) carries
that into its joint targets and contact-rich motion amplifies it: on an AVX-512 CPU, place_shoe's
100 ID manifest episodes averaged 133.1 expert frames against the shipped manifest's 133.0, and
133.0 again with Haswell's kernels: the shipped manifests were made with Haswell's.

OpenBLAS reads ``OPENBLAS_CORETYPE`` once, at load, so the package sets it on import, before numpy
loads, where the CPU runs Haswell's kernels (AVX2 and FMA) and the user has not chosen one.
"""

from __future__ import annotations

import ctypes
import os
import platform
import sys
from pathlib import Path

KERNELS = "Haswell"  # the family the shipped artefacts were made with
_NEEDS = ("avx2", "fma")


def _cpu_flags() -> set[str]:
    try:
        text = Path("/proc/cpuinfo").read_text()
    except OSError:
        return set()
    line = next((ln for ln in text.splitlines() if ln.startswith("flags")), "")
    return set(line.partition(":")[2].split())


def cpu_runs_pinned_kernels() -> bool:
    """An x86-64 CPU with AVX2 and FMA (what ``KERNELS`` needs)."""
    return platform.machine().lower() in ("x86_64", "amd64") and set(_NEEDS) <= _cpu_flags()


def pin_blas_kernels() -> str | None:
    """Set ``OPENBLAS_CORETYPE`` to ``KERNELS`` unless it is set, the machine is not x86-64, or its
    CPU lacks AVX2/FMA; return the value in force (None: OpenBLAS chooses)."""
    if "OPENBLAS_CORETYPE" in os.environ:
        return os.environ["OPENBLAS_CORETYPE"]
    if not cpu_runs_pinned_kernels():
        return None
    os.environ["OPENBLAS_CORETYPE"] = KERNELS
    return KERNELS


def openblas_kernels() -> str | None:
    """The kernel family numpy's OpenBLAS runs in this process (None: numpy is not loaded, or uses
    another BLAS)."""
    numpy = sys.modules.get("numpy")
    if numpy is None:
        return None
    for path in sorted((Path(numpy.__file__).parent.parent / "numpy.libs").glob("libscipy_openblas*")):
        lib = ctypes.CDLL(str(path))  # already loaded by numpy: the same handle
        for name in (
            "scipy_openblas_get_corename64_",
            "scipy_openblas_get_corename",
            "openblas_get_corename",
        ):
            fn = getattr(lib, name, None)
            if fn is not None:
                fn.restype = ctypes.c_char_p
                return fn().decode().strip()
    return None


def kernels_mismatch() -> str | None:
    """Why this process's episodes may differ in the last bits from the shipped artefacts (numpy's
    OpenBLAS loaded before the package pinned its kernels), or None."""
    want, have = os.environ.get("OPENBLAS_CORETYPE"), openblas_kernels()
    if not want or not have or have.lower() == want.lower():
        return None
    return (
        f"numpy's OpenBLAS runs {have} kernels, not {want}: numpy was loaded before lerobot_activearena, "
        f"so episodes are valid but not bit-identical to the ones behind the shipped seed manifests "
        f"(made with {KERNELS}'s). Import lerobot_activearena before numpy, or start Python with "
        f"OPENBLAS_CORETYPE={want}."
    )
