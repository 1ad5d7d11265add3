"""What nested media render differently from Cycles (``tracer.media.nesting``): a grid medium (a Volume object,
a density or emission driven by nodes) shares no space with other media, and a camera inside more media than
nest keeps only the first."""

from __future__ import annotations

from ..tracer.media.enclosure import enclosing_media
from ..tracer.media.nesting import MAX_NESTED, overlapping_sets, scene_bounds


def _listed(names) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _is_grid(spec) -> bool:
    return spec.density_grid is not None or spec.varies


def nested_media_warnings(tracer_scene) -> list[str]:
    """One warning per grid medium whose mesh overlaps other media or lies in the World's fog, and one when the
    camera is inside more than ``MAX_NESTED`` media."""
    materials, fog = tracer_scene.materials, tracer_scene.world.medium
    warnings, warned = [], set()
    bounds = scene_bounds(tracer_scene)
    overlaps = overlapping_sets(bounds)
    for m in sorted(bounds):  # the media of meshes in the scene (the export may list a material twice)
        material = materials[m]
        if not _is_grid(material.medium) or material.name in warned:
            continue
        others = sorted({n for s in overlaps if m in s for n in s if n != m})
        named = [f"material '{materials[n].name}''s volume" for n in others]
        if fog is not None:
            named.append("the World's fog")
        if named:
            warned.add(material.name)
            warnings.append(
                f"Material '{material.name}': its volume varies point by point (a Volume object's grid or a density "
                f"driven by nodes) and shares space with {_listed(named)}; Cycles adds them there, Prism renders "
                f"'{material.name}''s volume alone inside its mesh (the others are missing there).")
    origin = tracer_scene.camera.camera_to_world[:3, 3]
    inside = enclosing_media(origin, tracer_scene.vertices, tracer_scene.triangles, tracer_scene.triangle_material,
                             materials)
    if len(inside) > 1 and tuple(sorted(inside)) not in set(overlaps):  # more than MAX_NESTED
        names = [materials[m].name for m in inside]
        warnings.append(
            f"Material '{names[0]}': the camera is inside the volumes of materials "
            + ", ".join(f"'{n}'" for n in names) + f"; Prism nests up to {MAX_NESTED} media, so camera rays start "
            f"in '{names[0]}' alone. Move the camera out of some of these meshes.")
    return warnings
