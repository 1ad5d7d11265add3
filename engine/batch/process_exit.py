"""Leaving a process that has loaded the bpy module.

The bpy module can hang for ever in a global destructor at interpreter exit, so scripts that load it
leave with ``os._exit``, which skips exit handlers. Blender removes its session folder
(``bpy.app.tempdir``: ``blender_XXXXXX`` in the system temporary folder) in one of those handlers;
``exit_now`` removes it first, or every run on a farm node would leave one behind.
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path


def remove_blender_session_folder() -> None:
    """Remove Blender's session folder, if bpy is loaded and the folder is one Blender made."""
    bpy = sys.modules.get("bpy")
    tempdir = bpy.app.tempdir if bpy is not None else ""
    if tempdir and Path(tempdir).name.startswith("blender_"):
        shutil.rmtree(tempdir, ignore_errors=True)


def exit_now(status: int) -> None:
    """Flush the console, remove Blender's session folder and end the process with ``status`` at once."""
    remove_blender_session_folder()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)
