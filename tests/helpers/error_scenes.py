"""The scene the error tests start from (a floor, a bulb and a camera: it renders) and a change to its
light, shared by the tests of scene errors and of setting errors."""

from __future__ import annotations

import bpy

from .bpy_scenes import add_camera, add_plane, add_point_light


def base_scene():
    """A scene that renders: a plane, a light, a camera."""
    add_plane("Floor", 4.0)
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    add_camera((0.0, -3.0, 1.5), (1.1, 0.0, 0.0), resolution=(8, 8))


def light(**values):
    def mutate():
        data = bpy.data.lights["Bulb"]
        for key, value in values.items():
            if key == "energy":
                data.energy = value
            else:
                setattr(data.prism, key, value)

    return mutate
