"""Cryptomatte through Blender, against Cycles rendering the same scene: the passes' ids and coverages,
the metadata the compositor reads (layer key, name, hash, conversion, manifest), and the compositor's
Cryptomatte node picking the same matte from either render."""

from __future__ import annotations

import json

import bpy
import numpy as np
import pytest

from blender.test_passes import _cycles, _render_layers

KINDS = ("Object", "Material", "Asset")


@pytest.fixture
def crypto_scene(fresh_scene):
    """'Plane A' (no material: Cycles' default_surface) under the empty 'Root' (its asset), 'Plane B'
    (material 'Red') beside it, seen from above with background around, 24 x 16 pixels."""
    scene = fresh_scene
    mesh = bpy.data.meshes.new("Square")
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    root = bpy.data.objects.new("Root", None)
    a = bpy.data.objects.new("Plane A", mesh)
    a.parent = root
    b = bpy.data.objects.new("Plane B", mesh.copy())
    b.location = (2.3, 0.3, 0.0)
    b.rotation_euler.z = 0.4  # slanted edges: coverages between 0 and 1 along them
    b.data.materials.append(bpy.data.materials.new("Red"))
    lamp = bpy.data.objects.new("Lamp", bpy.data.lights.new("Lamp", "POINT"))
    lamp.location, lamp.data.energy = (1.0, 0.0, 3.0), 200.0
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (1.2, 0.0, 7.0)
    for obj in (root, a, b, lamp, camera):
        scene.collection.objects.link(obj)
    scene.camera = camera
    scene.world = bpy.data.worlds.new("Sky")
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 24, 16, 100
    scene.render.use_compositing = False
    scene.prism.samples = scene.prism.samples_per_pass = 64
    scene.prism.pixel_filter = "BOX"
    layer = scene.view_layers[0]
    layer.use_pass_cryptomatte_object = layer.use_pass_cryptomatte_material = True
    layer.use_pass_cryptomatte_asset = True
    _cycles(scene)
    return scene


def _metadata(prism_addon, path) -> dict[str, str]:
    from importlib import import_module

    oiio = import_module(f"{prism_addon.__name__}.engine.output.openimageio").import_openimageio()
    image = oiio.ImageInput.open(str(path))
    fields = {a.name: a.value for a in image.spec().extra_attribs if a.name.startswith("cryptomatte/")}
    image.close()
    return fields


def _ranks(layers, kind) -> np.ndarray:
    """[H, W, ranks, 2] (id, coverage) of a kind (its passes' channels r, g, b, a in order)."""
    passes = sorted(name for name in layers if name.startswith("Crypto" + kind))
    rgba = np.concatenate([layers[name] for name in passes], -1)
    return rgba.reshape(*rgba.shape[:2], -1, 2)


def _coverage_of(ranks, matte_id) -> np.ndarray:
    """The matte of one id: its coverage in whichever rank holds it (what the compositor's node sums)."""
    return np.where(ranks[..., 0] == matte_id, ranks[..., 1], 0.0).sum(-1)


def _float_id(prism_addon, name):
    from importlib import import_module

    crypto = import_module(f"{prism_addon.__name__}.engine.tracer.cryptomatte")
    return float(crypto.hash_to_float(crypto.name_hashes([name]))[0])


