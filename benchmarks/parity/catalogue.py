"""Every parity scene, in the report's order, and lookup by name."""

from __future__ import annotations

from .record import ParityScene
from .scenes_objects import SCENES as OBJECT_SCENES
from .scenes_output import SCENES as OUTPUT_SCENES

SCENES: list[ParityScene] = OBJECT_SCENES + OUTPUT_SCENES


def scene_named(name: str) -> ParityScene:
    for scene in SCENES:
        if scene.name == name:
            return scene
    raise KeyError(f"no parity scene '{name}': the scenes are {', '.join(s.name for s in SCENES)}")
