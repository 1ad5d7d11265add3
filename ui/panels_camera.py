"""Camera data properties: lens model, lens chooser, focus, and the real lens's read-outs."""

from __future__ import annotations

import importlib
import inspect
import os

import bpy

from ._panel_base import PrismPanel, error_label

_readout_cache: dict = {}


def _lens_catalogue():
    return importlib.import_module("..engine.tracer.lens.catalogue", __package__)


def _call_readouts(function, path: str, fstop: float, focus_distance_m: float, sensor_width_mm: float):
    """Call ``lens_readouts`` with the keyword arguments it declares."""
    wanted = {
        "sensor_width_mm": sensor_width_mm,
        "fstop": fstop,
        "f_number": fstop,
        "focus_distance_m": focus_distance_m,
        "focus_distance_mm": focus_distance_m * 1000.0,
    }
    parameters = inspect.signature(function).parameters
    return function(path, **{k: v for k, v in wanted.items() if k in parameters})


def _as_rows(result) -> list[tuple[str, str]]:
    if isinstance(result, dict):
        return [(str(k), str(v)) for k, v in result.items()]
    rows = []
    for item in result:
        if isinstance(item, (tuple, list)) and len(item) >= 2:
            rows.append((str(item[0]), str(item[1])))
        else:
            rows.append((str(item), ""))
    return rows


def lens_readout_rows(camera_data) -> tuple[list[tuple[str, str]], str | None]:
    """(rows of (label, value), error message or None) for the camera's real lens."""
    path = camera_data.prism.lens_path()
    if not path:
        return [], "Choose a lens prescription."
    if not os.path.isfile(path):
        return [], f"Lens file not found: {path}"
    dof = camera_data.dof
    key = (path, os.path.getmtime(path), dof.aperture_fstop, dof.focus_distance, camera_data.sensor_width)
    if key in _readout_cache:
        return _readout_cache[key]
    try:
        function = _lens_catalogue().lens_readouts
    except (ImportError, AttributeError):
        return [], "Lens read-outs are not available in this build."
    try:
        answer = (_as_rows(_call_readouts(function, path, dof.aperture_fstop, dof.focus_distance, camera_data.sensor_width)), None)
    except Exception as error:  # noqa: BLE001 - any failure is shown as a red label, never a traceback
        answer = ([], str(error) or type(error).__name__)
    if len(_readout_cache) > 32:
        _readout_cache.clear()
    _readout_cache[key] = answer
    return answer


class PRISM_PT_camera_lens(PrismPanel, bpy.types.Panel):
    """Which lens model the camera uses and which prescription."""

    bl_label = "Prism Lens"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return context.engine == "PRISM" and context.camera is not None

    def draw(self, context):
        layout = self.layout
        camera = context.camera
        settings = camera.prism
        layout.row().prop(settings, "lens_model", expand=True)
        layout.use_property_split = True
        layout.use_property_decorate = False
        if settings.lens_model != "REAL_LENS":
            return
        if camera.type != "PERSP":
            error_label(layout, "A real lens forms a perspective image: set Lens ▸ Type to Perspective.")
        layout.row().prop(settings, "lens_source", expand=True)
        if settings.lens_source == "BUNDLED":
            layout.prop(settings, "bundled_lens")
        else:
            layout.prop(settings, "lens_file")
        rows, error = lens_readout_rows(camera)
        box = layout.box()
        if error:
            error_label(box, error)
        column = box.column(align=True)
        for label, value in rows:
            row = column.row()
            row.label(text=label)
            row.label(text=value)


class PRISM_PT_camera_focus(PrismPanel, bpy.types.Panel):
    """Blender's own depth-of-field settings: the checkbox (Blender's camera), focus distance or object,
    f-stop and the aperture's blades."""

    bl_label = "Focus"
    bl_context = "data"
    bl_parent_id = "PRISM_PT_camera_lens"

    @classmethod
    def poll(cls, context):
        return context.engine == "PRISM" and context.camera is not None

    def draw(self, context):
        layout = self.layout
        camera = context.camera
        dof = camera.dof
        layout.use_property_split = True
        layout.use_property_decorate = False
        model = camera.prism.lens_model
        if model == "PINHOLE":
            layout.prop(dof, "use_dof", text="Depth of Field")
            if not dof.use_dof:
                return
        column = layout.column()
        column.prop(dof, "focus_object", text="Focus on Object")
        if dof.focus_object is not None and dof.focus_object.type == "ARMATURE":
            column.prop_search(dof, "focus_subtarget", dof.focus_object.data, "bones", text="Focus on Bone")
        sub = column.column()
        sub.active = dof.focus_object is None
        sub.prop(dof, "focus_distance", text="Distance")
        column.prop(dof, "aperture_fstop", text="F-Stop")
        if model != "REAL_LENS":
            column.prop(dof, "aperture_blades", text="Blades")
            column.prop(dof, "aperture_rotation", text="Rotation")
            column.prop(dof, "aperture_ratio", text="Ratio")
        layout.operator("prism.autofocus", icon="VIEWZOOM")


CLASSES = (PRISM_PT_camera_lens, PRISM_PT_camera_focus)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
