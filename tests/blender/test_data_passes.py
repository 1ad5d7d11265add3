"""Data passes through Blender (Mist, UV, IndexOB, IndexMA, AO): Blender's names and channels in the
multilayer EXR, and the values Cycles writes for the same scene."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from blender.test_passes import _cycles, _render_layers, _switch_on
from helpers.bpy_scenes import build_lit_card_scene

SWITCHES = ("mist", "uv", "object_index", "material_index", "ambient_occlusion")


@pytest.fixture
def data_scene(fresh_scene):
    build_lit_card_scene(resolution=(24, 16))
    scene = fresh_scene
    scene.render.use_compositing = False
    scene.prism.samples = scene.prism.samples_per_pass = 64
    scene.world = bpy.data.worlds.new("World")
    scene.world.color = (0.05, 0.05, 0.05)
    scene.world.mist_settings.start, scene.world.mist_settings.depth = 2.0, 3.0
    scene.world.mist_settings.falloff = "LINEAR"
    scene.world.light_settings.distance = 0.6
    bpy.data.objects["Card"].pass_index = 5
    bpy.data.objects["Floor"].pass_index = 2
    bpy.data.objects["Card"].active_material.pass_index = 9
    card = bpy.data.objects["Card"].data  # a UV map on the card only: the floor's UV pass is 0, 0, 0
    card.uv_layers.new(name="other").data.foreach_set("uv", [0.5] * 8)
    card.uv_layers.new(name="render").data.foreach_set("uv", [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0])
    card.uv_layers["render"].active_render = True
    _switch_on(scene, SWITCHES)
    return scene


def _inside(image):
    """Pixels whose four neighbours hold the same value (not at an edge between surfaces)."""
    same = np.zeros(image.shape[:2], bool)
    same[1:-1, 1:-1] = np.all([np.abs(image[1:-1, 1:-1] - np.roll(image, s, a)[1:-1, 1:-1]).max(-1) < 1e-6
                               for s in (1, -1) for a in (0, 1)], axis=0)
    return same


def test_data_passes_match_cycles(prism_addon, data_scene, tmp_path):
    prism = _render_layers(prism_addon, data_scene, tmp_path / "prism.exr")
    assert {"Mist", "UV", "IndexOB", "IndexMA", "AO"} <= set(prism)
    assert prism["Mist"].shape[-1] == 1 and prism["UV"].shape[-1] == 3 and prism["IndexOB"].shape[-1] == 1
    _cycles(data_scene)
    cycles = _render_layers(prism_addon, data_scene, tmp_path / "cycles.exr", engine="CYCLES")
    inside = _inside(cycles["IndexOB"]) & _inside(cycles["IndexMA"])
    assert inside.mean() > 0.5
    for name in ("IndexOB", "IndexMA"):
        assert set(np.unique(prism[name]).tolist()) <= {0.0, 2.0, 5.0, 9.0}, name  # ids, never blends
        assert np.array_equal(prism[name][inside], cycles[name][inside]), name
    assert {2.0, 5.0} <= set(np.unique(prism["IndexOB"]).tolist())
    mist = np.abs(prism["Mist"] - cycles["Mist"])[inside]
    assert np.percentile(mist, 95) < 0.005 and mist.max() < 0.02, (np.percentile(mist, 95), mist.max())
    # Channels A, U, V (the EXR sorts them). Cycles' Index passes hold sample 0 only, so a few pixels they
    # call inside touch an edge, where a sample or two of 64 (1/64 each) fall on the other surface.
    uv = np.abs(prism["UV"] - cycles["UV"])[inside]
    assert np.percentile(uv, 95) < 0.005 and uv.max() < 0.05, (np.percentile(uv, 95), uv.max())
    card = prism["UV"][..., 0] == 1.0  # A: samples all on the card; its render map (not "other", 0.5) spans 0-1
    assert card.sum() > 4 and prism["UV"][..., 1][card].max() > 0.7 and prism["UV"][..., 1][card].min() < 0.3
    # AO: 64 cosine rays a pixel; the floor under the card (0.5 m below, AO distance 0.6 m) is partly occluded.
    ao_p, ao_c = prism["AO"][..., 0][inside], cycles["AO"][..., 0][inside]
    assert ao_c.min() < 0.8
    print("measured: mist", mist.max(), "uv", uv.max(), "AO means", ao_p.mean(), ao_c.mean())
    assert abs(ao_p.mean() - ao_c.mean()) < 0.01, (ao_p.mean(), ao_c.mean())
    assert np.abs(ao_p - ao_c).max() < 0.25  # per pixel: 64 Bernoulli samples each


def test_vector_and_cryptomatte_are_not_warned(prism_addon, fresh_scene):
    from importlib import import_module

    warnings = import_module(f"{prism_addon.__name__}.engine.export.unrendered_settings")
    layer = fresh_scene.view_layers[0]
    layer.use_pass_vector = layer.use_pass_cryptomatte_object = layer.use_pass_cryptomatte_asset = True
    messages = warnings.unrendered_setting_warnings(fresh_scene, layer)
    assert not any("Vector pass" in m for m in messages)  # written (tests/blender/test_vector_pass.py)
    assert not any("Crypto" in m for m in messages)  # written (tests/blender/test_cryptomatte.py)


def test_pass_index_follows_each_object_and_instance(prism_addon, fresh_scene):
    """Object ▸ Pass Index per triangle, for objects sharing a mesh and for a collection's instances
    (each instance carries its object's index, as Cycles), read only when IndexOB is on."""
    from importlib import import_module

    from helpers.bpy_scenes import add_camera, add_plane, add_point_light

    export = import_module(f"{prism_addon.__name__}.engine.export")
    a = add_plane("A", 1.0)
    b = bpy.data.objects.new("B", a.data)  # the same mesh
    fresh_scene.collection.objects.link(b)
    a.pass_index, b.pass_index = 4, 6
    group = bpy.data.collections.new("Group")
    c = bpy.data.objects.new("C", a.data)
    c.pass_index = 8
    group.objects.link(c)
    for x in (3.0, 6.0):
        empty = bpy.data.objects.new(f"Instancer {x}", None)
        empty.instance_type, empty.instance_collection = "COLLECTION", group
        empty.location.x = x
        fresh_scene.collection.objects.link(empty)
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    add_camera((0.0, -3.0, 2.5), (0.9, 0.0, 0.0), resolution=(8, 8))
    depsgraph = bpy.context.evaluated_depsgraph_get()
    assert export.export_scene(depsgraph).data_passes.object_pass_index is None  # pass off: nothing read
    fresh_scene.view_layers[0].use_pass_object_index = True
    depsgraph = bpy.context.evaluated_depsgraph_get()
    scene = export.export_scene(depsgraph)
    names = [scene.object_names[o] for o in scene.triangle_object]
    index = scene.data_passes.object_pass_index
    assert len(index) == len(names) == 8  # A, B and two instances of C, two triangles each
    expected = {"A": 4.0, "B": 6.0, "C": 8.0}
    assert [float(v) for v in index] == [expected[n] for n in names]


def test_cut_out_data_passes_match_cycles(prism_addon, data_scene, tmp_path):
    """A cut-out card (Principled Alpha): Cycles writes the data passes of the first surface whose alpha reaches View
    Layer ▸ Alpha Threshold, and blends Mist and AO by alpha; Prism the same, from one scene."""
    card = bpy.data.objects["Card"].active_material.node_tree.nodes["Principled BSDF"].inputs["Alpha"]
    layer = data_scene.view_layers[0]

    def both(alpha, threshold, name):
        card.default_value, layer.pass_alpha_threshold = alpha, threshold
        prism = _render_layers(prism_addon, data_scene, tmp_path / f"prism_{name}.exr")
        _cycles(data_scene)
        cycles = _render_layers(prism_addon, data_scene, tmp_path / f"cycles_{name}.exr", engine="CYCLES")
        data_scene.render.engine = "PRISM"
        return prism, cycles

    # Alpha 0.25 above the threshold 0.2: every sample writes the card's UV map (A = 1), in both engines.
    prism, cycles = both(0.25, 0.2, "above")
    on_card = (cycles["UV"][..., 0] == 1.0) & _inside(cycles["UV"][..., :1])  # A = 1 here and around
    assert on_card.sum() >= 4 and np.all(prism["UV"][..., 0][on_card] == 1.0)  # the card's 6 x 3 pixels but its rim
    # Alpha 0.25 below the default threshold 0.5: the samples that go through write the floor's (no UV map: 0), the
    # others none; Mist and AO blend the card and the floor by alpha.
    prism, cycles = both(0.25, 0.5, "below")
    assert np.all(prism["UV"][on_card] == 0.0) and np.all(cycles["UV"][on_card] == 0.0)
    for name, bound in (("Mist", 0.01), ("AO", 0.03)):
        p, c = prism[name][..., 0][on_card].mean(), cycles[name][..., 0][on_card].mean()
        print("measured:", name, p, c)
        assert abs(p - c) < bound, (name, p, c)
    # Alpha 0: the card is not there for the data passes, its ids neither.
    prism, cycles = both(0.0, 0.5, "clear")
    for name in ("IndexOB", "IndexMA"):
        assert np.array_equal(prism[name][on_card], cycles[name][on_card]), name
        assert np.all(prism[name][on_card] == (2.0 if name == "IndexOB" else 0.0)), name
