"""Scene oddities answered at export, by name: a scene whose only mesh has no area is refused like an
empty one; an area light of Spread 0 and a camera whose Clip Start lies beyond its Clip End are rendered
with a warning saying what is rendered instead."""

from __future__ import annotations

import importlib

import bpy

from helpers.batch import run_batch
from helpers.bpy_scenes import add_camera, add_plane, add_point_light


def _export(prism_addon, warnings=None):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export, export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)


def _sliver(name="Sliver"):
    """A mesh of 2 triangles whose corners all lie on one line."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0)], [], [(0, 1, 2), (1, 2, 3)])
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def test_a_scene_of_zero_area_triangles_is_refused_naming_the_object(prism_addon, fresh_scene, tmp_path, capsys,
                                                                      bad_input):
    _sliver()
    flat = add_plane("Flattened", 2.0)
    flat.scale = (1.0, 0.0, 1.0)  # a plane squashed to a line
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    add_camera((0.0, -3.0, 1.0), (1.2, 0.0, 0.0), resolution=(8, 6))
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert (status, line) == (1, "Prism: error: Scene 'Scene' has no visible geometry: all 2 triangles of 'Sliver', "
                                 "all 2 triangles of 'Flattened' have zero area (their corners lie on one line or one "
                                 "point), so no ray can hit them: give the mesh some size (Edit Mode: check for merged "
                                 "vertices and a zero Scale), or add a mesh.")
    bad_input("a scene whose only meshes have zero-area triangles", status, line)
    add_plane("Floor", 4.0, location=(0.0, 0.0, -1.0))  # one real triangle is enough
    _, scene = _export(prism_addon)
    assert scene.triangle_count == 6


def test_an_area_light_of_spread_0_warns_what_is_rendered(prism_addon, fresh_scene):
    add_plane("Floor", 4.0)
    data = bpy.data.lights.new("Panel", "AREA")
    data.energy, data.size, data.spread = 50.0, 0.5, 0.0
    panel = bpy.data.objects.new("Panel", data)
    panel.location = (0.0, 0.0, 1.0)
    bpy.context.scene.collection.objects.link(panel)
    add_camera((0.0, -3.0, 1.0), (1.2, 0.0, 0.0), resolution=(8, 6))
    warnings: list[str] = []
    _, scene = _export(prism_addon, warnings)
    assert scene.lights[0].spread_rad == 0.0
    assert ("Light 'Panel': Spread 0° makes a collimated beam (Cycles lights only the patch straight in front of "
            "the light); Prism renders it with a Spread of 0.11°, the narrowest it samples, which lights the same "
            "patch but so noisily that it looks black at ordinary sample counts: set Spread to 1° or more (Object "
            "Data ▸ Light ▸ Spread).") in warnings
    data.spread = 0.02  # about 1.1°: sampled as it is, no warning
    warnings.clear()
    _export(prism_addon, warnings)
    assert not [w for w in warnings if "Spread" in w]


def test_clip_start_beyond_clip_end_says_only_the_world_is_seen(prism_addon, fresh_scene, bad_input):
    add_plane("Floor", 4.0)
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    camera = add_camera((0.0, -3.0, 1.0), (1.2, 0.0, 0.0), resolution=(8, 6))
    camera.data.clip_start, camera.data.clip_end = 20.0, 10.0
    warnings: list[str] = []
    _export(prism_addon, warnings)
    clip = [w for w in warnings if "Clip Start" in w]
    assert len(clip) == 1 and clip[0].startswith("Camera 'Camera': Clip Start (20 m) lies beyond Clip End (10 m), so "
                                                 "the camera sees no geometry, only the world (as in Cycles)")
    bad_input("Camera Clip Start 20 m beyond Clip End 10 m (a warning at export; the world is rendered, as Cycles)",
              0, clip[0])