def test_cryptomatte_matches_cycles(prism_addon, crypto_scene, tmp_path):
    prism = _render_layers(prism_addon, crypto_scene, tmp_path / "prism.exr")
    prism_meta = _metadata(prism_addon, tmp_path / "prism.exr")
    cycles = _render_layers(prism_addon, crypto_scene, tmp_path / "cycles.exr", engine="CYCLES")
    cycles_meta = _metadata(prism_addon, tmp_path / "cycles.exr")
    for kind in KINDS:
        assert sorted(n for n in prism if n.startswith("Crypto" + kind)) == [f"Crypto{kind}0{i}" for i in range(3)]
    # metadata: the same keys, name, hash and conversion; the manifest lists what Prism renders with
    # Cycles' hashes (Cycles adds its lights, world and built-in shaders, which no pixel shows)
    assert {k.rsplit("/", 1)[0] for k in prism_meta} == {k.rsplit("/", 1)[0] for k in cycles_meta}
    assert len(prism_meta) == 12

    for key, value in prism_meta.items():
        if key.endswith("/manifest"):
            mine, theirs = json.loads(value), json.loads(cycles_meta[key])
            assert mine.items() <= theirs.items(), (key, mine, theirs)
        else:
            assert value == cycles_meta[key], key
    manifests = {prism_meta[k.replace("manifest", "name")]: json.loads(v) for k, v in prism_meta.items()
                 if k.endswith("manifest")}
    assert manifests["ViewLayer.CryptoObject"].keys() == {"Plane A", "Plane B"}
    assert manifests["ViewLayer.CryptoAsset"].keys() == {"Root", "Plane B"}
    assert manifests["ViewLayer.CryptoMaterial"].keys() == {"default_surface", "Red"}
    for kind in KINDS:
        mine, theirs = _ranks(prism, kind), _ranks(cycles, kind)
        assert np.all(np.diff(mine[..., 1], axis=-1) <= 0.0)  # ranks sorted by coverage
        inside = theirs[..., 0, 1] == 1.0  # every Cycles sample on one surface
        assert 0.2 < inside.mean() < 0.8
        assert np.array_equal(mine[..., 0, 0][inside], theirs[..., 0, 0][inside]), kind
        assert np.all(mine[..., 0, 1][inside & (mine[..., 0, 1] < 1.0)] > 0.9)  # at most an edge sample or so
        ids = {float(i) for i in np.unique(theirs[..., 0]) if i != 0.0}
        assert ids == {float(i) for i in np.unique(mine[..., 0]) if i != 0.0}, kind
        for matte_id in ids:
            a, b = _coverage_of(mine, matte_id), _coverage_of(theirs, matte_id)
            edge = (b > 0.0) & (b < 1.0)
            print(kind, matte_id, "edge pixels", edge.sum(), "max |Δcoverage|", np.abs(a - b).max(),
                  "mean", np.abs(a - b)[edge].mean())
            assert edge.sum() > 4 and np.abs(a - b).max() < 0.2 and np.abs(a - b)[edge].mean() < 0.05
    objects = _ranks(prism, "Object")
    assert {_float_id(prism_addon, "Plane A"), _float_id(prism_addon, "Plane B")} <= set(np.unique(objects[..., 0]))
    background = _ranks(cycles, "Object")[..., 0, 1] == 0.0
    assert background.any() and np.all(objects[background][:, 0, 1] < 0.1)


def _composited_matte(scene, path, engine, matte_names) -> np.ndarray:
    """The compositor's Cryptomatte node (source Render, layer CryptoObject, matte of ``matte_names``)
    fed to the Composite output, rendered by ``engine``: the matte [H, W], row 0 on top."""
    from helpers.cycles import read_exr_rgba

    scene.render.engine = engine
    scene.use_nodes = True
    tree = scene.node_tree
    for node in list(tree.nodes):
        tree.nodes.remove(node)
    crypto = tree.nodes.new("CompositorNodeCryptomatteV2")
    crypto.source, crypto.scene = "RENDER", scene
    try:  # the layers on offer: after a render, its result's "<view layer>.Crypto…"; before, the switches'
        crypto.layer_name = f"{scene.view_layers[0].name}.CryptoObject"
    except TypeError:
        crypto.layer_name = "CryptoObject"
    crypto.matte_id = matte_names
    tree.links.new(crypto.outputs["Matte"], tree.nodes.new("CompositorNodeComposite").inputs["Image"])
    scene.render.use_compositing = True
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.color_mode = "OPEN_EXR", "32", "RGBA"
    scene.render.filepath, scene.render.use_file_extension = str(path), False
    bpy.ops.render.render(write_still=True)
    return read_exr_rgba(str(path))[..., 0]


