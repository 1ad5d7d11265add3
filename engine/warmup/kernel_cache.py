"""Where compiled tracer kernels are cached inside Blender, and the first-render notice.

Imports no numba (only ``engine.tracer.kernel_folder``): the render session calls it before any kernel
module is imported, and the background warm-up (``engine.warmup``) asks it whether the cache is warm
from Blender's process.

- ``configure()`` points the kernel cache at the extension's own user folder,
  ``bpy.utils.extension_path_user(<package>, path="kernel_cache")`` (for example
  ``~/.config/blender/4.5/extensions/.user/user_default/prism_spectral/kernel_cache`` on Linux).
  Blender keeps that folder writable and across upgrades of the extension, even when the
  extension itself is installed read-only (a "System" repository). It must run before any
  tracer kernel module is imported, so the session module calls it first. When Prism runs as a
  plain module (``render.py`` with the bpy module, the legacy add-on path), there is no
  extension folder and the tracer's own default applies (``$PRISM_KERNEL_CACHE``, else a per-user
  cache folder; see ``engine.tracer.jit``).
- It also adopts the kernels shipped inside the extension when this CPU's own are not compiled yet
  (``shipped_kernels``): the first render then loads instead of compiling.
- ``compiling_notice()`` is ``COMPILING_MESSAGE`` while this tracer source has not been compiled
  into that folder yet (the first render on a machine, or after an update), else None;
  ``mark_compiled()`` records a render that compiled everything.
"""

from __future__ import annotations

from pathlib import Path

COMPILING_MESSAGE = "Compiling Prism kernels (first render only)"
#: Said instead while the background warm-up (``engine.warmup``) compiles them and the render waits for it.
WAITING_MESSAGE = "Waiting for the Prism kernels compiling in the background (first render only)"
CACHE_SUBFOLDER = "kernel_cache"

#: The add-on's package: ``bl_ext.<repository>.prism_spectral`` when installed as an extension.
ADDON_PACKAGE = __name__.rsplit(".", 3)[0]  # <add-on>.engine.warmup.kernel_cache

_configured = False


def extension_cache_directory(package: str = ADDON_PACKAGE) -> Path | None:
    """The extension's user ``kernel_cache`` folder (created), or None outside an extension.

    None when ``package`` is not an extension (plain module, legacy add-on) or the folder cannot
    be created; the tracer then uses its own default directory.
    """
    if not package.startswith("bl_ext."):
        return None
    try:
        import bpy

        return Path(bpy.utils.extension_path_user(package, path=CACHE_SUBFOLDER, create=True))
    except (ImportError, ValueError, OSError):
        return None


def configure() -> Path:
    """Choose the kernel cache directory and, where this CPU's own kernels are not compiled yet, the
    kernels shipped with the extension (``shipped_kernels``): once per process. Returns the directory."""
    global _configured
    from ..tracer import kernel_folder

    if not _configured:
        _configured = True
        directory = extension_cache_directory()
        if directory is not None:
            try:
                kernel_folder.configure_cache(directory)
            except OSError:
                pass  # keep the tracer's default folder
        from . import shipped_kernels

        try:
            shipped_kernels.adopt()
        except Exception:  # noqa: BLE001 - shipped kernels only save time: without them the render compiles
            import traceback

            traceback.print_exc()
    return kernel_folder.cache_directory()


def check_directory() -> None:
    """``PrismInputError`` naming ``$PRISM_KERNEL_CACHE`` (or ``$NUMBA_CACHE_DIR``) when the folder it
    names cannot hold the kernels; a render calls it before exporting anything."""
    from ..tracer import kernel_folder

    kernel_folder.prepare_kernel_directory()


def compiling_notice() -> str | None:
    """``COMPILING_MESSAGE`` if this render will compile the kernels (cold cache), else None."""
    from ..tracer import kernel_folder

    return None if kernel_folder.cache_is_warm() else COMPILING_MESSAGE


def mark_compiled() -> None:
    """Record that a finished render compiled every kernel it needed into the cache."""
    from ..tracer import kernel_folder

    try:
        kernel_folder.cache_directory().mkdir(parents=True, exist_ok=True)
    except OSError:
        return  # a cache that cannot be written only costs the notice on the next render
    kernel_folder.mark_cache_warm()
