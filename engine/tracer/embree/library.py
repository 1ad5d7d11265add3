"""The Embree 4 shared library shipped by the embreex wheel: found, loaded once, its C signatures declared.

Kernels call Embree by symbol name (``numba.types.ExternalFunction``), resolved by LLVM's in-process
linker: ``load()`` registers the addresses of the entry points kernels use with llvmlite, so compiled
kernels stay cacheable on disk (a ctypes function pointer would be baked into the machine code as an
address and numba refuses to cache that). ``load()`` must run before any kernel that traces is compiled
or loaded from the cache; ``queries`` calls it on import.

Where the embreex 4.4.0.post1 wheels put the library (auditwheel, delvewheel and delocate each move
it; checked in the cp311 wheels ``make extension`` bundles): Linux ``embreex.libs/libembree4-<hash>.so.4``,
Windows ``embreex.libs/embree4.dll`` (beside ``tbb12.dll``, which importing embreex puts on the DLL search
path), macOS ``embreex/.dylibs/libembree4.4.dylib``.
"""

from __future__ import annotations

import ctypes
import sys
from pathlib import Path

from .errors import EmbreeError

#: Entry points compiled kernels call (registered with LLVM by name).
KERNEL_SYMBOLS = ("rtcIntersect1", "rtcOccluded1")

_void_p, _uint, _int, _size = ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_size_t

#: name: (result type, argument types). Enums are C ints; handles are pointers.
_SIGNATURES = {
    "rtcNewDevice": (_void_p, [ctypes.c_char_p]),
    "rtcReleaseDevice": (None, [_void_p]),
    "rtcGetDeviceError": (_int, [_void_p]),
    "rtcGetDeviceLastErrorMessage": (ctypes.c_char_p, [_void_p]),
    "rtcGetErrorString": (ctypes.c_char_p, [_int]),
    "rtcNewScene": (_void_p, [_void_p]),
    "rtcSetSceneFlags": (None, [_void_p, _int]),
    "rtcSetSceneBuildQuality": (None, [_void_p, _int]),
    "rtcCommitScene": (None, [_void_p]),
    "rtcReleaseScene": (None, [_void_p]),
    "rtcNewGeometry": (_void_p, [_void_p, _int]),
    "rtcSetGeometryTimeStepCount": (None, [_void_p, _uint]),
    "rtcSetGeometryTimeRange": (None, [_void_p, ctypes.c_float, ctypes.c_float]),
    "rtcSetSharedGeometryBuffer": (None, [_void_p, _int, _uint, _int, _void_p, _size, _size, _size]),
    "rtcCommitGeometry": (None, [_void_p]),
    "rtcAttachGeometry": (_uint, [_void_p, _void_p]),
    "rtcReleaseGeometry": (None, [_void_p]),
}

_loaded: list = []


def candidate_paths() -> list[Path]:
    """Where this platform's embreex wheel keeps ``libembree4`` (see the module docstring)."""
    import importlib.util

    spec = importlib.util.find_spec("embreex")
    if spec is None or not spec.submodule_search_locations:
        return []
    package = Path(list(spec.submodule_search_locations)[0])
    site = package.parent
    if sys.platform == "win32":
        patterns = [(site / "embreex.libs", "embree4*.dll"), (package, "embree4*.dll")]
    elif sys.platform == "darwin":
        patterns = [(package / ".dylibs", "libembree4*.dylib"), (site / "embreex.libs", "libembree4*.dylib")]
    else:
        patterns = [(site / "embreex.libs", "libembree4*.so*"), (package / ".libs", "libembree4*.so*")]
    found = []
    for folder, pattern in patterns:
        if folder.is_dir():
            found.extend(sorted(folder.glob(pattern)))
    return found


def load() -> ctypes.CDLL:
    """The loaded library, with its signatures declared and the kernels' symbols registered (once)."""
    if _loaded:
        return _loaded[0]
    try:
        import embreex  # noqa: F401  (on Windows its import adds the folder of Embree's own DLLs to the search path)
    except ImportError:
        pass
    paths = candidate_paths()
    if not paths:
        raise EmbreeError("Embree's library was not found: the embreex package is missing or incomplete "
                          "(reinstall Prism's dependencies)")
    try:
        library = ctypes.CDLL(str(paths[0]))
    except OSError as error:
        raise EmbreeError(f"Embree's library {paths[0].name} could not be loaded: {error}") from error
    for name, (result, arguments) in _SIGNATURES.items():
        function = getattr(library, name)
        function.restype = result
        function.argtypes = arguments
    from llvmlite import binding

    for name in KERNEL_SYMBOLS:
        binding.add_symbol(name, ctypes.cast(getattr(library, name), ctypes.c_void_p).value)
    _loaded.append(library)
    return library
