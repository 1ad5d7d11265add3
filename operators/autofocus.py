"""Autofocus: set the active camera's focus distance to what it looks at.

The distance is measured along the camera's view axis from the camera's origin, which is
where Prism's real lens puts the film (and where Blender measures its focus distance).
"""

from __future__ import annotations

import bpy
from bpy.props import StringProperty
from mathutils import Vector


def _larger_frame_dimension_mm(data, render):
    """The frame's larger dimension on the sensor (Blender's unit of lens shift)."""
    aspect = (render.resolution_y * render.pixel_aspect_y) / max(render.resolution_x * render.pixel_aspect_x, 1e-9)
    if data.sensor_fit == "HORIZONTAL":
        return data.sensor_width * max(1.0, aspect)
    if data.sensor_fit == "VERTICAL":
        return data.sensor_height * max(1.0, 1.0 / aspect)
    return data.sensor_width


def _frame_centre_direction(camera_object, render):
    """World direction through the centre of the frame (lens shift included), unit length."""
    data = camera_object.data
    local = Vector((0.0, 0.0, -1.0))
    if data.type == "PERSP" and (data.shift_x or data.shift_y):
        larger = _larger_frame_dimension_mm(data, render)
        local = Vector((data.shift_x * larger / data.lens, data.shift_y * larger / data.lens, -1.0))
    return (camera_object.matrix_world.to_3x3() @ local).normalized()


class PRISM_OT_autofocus(bpy.types.Operator):
    """Focus the active camera on what is under the centre of the frame, or on the focus object"""

    bl_idname = "prism.autofocus"
    bl_label = "Autofocus"
    bl_options = {"REGISTER", "UNDO"}

    target: StringProperty(
        name="Object",
        description="Focus on this object's origin instead (empty: the camera's focus object, else the frame centre)",
        default="",
    )

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def execute(self, context):
        scene = context.scene
        camera = scene.camera
        if camera is None or camera.type != "CAMERA":
            self.report({"ERROR"}, "Autofocus: the scene has no active camera. Add a camera and make it active "
                                   "(View > Cameras > Set Active Object as Camera).")
            return {"CANCELLED"}
        depsgraph = context.evaluated_depsgraph_get()
        camera_eval = camera.evaluated_get(depsgraph)
        origin = camera_eval.matrix_world.translation.copy()
        axis = (camera_eval.matrix_world.to_3x3() @ Vector((0.0, 0.0, -1.0))).normalized()

        target = self._target_object(camera)
        if target is False:
            return {"CANCELLED"}
        if target is not None:
            location = target.evaluated_get(depsgraph).matrix_world.translation
            what = f"object '{target.name}'"
        else:
            direction = _frame_centre_direction(camera_eval, scene.render)
            hit, location, _normal, _index, hit_object, _matrix = scene.ray_cast(depsgraph, origin, direction)
            if not hit:
                self.report({"ERROR"}, f"Autofocus: nothing is under the centre of camera '{camera.name}''s frame. "
                                       "Aim the camera at an object, or choose a focus object.")
                return {"CANCELLED"}
            what = f"'{hit_object.name}'"
        distance = (location - origin).dot(axis)
        if not distance > 0:
            self.report({"ERROR"}, f"Autofocus: {what} is behind camera '{camera.name}'; aim the camera at it.")
            return {"CANCELLED"}
        camera.data.dof.focus_distance = distance
        self.report({"INFO"}, f"Camera '{camera.name}' focused at {distance:.3f} m on {what}.")
        return {"FINISHED"}

    def _target_object(self, camera):
        """The object to focus on: the named one, else the camera's focus object, else None.

        Returns False (after reporting) when the named object does not exist.
        """
        if self.target:
            obj = bpy.data.objects.get(self.target)
            if obj is None:
                self.report({"ERROR"}, f"Autofocus: there is no object named '{self.target}'.")
                return False
            return obj
        return camera.data.dof.focus_object


_CLASSES = (PRISM_OT_autofocus,)


register, unregister = bpy.utils.register_classes_factory(_CLASSES)