def test_compositor_cryptomatte_node_picks_the_same_matte(prism_addon, crypto_scene, tmp_path):
    prism = _composited_matte(crypto_scene, tmp_path / "prism.exr", "PRISM", "Plane B")
    cycles = _composited_matte(crypto_scene, tmp_path / "cycles.exr", "CYCLES", "Plane B")
    inside, outside = cycles == 1.0, cycles == 0.0
    assert 0.1 < inside.mean() < 0.6 and outside.mean() > 0.3
    assert np.all(prism[inside & (prism < 1.0)] > 0.9) and np.all(prism[outside & (prism > 0.0)] < 0.1)
    print("matte |Δ| max", np.abs(prism - cycles).max(), "mean", np.abs(prism - cycles).mean())
    assert np.abs(prism - cycles).max() < 0.2 and np.abs(prism - cycles).mean() < 0.01
    both = _composited_matte(crypto_scene, tmp_path / "both.exr", "PRISM", "Plane A, Plane B")
    assert np.all(both >= prism) and both.max() <= 1.0 + 1e-6 and (both == 1.0).sum() > (prism == 1.0).sum()


def test_batch_script_writes_the_passes_and_metadata_into_the_exr(prism_addon, crypto_scene, tmp_path):
    from importlib import import_module

    from blender.test_batch_render import run_render_script
    from blender.test_passes import _read_layers

    crypto_scene.render.engine = "PRISM"
    crypto_scene.view_layers[0].pass_cryptomatte_depth = 2  # one pass a kind
    blend = tmp_path / "crypto.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    completed = run_render_script(blend, "--samples", 4, "--output", tmp_path / "out.exr")
    assert completed.returncode == 0, completed.stderr
    layers = _read_layers(prism_addon, tmp_path / "out.exr")
    assert {"CryptoObject00", "CryptoMaterial00", "CryptoAsset00"} <= set(layers) and "CryptoObject01" not in layers
    fields = _metadata(prism_addon, tmp_path / "out.exr")
    metadata = import_module(f"{prism_addon.__name__}.engine.render.cryptomatte_metadata")
    key = metadata.layer_key("ViewLayer.CryptoObject")
    assert key == "cryptomatte/542cafa"  # Blender's key for this layer name (as Cycles writes it)
    assert fields[key + "/name"] == "ViewLayer.CryptoObject" and fields[key + "/hash"] == "MurmurHash3_32"
    assert fields[key + "/conversion"] == "uint32_to_float32"
    assert json.loads(fields[key + "/manifest"]) == {"Plane A": "c6a3fefd", "Plane B": "a53d11e4"}  # Cycles' hashes
    assert len(fields) == 12


def test_instances_and_parents_are_named_as_cycles_names_them(prism_addon, crypto_scene, tmp_path):
    """Two instances of a collection holding 'Child' under 'Parent': every instance is 'Child', its asset
    'Parent' (the instanced object's own topmost parent, not the instancer), as in Cycles' passes."""
    group = bpy.data.collections.new("Group")
    parent = bpy.data.objects.new("Parent", None)
    child = bpy.data.objects.new("Child", bpy.data.objects["Plane A"].data)
    child.parent, child.scale = parent, (0.4, 0.4, 1.0)
    for obj in (parent, child):
        group.objects.link(obj)
    for x in (-0.6, 3.0):
        instancer = bpy.data.objects.new(f"Instancer {x}", None)
        instancer.instance_type, instancer.instance_collection = "COLLECTION", group
        instancer.location = (x, -1.2, 0.5)
        crypto_scene.collection.objects.link(instancer)
    prism = _render_layers(prism_addon, crypto_scene, tmp_path / "prism.exr")
    prism_meta = _metadata(prism_addon, tmp_path / "prism.exr")
    cycles = _render_layers(prism_addon, crypto_scene, tmp_path / "cycles.exr", engine="CYCLES")
    cycles_meta = _metadata(prism_addon, tmp_path / "cycles.exr")
    manifests = {prism_meta[k[:-len("manifest")] + "name"]: (json.loads(v), json.loads(cycles_meta[k]))
                 for k, v in prism_meta.items() if k.endswith("/manifest")}
    mine, theirs = manifests["ViewLayer.CryptoObject"]
    assert mine.keys() == {"Plane A", "Plane B", "Child"} and mine.items() <= theirs.items()
    mine, theirs = manifests["ViewLayer.CryptoAsset"]
    assert mine.keys() == {"Root", "Plane B", "Parent"} and mine.items() <= theirs.items()
    for kind, name in (("Object", "Child"), ("Asset", "Parent")):
        matte_id = _float_id(prism_addon, name)
        a, b = _coverage_of(_ranks(prism, kind), matte_id), _coverage_of(_ranks(cycles, kind), matte_id)
        assert (b == 1.0).sum() >= 4 and np.all(a[b == 1.0] > 0.9) and np.all(a[b == 0.0] < 0.1), kind


