"""Whether the camera stands inside closed meshes that hold media (``tracer.media.enclosure``): camera rays
start in the medium around the camera (``KernelSettings.camera_medium``); media do not nest, so a camera
inside two of them is told which one its rays start in."""

from __future__ import annotations

from ..tracer.media.enclosure import enclosing_media


def camera_in_medium_warnings(tracer_scene) -> list[str]:
    """One warning when the camera is inside the volumes of several materials (nested media)."""
    origin = tracer_scene.camera.camera_to_world[:3, 3]
    inside = enclosing_media(origin, tracer_scene.vertices, tracer_scene.triangles, tracer_scene.triangle_material,
                             tracer_scene.materials)
    if len(inside) < 2:
        return []
    names = [tracer_scene.materials[m].name for m in inside]
    return [f"Material '{names[0]}': the camera is inside the volumes of materials "
            + ", ".join(f"'{n}'" for n in names) + f"; Prism does not nest media, so camera rays start in "
            f"'{names[0]}' alone. Move the camera out of all but one of these meshes."]
