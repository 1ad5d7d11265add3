"""Denoising with OpenImageDenoise, the library Blender ships and its compositor's Denoise node runs.

Render ▸ Prism ▸ Denoise runs OIDN's ray-tracing filter ("RT") on the final Combined pass, guided by the
Denoising Albedo and Denoising Normal passes, with the Denoise node's options: prefilter ``NONE`` (the
guides are trusted as noise-free), ``FAST`` (the filter is told the guides are noisy) or ``ACCURATE``
(the guides are denoised first, then trusted), quality ``HIGH`` / ``BALANCED`` / ``FAST``, HDR input.
The library is Blender's own: found next to Blender's executable or the ``bpy`` module and reached
through its C API with ctypes (no extra package).
"""

from __future__ import annotations

import ctypes
import sys
from pathlib import Path

import numpy as np

from ..tracer.errors import PrismInputError

_DEVICE_CPU = 1
_FORMAT_FLOAT3 = 3
QUALITY = {"FAST": 4, "BALANCED": 5, "HIGH": 6}
PREFILTERS = ("NONE", "FAST", "ACCURATE")

_library = None


def _candidate_files() -> list[Path]:
    names = {"win32": ["OpenImageDenoise.dll"], "darwin": ["libOpenImageDenoise.2.dylib", "libOpenImageDenoise.dylib"]}
    names = names.get(sys.platform, ["libOpenImageDenoise.so.2", "libOpenImageDenoise.so"])
    folders = []
    try:
        import bpy

        binary = Path(bpy.app.binary_path) if bpy.app.binary_path else None
        module = Path(bpy.__file__).resolve()
        for parent in list(module.parents)[:6]:
            folders += [parent / "lib", parent]
        if binary is not None:
            folders += [binary.parent, binary.parent / "lib", binary.parent.parent / "Resources" / "lib"]
            folders += [p / "lib" for p in binary.parent.glob("*") if p.is_dir()]
    except ImportError:
        pass
    return [folder / name for folder in folders for name in names if (folder / name).is_file()]


def _loaded_from_process() -> list[Path]:
    """On Linux the library Blender already loaded is listed in /proc/self/maps."""
    maps = Path("/proc/self/maps")
    if not maps.is_file():
        return []
    found = []
    for line in maps.read_text().splitlines():
        path = line.split()[-1] if line.split() else ""
        if "libOpenImageDenoise.so" in path and "_core" not in path and "device" not in path:
            found.append(Path(path))
    return found


def library():
    """Blender's OpenImageDenoise (ctypes), loaded once; ``PrismInputError`` when this Blender has none."""
    global _library
    if _library is not None:
        return _library
    for path in dict.fromkeys(_loaded_from_process() + _candidate_files()):
        try:
            lib = ctypes.CDLL(str(path))
        except OSError:
            continue
        _declare(lib)
        _library = lib
        return lib
    raise PrismInputError(
        "Denoising needs OpenImageDenoise, which this Blender build does not include: turn off Render ▸ Prism ▸ "
        "Denoise (or use an official Blender build)."
    )


def _declare(lib) -> None:
    p, c, s = ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t
    lib.oidnNewDevice.restype = p
    lib.oidnNewDevice.argtypes = [ctypes.c_int]
    lib.oidnCommitDevice.argtypes = [p]
    lib.oidnReleaseDevice.argtypes = [p]
    lib.oidnNewFilter.restype = p
    lib.oidnNewFilter.argtypes = [p, c]
    lib.oidnSetSharedFilterImage.argtypes = [p, c, p, ctypes.c_int, s, s, s, s, s]
    lib.oidnSetFilterBool.argtypes = [p, c, ctypes.c_bool]
    lib.oidnSetFilterInt.argtypes = [p, c, ctypes.c_int]
    lib.oidnCommitFilter.argtypes = [p]
    lib.oidnExecuteFilter.argtypes = [p]
    lib.oidnReleaseFilter.argtypes = [p]
    lib.oidnGetDeviceError.restype = ctypes.c_int
    lib.oidnGetDeviceError.argtypes = [p, ctypes.POINTER(ctypes.c_char_p)]


def _run(lib, device, images: dict[str, np.ndarray], output: np.ndarray, hdr: bool, clean_aux: bool,
         quality: int) -> None:
    height, width, _ = output.shape
    handle = lib.oidnNewFilter(device, b"RT")
    try:
        for name, image in images.items():
            lib.oidnSetSharedFilterImage(handle, name.encode(), image.ctypes.data, _FORMAT_FLOAT3, width, height,
                                         0, 0, 0)
        lib.oidnSetSharedFilterImage(handle, b"output", output.ctypes.data, _FORMAT_FLOAT3, width, height, 0, 0, 0)
        if "color" in images:
            lib.oidnSetFilterBool(handle, b"hdr", hdr)
        if "albedo" in images and "color" in images:
            lib.oidnSetFilterBool(handle, b"cleanAux", clean_aux)
        lib.oidnSetFilterInt(handle, b"quality", quality)
        lib.oidnCommitFilter(handle)
        lib.oidnExecuteFilter(handle)
        message = ctypes.c_char_p()
        if lib.oidnGetDeviceError(device, ctypes.byref(message)):
            text = message.value.decode(errors="replace") if message.value else "unknown error"
            raise PrismInputError(f"OpenImageDenoise failed: {text}.")
    finally:
        lib.oidnReleaseFilter(handle)


def _float3(image: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(image, np.float32)[..., :3])


def denoise(color: np.ndarray, albedo: np.ndarray | None = None, normal: np.ndarray | None = None,
            prefilter: str = "ACCURATE", quality: str = "HIGH", hdr: bool = True) -> np.ndarray:
    """The denoised ``color`` [H, W, 3] (scene-linear), guided by ``albedo`` and ``normal`` [H, W, 3]
    when given (a normal needs an albedo, as in OIDN). Rows may be in any order (all images alike)."""
    if prefilter not in PREFILTERS:
        raise PrismInputError(f"Denoising prefilter '{prefilter}' is unknown: use one of {', '.join(PREFILTERS)}.")
    if quality not in QUALITY:
        raise PrismInputError(f"Denoising quality '{quality}' is unknown: use one of {', '.join(QUALITY)}.")
    lib = library()
    level = QUALITY[quality]
    images = {"color": _float3(color)}
    if albedo is not None:
        images["albedo"] = _float3(albedo)
        if normal is not None:
            images["normal"] = _float3(normal)
    device = lib.oidnNewDevice(_DEVICE_CPU)
    if not device:
        raise PrismInputError("OpenImageDenoise could not start on this CPU: turn off Render ▸ Prism ▸ Denoise.")
    try:
        lib.oidnCommitDevice(device)
        if prefilter == "ACCURATE":
            for name in ("albedo", "normal"):
                if name in images:
                    cleaned = np.empty_like(images[name])
                    _run(lib, device, {name: images[name]}, cleaned, hdr, True, level)
                    images[name] = cleaned
        output = np.empty_like(images["color"])
        _run(lib, device, images, output, hdr, prefilter != "FAST", level)
    finally:
        lib.oidnReleaseDevice(device)
    return output
