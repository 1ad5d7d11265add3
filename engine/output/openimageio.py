"""OpenImageIO, which Blender bundles in its own Python's site-packages (not on ``sys.path`` of the
bpy module): imported on first use by the writers of EXR files."""

from __future__ import annotations

import sys
from pathlib import Path


def import_openimageio():
    """The ``OpenImageIO`` module (Blender's copy when no other is importable)."""
    try:
        import OpenImageIO
    except ImportError:
        import bpy

        version = f"python{sys.version_info.major}.{sys.version_info.minor}"
        sys.path.append(str(Path(bpy.utils.system_resource("PYTHON")) / "lib" / version / "site-packages"))
        import OpenImageIO
    return OpenImageIO
