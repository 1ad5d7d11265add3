"""PNG files made the way Blender makes a scene's PNG, for images that were not rendered as PNG.

A PNG is scene-linear pixels through the scene's Color Management (display device, view
transform, look, exposure, gamma, curves, white balance), dithered, at the output's depth and
channels. ``png_settings(scene)`` records all of that as plain values: a chunk carries them,
because the merge that writes the frame's PNG later has no .blend file.

``write_png`` writes an image with such settings through Blender's own writer: it puts the
pixels in the Render Result of a scratch scene holding the settings (a Prism "render" that
shows the image instead of tracing, see ``RenderRequest.show_image``) and saves that as
``write_still`` would. So a merged frame's PNG has the pixels of the PNG one render of all the
samples writes, dither included.
"""

from __future__ import annotations

from pathlib import Path

import bpy

from ..render.request import RenderRequest, render_request
from ..tracer.errors import PrismInputError

#: The output settings a PNG depends on, besides Color Management and dither.
_PNG_FIELDS = ("color_management", "color_mode", "color_depth", "compression")
#: Applied first: the looks Blender offers depend on the view transform.
_FIRST = ("view_transform", "look")
#: Computed from other settings (the white point from temperature and tint): never recorded.
_DERIVED = {"white_balance_whitepoint"}


def png_settings(scene) -> dict:
    """What ``scene`` turns a scene-linear image into a PNG with, as JSON-ready values.

    Read it with the scene's output format set to PNG (Blender adapts the depth to the format).
    """
    image = scene.render.image_settings
    settings = {
        "display_settings": _values(scene.display_settings),
        "view_settings": _view_values(scene.view_settings),
        "dither_intensity": scene.render.dither_intensity,
        "image_settings": {name: getattr(image, name) for name in _PNG_FIELDS if hasattr(image, name)},
    }
    if getattr(image, "color_management", "FOLLOW_SCENE") == "OVERRIDE":
        settings["override_display_settings"] = _values(image.display_settings)
        settings["override_view_settings"] = _view_values(image.view_settings)
    return settings


def write_png(image, settings: dict, path: Path, source: str, frame: int = 1) -> None:
    """Write ``image`` (scene-linear [H, W, 3], row 0 at the top) to the PNG ``path`` as a scene
    with ``settings`` writes its renders. ``source`` names where the settings come from in errors."""
    height, width = image.shape[:2]
    scene = bpy.data.scenes.new("Prism PNG output")
    camera = bpy.data.objects.new("Prism PNG output", bpy.data.cameras.new("Prism PNG output"))
    try:
        scene.collection.objects.link(camera)
        scene.camera = camera  # Blender renders no scene without one
        scene.frame_current = frame
        scene.render.engine = "PRISM"
        scene.render.resolution_x, scene.render.resolution_y = width, height
        scene.render.resolution_percentage = 100
        apply_png_settings(settings, scene, source)
        with render_request(RenderRequest(show_image=image, quick_first_pass=False)) as report:
            bpy.ops.render.render(write_still=False, scene=scene.name)
        if report.error or not report.started:
            raise PrismInputError(f"Cannot write '{path}': {report.error or 'Blender did not start the render'}.")
        result = next(image for image in bpy.data.images if image.type == "RENDER_RESULT")
        try:
            result.save_render(filepath=str(path), scene=scene)
        except RuntimeError as error:
            raise PrismInputError(f"Cannot write '{path}': {str(error).strip()}.") from None
    finally:
        data = camera.data
        bpy.data.objects.remove(camera)
        bpy.data.cameras.remove(data)
        bpy.data.scenes.remove(scene)


def apply_png_settings(settings: dict, scene, source: str) -> None:
    """Give ``scene`` the PNG ``settings`` (see ``png_settings``); an error naming ``source`` and
    the setting when this Blender cannot."""
    _set(scene.display_settings, settings["display_settings"], source, "Color Management")
    _set_view(scene.view_settings, settings["view_settings"], source, "Color Management")
    scene.render.dither_intensity = settings["dither_intensity"]
    image = scene.render.image_settings
    image.file_format = "PNG"
    _set(image, settings["image_settings"], source, "Output")
    if "override_display_settings" in settings:
        _set(image.display_settings, settings["override_display_settings"], source, "Output ▸ Color Management")
        _set_view(image.view_settings, settings["override_view_settings"], source, "Output ▸ Color Management")


def _values(struct) -> dict:
    """The editable plain properties of an RNA struct (no pointers or collections)."""
    return {
        prop.identifier: _plain(prop, getattr(struct, prop.identifier))
        for prop in struct.bl_rna.properties
        if prop.identifier != "rna_type" and prop.identifier not in _DERIVED and not prop.is_readonly
        and prop.type not in ("POINTER", "COLLECTION")
    }


def _plain(prop, value):
    """A property's value as JSON holds it: enum flags as a sorted list, arrays as lists."""
    if prop.type == "ENUM" and prop.is_enum_flag:
        return sorted(value)
    return value if isinstance(value, (bool, int, float, str)) else list(value)


def _view_values(view) -> dict:
    values = _values(view)
    if view.use_curve_mapping:
        mapping = view.curve_mapping
        values["curve_mapping"] = {
            **_values(mapping),
            "curves": [[[point.location[0], point.location[1], point.handle_type] for point in curve.points]
                       for curve in mapping.curves],
        }
    return values


def _set(struct, values: dict, source: str, panel: str) -> None:
    """Set ``values`` on ``struct``, view transform and look first. Properties this Blender lacks
    (chunks of another Blender version) are skipped: their PNG cannot be the same anyway."""
    for name in sorted(values, key=lambda key: _FIRST.index(key) if key in _FIRST else len(_FIRST)):
        prop = struct.bl_rna.properties.get(name)
        if prop is None or name == "curve_mapping" or prop.is_readonly:
            continue
        value = values[name]
        if _plain(prop, getattr(struct, name)) == value:
            continue
        try:
            setattr(struct, name, set(value) if prop.type == "ENUM" and prop.is_enum_flag else value)
        except (TypeError, ValueError, AttributeError) as error:
            raise PrismInputError(
                f"'{source}' was rendered with {panel} ▸ {prop.name or name} '{value}', which this Blender cannot "
                f"use ({str(error).strip()}): write the PNG with the Blender the chunks were rendered with, or "
                "merge to EXR."
            ) from None


def _set_view(view, values: dict, source: str, panel: str) -> None:
    _set(view, values, source, panel)
    mapping_values = values.get("curve_mapping")
    if not mapping_values:
        return
    mapping = view.curve_mapping
    _set(mapping, {key: value for key, value in mapping_values.items() if key != "curves"}, source, panel)
    for curve, points in zip(mapping.curves, mapping_values["curves"]):
        while len(curve.points) > 2:
            curve.points.remove(curve.points[1])
        for point, (x, y, _) in zip(curve.points, points[:2]):
            point.location = (x, y)
        for x, y, _ in points[2:]:
            curve.points.new(x, y)
        for point, (_, _, handle) in zip(curve.points, points):
            point.handle_type = handle
    mapping.update()
