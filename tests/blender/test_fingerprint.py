"""The fingerprint a chunk carries: it changes with what changes the image, part by part, and with
nothing else (names, thread counts, where a lens file is mounted)."""

from __future__ import annotations

import copy
import dataclasses

import numpy as np

from engine.render.fingerprint import differing_parts, render_fingerprint
from engine.tracer.lens.catalogue import LENS_DIRECTORY
from engine.tracer.scene import Camera, Light, Material, Scene
from engine.tracer.settings import RenderSettings


def _scene(lens_file=None) -> Scene:
    return Scene(
        vertices=np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
        triangles=np.array([[0, 1, 2]], np.int32),
        triangle_material=np.zeros(1, np.int32),
        materials=[Material(name="Grey")],
        camera=Camera(name="Camera", camera_to_world=np.eye(4), resolution=(8, 8), lens_file=lens_file,
                      model="real_lens" if lens_file else "pinhole"),
        lights=[Light(name="Bulb", kind="point", position=np.array([0.0, 0.0, 2.0]), power_w=10.0)],
        object_names=["Card"],
        triangle_object=np.zeros(1, np.int32),
    )


def test_names_threads_samples_and_seed_leave_it_unchanged():
    scene, settings = _scene(), RenderSettings(samples=4, seed=1, threads=1)
    renamed = copy.deepcopy(scene)
    renamed.materials[0].name, renamed.lights[0].name, renamed.object_names = "Other", "Lamp", ["Renamed"]
    other_run = dataclasses.replace(settings, samples=64, seed=9, threads=8)
    assert render_fingerprint(renamed, other_run, 1) == render_fingerprint(scene, settings, 1.0)


def test_each_part_changes_with_what_it_holds():
    scene, settings = _scene(), RenderSettings()
    base = render_fingerprint(scene, settings, 3)
    changes = {
        "geometry": lambda s, r: s.vertices.__setitem__((1, 0), 1.0 + 1e-12),
        "materials": lambda s, r: setattr(s.materials[0], "roughness", 0.5),
        "lights": lambda s, r: setattr(s.lights[0], "power_w", 11.0),
        "camera": lambda s, r: setattr(s.camera, "focal_length_mm", 35.0),
        "world": lambda s, r: setattr(s.world, "strength", 0.5),
        "settings": lambda s, r: setattr(r, "max_bounces", 2),
    }
    for part, change in changes.items():
        changed_scene, changed_settings = copy.deepcopy(scene), copy.deepcopy(settings)
        change(changed_scene, changed_settings)
        assert differing_parts(base, render_fingerprint(changed_scene, changed_settings, 3)) == [part]


def test_the_frame_is_a_part_of_its_own_written_as_its_number():
    scene, settings = _scene(), RenderSettings()
    frame_1, frame_2 = render_fingerprint(scene, settings, 1), render_fingerprint(scene, settings, 2)
    assert differing_parts(frame_1, frame_2) == ["frame"]  # the same scene state, another frame
    assert (frame_1["frame"], frame_2["frame"]) == ("1", "2")
    assert render_fingerprint(scene, settings, -7.5)["frame"] == "-7.5"  # with a subframe


def test_a_lens_file_counts_by_its_content_not_its_path(tmp_path):
    original = LENS_DIRECTORY / "double_gauss_50mm.lens"
    mounted = tmp_path / "elsewhere.lens"
    mounted.write_bytes(original.read_bytes())
    settings = RenderSettings()
    assert render_fingerprint(_scene(str(original)), settings, 1) == render_fingerprint(_scene(str(mounted)), settings, 1)
    mounted.write_bytes(original.read_bytes().replace(b"thickness_mm = 3.76", b"thickness_mm = 3.80"))
    assert differing_parts(render_fingerprint(_scene(str(original)), settings, 1),
                           render_fingerprint(_scene(str(mounted)), settings, 1)) == ["camera"]


def test_what_beside_the_triangles_changes_the_image_changes_the_geometry_part():
    """Ray visibility, flat shading, a UV map, a light group, a pass's input and motion blur's time steps each change
    the geometry part alone; a scene that holds them at their defaults hashes as one without them."""
    from engine.tracer.data_passes import DataPassInputs
    from engine.tracer.motion import Motion
    from engine.tracer.scene import SurfaceAttributes

    scene, settings = _scene(), RenderSettings()
    base = render_fingerprint(scene, settings, 1)
    defaults = copy.deepcopy(scene)
    defaults.object_light_groups, defaults.data_passes = [], DataPassInputs()
    assert render_fingerprint(defaults, settings, 1) == base
    uv = np.zeros((1, 1, 3, 2), np.float32)
    changes = {
        "object_flags": np.array([3], np.uint8),
        "triangle_flat": np.array([True]),
        "surface": SurfaceAttributes(uvs=uv),
        "object_light_groups": ["Key"],
        "data_passes": DataPassInputs(mist_depth_m=10.0),
        "motion": Motion(np.stack([scene.vertices, scene.vertices + [0.1, 0.0, 0.0]])),
    }
    for name, value in changes.items():
        changed = copy.deepcopy(scene)
        setattr(changed, name, value)
        assert differing_parts(base, render_fingerprint(changed, settings, 1)) == ["geometry"], name
    moved = copy.deepcopy(scene)
    moved.motion = Motion(np.stack([scene.vertices, scene.vertices + [0.2, 0.0, 0.0]]))
    assert differing_parts(render_fingerprint(moved, settings, 1),
                           render_fingerprint(dataclasses.replace(scene, motion=changes["motion"]), settings, 1)) == [
        "geometry"]
    uv[0, 0, 0, 0] = 0.5  # another UV map
    changed = copy.deepcopy(scene)
    changed.surface = SurfaceAttributes(uvs=uv)
    other = copy.deepcopy(scene)
    other.surface = SurfaceAttributes(uvs=np.zeros((1, 1, 3, 2), np.float32))
    assert differing_parts(render_fingerprint(changed, settings, 1), render_fingerprint(other, settings, 1)) == [
        "geometry"]
