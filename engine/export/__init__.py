"""Blender scene → ``engine.tracer.scene.Scene``: the export layer.

Reads the evaluated depsgraph (modifiers and instances applied) with
``foreach_get`` into numpy. Each kind of data-block has its own module.
"""

from __future__ import annotations

import numpy as np

from ..tracer.errors import PrismInputError
from ..tracer.scene import Camera, Scene
from ..tracer.curves import curve_count
from ..tracer.spheres import rendered_rows
from .border import render_border
from .camera import export_camera, render_resolution
from .data_passes import export_data_passes
from .light_linking import export_light_links
from .lights import export_lights
from .meshes import export_meshes
from .missing_libraries import missing_libraries
from .motion import export_motion
from .simplify_settings import simplify_warnings
from .unrendered_settings import unrendered_setting_warnings
from .vector_pass import export_vector_pass
from .view_layer_filter import LayerFilter, layer_filter
from .world import export_world
from .zero_area import zero_area_objects, zero_area_sentence

__all__ = ["PrismInputError", "export_camera", "export_scene", "render_border", "render_resolution"]


def _emits(material) -> bool:
    medium = material.medium
    terms = [] if medium is None else [(s, rgb) for s, rgb, _ in medium.emission] + medium.emission_field
    if any(strength > 0 and max(rgb) > 0 for strength, rgb in terms):
        return True  # an emitting volume lights the scene from inside its mesh
    shader = material.shader
    if shader is not None:
        return shader.emission is not None and shader.emission_strength > 0
    return material.emission is not None and material.emission_strength > 0


def _check_something_to_see(scene_name: str, tracer_scene: Scene, missing=(), world_filtered_by: str = "",
                            world_notes=(), included: LayerFilter = LayerFilter()) -> None:
    """Raises when the image could only be black or empty; ``missing``: ``MissingLibrary``s, named when
    nothing is left to see; ``world_filtered_by``: the view layer whose Filter ▸ Environment is off (its
    world lights nothing), named when nothing else lights the scene; ``world_notes``: the warnings about
    the world (a link Prism ignored may be why it is black), told with the refusal since the warnings of a
    refused render are not printed; ``included``: the view layer's Filter, whose Surfaces or Curves off
    may leave the world alone to render (as Cycles renders it)."""
    points = (tracer_scene.points is not None and len(rendered_rows(tracer_scene.points)) > 0) or bool(
        curve_count(tracer_scene.curves))  # spheres or curves to see
    if tracer_scene.world.medium is not None and tracer_scene.triangle_count == 0 and not points:
        return  # fog in the world is something to see (lit by the lights in it), as Cycles renders it
    if tracer_scene.triangle_count == 0 and not points and missing:
        raise PrismInputError(f"Scene '{scene_name}' has no visible geometry: "
                              + "; ".join(library.sentence() for library in missing) + ".")
    if tracer_scene.triangle_count == 0 and not points and included.left_out():
        if not tracer_scene.world.is_black():
            return  # the world alone, as Cycles renders a layer whose filter leaves out every surface
        raise PrismInputError(
            f"Scene '{scene_name}' has nothing to render: View Layer '{included.layer_name}' ▸ Filter ▸ "
            f"{' and '.join(included.left_out())} {'is' if len(included.left_out()) == 1 else 'are'} off, so no "
            "geometry is rendered, and the world is black"
            + (" (Filter ▸ Environment is off too)" if world_filtered_by else "")
            + ": turn the filter on, or the image would be black.")
    if tracer_scene.triangle_count == 0 and not points and tracer_scene.points is not None and len(tracer_scene.points):
        names = sorted({tracer_scene.object_names[int(i)] for i in np.unique(tracer_scene.points.object)})
        raise PrismInputError(
            f"Scene '{scene_name}' has no visible geometry: every point of point cloud "
            + ", ".join(f"'{name}'" for name in names) + " has a radius of 0 (or not a number): give the points a "
            "radius (Geometry Nodes ▸ Set Point Radius, or the radius attribute), or add a mesh.")
    if tracer_scene.triangle_count == 0 and not points:
        raise PrismInputError(
            f"Scene '{scene_name}' has no visible geometry: add a mesh object, or enable an object for "
            "rendering (Outliner ▸ camera icon), before rendering."
        )
    flat = zero_area_objects(tracer_scene.vertices, tracer_scene.triangles, tracer_scene.triangle_object,
                             tracer_scene.object_names)
    if flat and not points:
        raise PrismInputError(
            f"Scene '{scene_name}' has no visible geometry: {zero_area_sentence(flat)}, so no ray can hit them: "
            "give the mesh some size (Edit Mode: check for merged vertices and a zero Scale), or add a mesh."
        )
    world_lit = not tracer_scene.world.is_black()
    used = {int(i) for i in np.unique(tracer_scene.triangle_material)}
    for extra in (tracer_scene.points, tracer_scene.curves):
        if extra is not None and len(extra):
            used |= {int(i) for i in np.unique(extra.material)}
    emissive = any(_emits(tracer_scene.materials[i]) for i in used)
    if not (tracer_scene.lights or world_lit or emissive) and world_filtered_by:
        raise PrismInputError(
            f"Scene '{scene_name}' has no light (no light with power, no emissive material, and View Layer "
            f"'{world_filtered_by}' ▸ Filter ▸ Environment is off, so the world lights nothing, as in Cycles): "
            "turn Environment on or add a light, or the image would be black."
        )
    if not (tracer_scene.lights or world_lit or emissive):
        raise PrismInputError(
            f"Scene '{scene_name}' has no light (no light with power, no emissive material, a black world): "
            "add a light or give the world a colour, or the image would be black."
            + "".join(f" ({note})" for note in world_notes)
        )


