"""Cycles settings that Cycles applies while it syncs a scene, not Blender's depsgraph, and Prism does not: Render ▸
Simplify ▸ Texture Limit and Culling, and Light Paths ▸ Fast GI Approximation. Each is named in a warning with what
Prism renders instead. (Simplify's Max Subdivision and Child Particles Blender applies to the evaluated geometry,
so Prism renders them as Cycles does; its Volume Resolution is the viewport's.)
"""

from __future__ import annotations

#: At most this many names in one warning; the rest are counted.
_NAMED = 3


def _names(items) -> str:
    shown = ", ".join(f"'{name}'" for name in items[:_NAMED])
    return shown + (f" and {len(items) - _NAMED} more" if len(items) > _NAMED else "")


def texture_limit_warning(scene, images) -> str | None:
    """Simplify ▸ Texture Limit (render) when it would shrink one of ``images`` (the image datablocks the render
    uses): Cycles halves an image until its larger side fits (``scene/image.cpp``)."""
    cycles = getattr(scene, "cycles", None)
    limit = getattr(cycles, "texture_limit_render", "OFF")
    if not scene.render.use_simplify or limit == "OFF":
        return None
    larger = [image.name for image in images if max(image.size[:2], default=0) > int(limit)]
    if not larger:
        return None
    return (f"Scene '{scene.name}': Simplify ▸ Texture Limit {limit} px is not applied: Prism renders "
            f"{_names(larger)} at full size, where Cycles halves each until its larger side is at most {limit} px.")


def culling_warning(scene, objects) -> str | None:
    """Simplify ▸ Culling (camera, distance) when it applies to one of ``objects``: Cycles then leaves out, at
    sync, those whose bounds lie outside the camera's view by more than the margin, or farther than the
    distance."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None or not scene.render.use_simplify:
        return None
    kinds = [(name, f"{what} (margin {getattr(cycles, margin):g}{unit})") for name, what, margin, unit in
             (("use_camera_cull", "Camera Culling", "camera_cull_margin", ""),
              ("use_distance_cull", "Distance Culling", "distance_cull_margin", " m"))
             if getattr(cycles, name, False)]
    culled = sorted({obj.name for obj in objects for name, _ in kinds
                     if getattr(getattr(obj, "cycles", None), name, False)})
    if not culled:
        return None
    return (f"Scene '{scene.name}': Simplify ▸ Culling ▸ {' and '.join(label for _, label in kinds)} is not "
            f"applied: Prism renders {_names(culled)} wherever they are, where Cycles leaves them out when they lie "
            "outside the camera's view or too far from it (and with them their shadows and reflections).")


def fast_gi_warning(scene) -> str | None:
    """Light Paths ▸ Fast GI Approximation, which Prism does not model: it traces every bounce."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None or not getattr(cycles, "use_fast_gi", False):
        return None
    bounces = int(getattr(cycles, "ao_bounces_render", 0))
    if bounces <= 0:  # "0 disables this feature"
        return None
    return (f"Scene '{scene.name}': Light Paths ▸ Fast GI Approximation is not modelled: Prism traces every "
            f"bounce, where Cycles approximates the diffuse light after {bounces} bounce{'s' if bounces > 1 else ''} "
            "with the World's ambient occlusion, so Prism's indirect light is the full one.")


def simplify_warnings(scene, depsgraph) -> list[str]:
    """The warnings above for ``scene`` rendered through ``depsgraph`` (its objects and the images it uses)."""
    ids = list(getattr(depsgraph, "ids", ()))
    images = [i for i in ids if getattr(i, "id_type", "") == "IMAGE" and getattr(i, "size", None) is not None]
    # the originals' settings: an evaluated copy's add-on properties are only as new as its last evaluation
    objects = [getattr(i, "original", i) for i in ids if getattr(i, "id_type", "") == "OBJECT"]
    return [w for w in (texture_limit_warning(scene, images), culling_warning(scene, objects),
                        fast_gi_warning(scene)) if w is not None]
