"""Run numpy's OpenBLAS on one kernel family, so episodes are bit-identical across x86-64 CPUs.

OpenBLAS picks its kernels by CPU when numpy loads it (Haswell, SkylakeX, Zen, ...), and their
results differ in the last bits. The expert's IK (mink: small matrix products in numpy) carries
that into its joint targets and contact-rich motion amplifies it: on an AVX-512 CPU, place_shoe's
100 ID manifest episodes averaged 133.1 expert frames against the shipped manifest's 133.0, and
133.0 again with Haswell's kernels: the shipped manifests were made with Haswell's.

Where episodes are produced (``sample_scene``, ``ActiveArenaSim``) ``use_pinned_kernels`` switches
the loaded OpenBLAS to Haswell's kernels through its own dynamic-arch entry points (the same
selection OpenBLAS makes at load from ``OPENBLAS_CORETYPE``), so it holds whatever was imported
first; importing the package changes nothing.
"""

from __future__ import annotations

import ctypes
import os
import platform
import sys
import threading
from pathlib import Path

KERNELS = "Haswell"  # the family the shipped artefacts were made with
_NEEDS = ("avx2", "fma")
_LOCK = threading.Lock()
_DECIDED: list[str | None] = []  # the family in force, once decided (the producers call this often)


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


def _openblas() -> ctypes.CDLL | None:
    """numpy's OpenBLAS (the handle numpy loaded), or None: numpy is not loaded or uses another BLAS."""
    numpy = sys.modules.get("numpy")
    if numpy is None:
        return None
    for path in sorted((Path(numpy.__file__).parent.parent / "numpy.libs").glob("libscipy_openblas*")):
        return ctypes.CDLL(str(path))
    return None


def openblas_kernels() -> str | None:
    """The kernel family numpy's OpenBLAS runs in this process (None: numpy is not loaded, or uses
    another BLAS)."""
    lib = _openblas()
    if lib is None:
        return None
    for name in ("scipy_openblas_get_corename64_", "scipy_openblas_get_corename", "openblas_get_corename"):
        fn = getattr(lib, name, None)
        if fn is not None:
            fn.restype = ctypes.c_char_p
            return fn().decode().strip()
    return None


def switch_kernels(kernels: str) -> str:
    """Make numpy's OpenBLAS run ``kernels`` from now on (OpenBLAS's own selection: forget the chosen
    family, choose again from ``OPENBLAS_CORETYPE``); processes started later inherit the choice.
    Call it while no other thread is inside BLAS. Returns the family in force."""
    import numpy  # noqa: F401  (loads OpenBLAS if nothing has yet)

    lib = _openblas()
    quit_, init = (getattr(lib, n, None) for n in ("gotoblas_dynamic_quit", "gotoblas_dynamic_init"))
    if quit_ is None or init is None:
        raise RuntimeError(
            "numpy's BLAS is not a dynamic-arch OpenBLAS (the numpy wheels' own), so its kernels cannot be "
            f"switched to {kernels}; start Python with OPENBLAS_CORETYPE={kernels} instead."
        )
    os.environ["OPENBLAS_CORETYPE"] = kernels
    with _LOCK:
        quit_()
        init()
    have = openblas_kernels()
    if (have or "").lower() != kernels.lower():
        raise RuntimeError(
            f"OpenBLAS runs {have} kernels after switching to {kernels}: not a family it knows"
        )
    return have


def use_pinned_kernels() -> str | None:
    """Run ``KERNELS`` on x86-64 CPUs with AVX2 and FMA unless the user chose a family
    (``OPENBLAS_CORETYPE``); return the family in force (None: numpy's BLAS is not OpenBLAS). Cheap
    after the first call: the episode producers call it every time."""
    if not _DECIDED:
        _DECIDED.append(_decide())
    return _DECIDED[0]


def _decide() -> str | None:
    have = openblas_kernels() if "numpy" in sys.modules else None
    chosen = os.environ.get("OPENBLAS_CORETYPE")
    if chosen is not None and chosen.lower() != KERNELS.lower():
        return have  # the user's choice, made before numpy loaded
    if not cpu_runs_pinned_kernels():
        return have
    if have is None:
        import numpy  # noqa: F401

        have = openblas_kernels()
        if have is None:
            return None
    if have.lower() != KERNELS.lower():
        have = switch_kernels(KERNELS)
    os.environ["OPENBLAS_CORETYPE"] = KERNELS  # worker processes load the same family
    return have