def export_scene(depsgraph, warnings: list[str] | None = None, frame_set=None, camera: Camera | None = None,
                 motion: bool = True) -> Scene:
    """Build the tracer scene from an evaluated depsgraph.

    With Render ▸ Motion Blur on, the scene is evaluated again at the shutter's times through
    ``frame_set(frame, subframe)`` (a render passes its engine's, which re-evaluates ``depsgraph``; default:
    the scene's own ``frame_set``) and set back to its frame afterwards (``motion``); with the Vector pass
    on and motion blur off, at the previous and next frames (``vector_pass``).

    ``camera``: the camera to render from instead of the scene's (a bake's, which only places the render's
    origin: a scene without a camera bakes); ``motion`` False: neither motion blur nor the Vector pass's
    other frames (a bake's surface points are where the objects are at the frame).

    Raises ``PrismInputError`` (naming the object and the fix) for scenes that
    cannot render: no camera, unsupported camera, NaN geometry, unknown glass, ...
    Inputs Prism ignores are appended to ``warnings`` (one message each).
    """
    scene = depsgraph.scene
    missing = missing_libraries(scene)
    if warnings is not None:
        warnings.extend(unrendered_setting_warnings(scene, depsgraph.view_layer))
        warnings.extend(simplify_warnings(scene, depsgraph))
        warnings.extend(f"Scene '{scene.name}': {library.sentence()}." for library in missing)
    if camera is None:
        camera = export_camera(scene, depsgraph, warnings)
    geometry = export_meshes(depsgraph, warnings)
    tracer_scene = Scene(
        vertices=geometry.vertices,
        triangles=geometry.triangles,
        triangle_material=geometry.triangle_material,
        triangle_object=geometry.triangle_object,
        object_names=geometry.object_names,
        object_light_groups=geometry.object_light_groups,
        corner_normals=geometry.corner_normals,
        triangle_flat=geometry.triangle_flat,
        triangle_terminator=geometry.triangle_terminator,
        surface=geometry.surface,
        points=geometry.points,
        curves=geometry.curves,
        object_flags=geometry.object_flags,
        materials=geometry.materials,
        camera=camera,
        lights=export_lights(depsgraph, warnings),
        world=export_world(depsgraph.scene_eval, warnings, depsgraph.view_layer),  # its world: evaluated
    )
    tracer_scene.world.light_group = scene.world.lightgroup if scene.world is not None else ""
    tracer_scene.light_links = export_light_links(depsgraph, geometry.object_names, warnings)
    tracer_scene.data_passes = export_data_passes(scene, geometry, depsgraph.view_layer)
    if motion:
        frame_set = frame_set or (lambda f, s: scene.frame_set(f, subframe=s))
        meshes_again = lambda evaluated: export_meshes(evaluated, None)  # noqa: E731
        export_motion(scene, depsgraph, tracer_scene, frame_set, meshes_again, warnings if warnings is not None else [],
                      geometry)
        export_vector_pass(scene, depsgraph, tracer_scene, frame_set, meshes_again,
                           warnings if warnings is not None else [], geometry)
    tracer_scene.validate()
    if warnings is not None:
        from .nested_media import nested_media_warnings

        warnings.extend(nested_media_warnings(tracer_scene))
    filtered_by = depsgraph.view_layer.name if scene.world is not None and not depsgraph.view_layer.use_sky else ""
    world_notes = [w for w in warnings or () if scene.world is not None and w.startswith(f"World '{scene.world.name}'")]
    _check_something_to_see(scene.name, tracer_scene, missing, filtered_by, world_notes,
                            layer_filter(depsgraph.view_layer))
    return tracer_scene
