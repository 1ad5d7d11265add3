"""The Autofocus operator: focus distance from a ray cast through the frame centre or a focus object."""

import math

import bpy
import pytest
from helpers.bpy_scenes import add_camera


def _cube(name, location, size=2.0):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location)
    cube = bpy.context.active_object
    cube.name = name
    return cube


def test_focuses_on_the_cube_in_front_of_the_camera(fresh_scene):
    _cube("Target", (0.0, 0.0, 0.0))
    camera = add_camera((0.0, -10.0, 0.0), (math.pi / 2, 0.0, 0.0))  # looks along +Y at the cube
    camera.data.dof.focus_distance = 1.0
    assert bpy.ops.prism.autofocus() == {"FINISHED"}
    assert camera.data.dof.focus_distance == pytest.approx(9.0, abs=1e-4)  # the cube's near face at y = -1


def test_uses_modifiers_and_the_focus_object(fresh_scene):
    cube = _cube("Target", (0.0, 0.0, 0.0))
    move = cube.modifiers.new("Move", "DISPLACE")  # evaluated geometry moves 0.5 toward the camera
    move.direction, move.mid_level, move.strength = "Y", 0.0, -0.5
    camera = add_camera((0.0, -10.0, 0.0), (math.pi / 2, 0.0, 0.0))
    assert bpy.ops.prism.autofocus() == {"FINISHED"}
    assert camera.data.dof.focus_distance == pytest.approx(8.5, abs=1e-3)
    far = _cube("Far", (3.0, 20.0, 1.0), size=1.0)
    camera.data.dof.focus_object = far
    assert bpy.ops.prism.autofocus() == {"FINISHED"}
    assert camera.data.dof.focus_distance == pytest.approx(30.0, abs=1e-4)  # along the view axis
    camera.data.dof.focus_object = None
    assert bpy.ops.prism.autofocus(target="Target") == {"FINISHED"}
    assert camera.data.dof.focus_distance == pytest.approx(10.0, abs=1e-4)


def test_clear_errors_without_camera_or_target(fresh_scene):
    with pytest.raises(RuntimeError, match="no active camera"):
        bpy.ops.prism.autofocus()
    add_camera((0.0, -10.0, 0.0), (math.pi / 2, 0.0, 0.0))
    with pytest.raises(RuntimeError, match="nothing is under the centre of camera 'Camera'"):
        bpy.ops.prism.autofocus()
    with pytest.raises(RuntimeError, match="no object named 'Nope'"):
        bpy.ops.prism.autofocus(target="Nope")
