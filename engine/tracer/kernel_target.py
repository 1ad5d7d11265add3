"""The CPU the kernels are compiled for: this machine's own (the default) or a portable x86-64 level.

Kernels compiled for this machine's CPU use every instruction it has, but only run here. Kernels
compiled for a portable level (``x86-64-v3``: AVX2 and FMA, the x86-64 psABI's level 3, every Intel
CPU since Haswell and AMD since Zen) run on any CPU that has that level's features, so they can be
compiled once and shipped inside the extension: the first render on a new machine then loads them
instead of compiling for minutes (``engine.warmup.shipped_kernels``). On a Xeon with AVX-512 they ran
about 5 % slower than its own kernels, so the add-on still compiles this machine's kernels in the
background and uses them from the next session on.

The choice is made once per process, before ``jit`` imports numba (``use``); numba's
``config.CPU_NAME`` and ``config.CPU_FEATURES`` then say it, and numba keys every cached kernel by it
(``codegen.magic_tuple()``). Imports no numba; ``host_supports`` imports llvmlite only.
"""

from __future__ import annotations

import sys

HOST = None  # this machine's CPU, all of its features

#: Portable CPU levels kernels may be compiled for, with the LLVM features each requires of a CPU
#: (x86-64 psABI micro-architecture levels: v2's and v3's features).
PORTABLE_FEATURES = {
    "x86-64-v3": ("cx16", "sahf", "popcnt", "sse3", "sse4.1", "sse4.2", "ssse3",
                  "avx", "avx2", "bmi", "bmi2", "f16c", "fma", "lzcnt", "movbe", "xsave"),
}

_chosen: list[str | None] = [HOST]
_applied: list[str | None] = []  # the target jit applied to numba, once it has


def use(target: str | None) -> None:
    """Compile and load kernels for ``target`` (``HOST`` or a name in ``PORTABLE_FEATURES``) in this
    process. Only before ``jit`` is imported: numba's code generator is made once per process."""
    if target is not HOST and target not in PORTABLE_FEATURES:
        raise ValueError(f"unknown kernel CPU target {target!r}: use None or one of {sorted(PORTABLE_FEATURES)}")
    if _applied and _applied[0] != target:
        raise RuntimeError(f"kernels are already compiled for {_applied[0] or 'this CPU'} in this process")
    _chosen[0] = target


def current() -> str | None:
    """The target chosen for this process (``HOST`` unless ``use`` said otherwise)."""
    return _chosen[0]


def applied(target: str | None) -> None:
    """Called by ``jit`` once numba is configured for ``target``: later ``use`` calls must agree."""
    _applied[:] = [target]
    _chosen[0] = target


def host_supports(target: str) -> bool:
    """Whether this machine's CPU has every feature ``target`` requires (asked of LLVM, as numba does)."""
    try:
        from llvmlite import binding

        features = binding.get_host_cpu_features()
    except Exception:  # noqa: BLE001 - no llvmlite, or an LLVM that cannot tell: compile for the host
        return False
    return all(features.get(name, False) for name in PORTABLE_FEATURES[target])


def machine() -> str:
    """This platform and Python as shipped kernels are tagged: kernels of another cannot load here."""
    import platform

    return f"{sys.platform}-{platform.machine().lower()}-py{sys.version_info[0]}{sys.version_info[1]}"