def _square(name, location, scale, material):
    obj = bpy.data.objects.new(name, bpy.data.meshes.new(name))
    obj.data.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    obj.data.materials.append(material)
    obj.location, obj.scale = location, (scale, scale, 1.0)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def test_cut_outs_share_their_pixels_with_what_is_behind_them_as_in_cycles(prism_addon, crypto_scene, tmp_path):
    """'Veil' (Principled Alpha 0.6) over 'Plane B' and 'Filter' (a grey Transparent BSDF alone, 50 %) over
    'Plane A': Cycles writes a cut-out with its opacity and goes on with the rest (0.6 / 0.4, 0.5 / 0.5);
    Prism's paths take one lobe each and carry the weight, so the coverages agree in expectation."""
    veil = bpy.data.materials.new("Half")
    veil.use_nodes = True
    veil.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.6
    grey = bpy.data.materials.new("Grey filter")
    grey.use_nodes = True
    nodes = grey.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    transparent = nodes.new("ShaderNodeBsdfTransparent")
    transparent.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
    grey.node_tree.links.new(transparent.outputs[0], nodes["Material Output"].inputs["Surface"])
    _square("Veil", (2.3, 0.3, 0.5), 0.6, veil)
    _square("Filter", (0.0, 0.0, 0.5), 0.6, grey)
    crypto_scene.prism.samples = crypto_scene.prism.samples_per_pass = crypto_scene.cycles.samples = 256
    prism = _ranks(_render_layers(prism_addon, crypto_scene, tmp_path / "prism.exr"), "Object")
    cycles = _ranks(_render_layers(prism_addon, crypto_scene, tmp_path / "cycles.exr", engine="CYCLES"), "Object")
    for front, back, opacity in (("Veil", "Plane B", 0.6), ("Filter", "Plane A", 0.5)):
        front_id, back_id = _float_id(prism_addon, front), _float_id(prism_addon, back)
        over = ((np.abs(_coverage_of(cycles, front_id) - opacity) < 1e-3)
                & (np.abs(_coverage_of(cycles, back_id) - (1.0 - opacity)) < 1e-3))
        assert over.sum() >= 9, front
        for matte_id, expected in ((front_id, opacity), (back_id, 1.0 - opacity)):
            coverage = _coverage_of(prism, matte_id)[over]
            print("cut-out", front, expected, "Prism mean", coverage.mean(), "min", coverage.min(),
                  "max", coverage.max())
            assert abs(coverage.mean() - expected) < 0.02 and np.abs(coverage - expected).max() < 0.1, front


def test_passes_follow_the_view_layers_switches_and_levels(prism_addon, fresh_scene):
    """What Prism registers (the compositor's Render Layers sockets, the Render Result's passes): Cycles'
    names, four channels r, g, b, a, Levels made even (two ranks a pass), nothing when off."""
    from importlib import import_module

    result_passes = import_module(f"{prism_addon.__name__}.engine.render.result_passes")
    layer = fresh_scene.view_layers[0]
    assert not [p for p in result_passes.enabled_passes(fresh_scene, layer) if p[0].startswith("Crypto")]
    layer.use_pass_cryptomatte_material = True
    for levels, passes in ((6, 3), (3, 2), (2, 1), (16, 8)):
        layer.pass_cryptomatte_depth = levels
        crypto = [p for p in result_passes.enabled_passes(fresh_scene, layer) if p[0].startswith("Crypto")]
        assert crypto == [(f"CryptoMaterial{i:02d}", 4, "rgba", "COLOR") for i in range(passes)], levels
