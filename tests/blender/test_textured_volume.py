"""A mesh volume whose Density is driven by nodes (a gradient, a Noise Texture) is baked onto a grid over the
mesh (``tracer.media.baked_density``) and rendered as Cycles renders it: the baked voxels hold the node
tree's value at their centres (Generated coordinates of a turned, scaled cube), an absorbing gradient cube
transmits the background as the closed form exp(-∫ density) per pixel column, and a smoke cube of Noise
Texture density matches Cycles 4.5 in absolute light. A Density that reads the surface or the ray (Normal)
cannot be baked and is warned."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.cycles import compare_mean_luminance, luminance, render_prism_rgba
from helpers.node_scenes import black_world, camera, glow_material, material, node


def _gradient_material(name, k, axis="X", shader="ShaderNodeVolumeAbsorption", **inputs):
    """A volume whose Density is k × the Generated coordinate ``axis`` (0 to 1 across the mesh's bounds)."""
    mat, nodes, link = material(name)
    coordinates = nodes.new("ShaderNodeTexCoord")
    separate = nodes.new("ShaderNodeSeparateXYZ")
    scale = node(nodes, "ShaderNodeMath", Value_001=k)
    scale.operation = "MULTIPLY"
    volume = node(nodes, shader, **inputs)
    link(coordinates.outputs["Generated"], separate.inputs[0])
    link(separate.outputs[axis], scale.inputs[0])
    link(scale.outputs[0], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    return mat


def _cube(name, mat, size=2.0, location=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0), scale=(1.0, 1.0, 1.0)):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.scale = scale
    obj.data.materials.append(mat)
    return obj


def test_a_node_driven_density_compiles_to_a_baked_field_and_a_normal_driven_one_is_warned(prism_addon, fresh_scene):
    nodes_module = importlib.import_module(f"{prism_addon.__name__}.engine.export.nodes")
    mat, nodes, link = material("Cloud")
    volume = node(nodes, "ShaderNodeVolumeScatter", Density=1.5)
    noise = nodes.new("ShaderNodeTexNoise")
    link(noise.outputs["Fac"], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    compiled = nodes_module.compile_material(mat, load_pixels=False)
    assert compiled.warnings == []
    assert compiled.medium.density_varies and compiled.medium.scatter[0][0] == 1.0
    assert compiled.shader.volume_density >= 0

    mat, nodes, link = material("Rim")
    volume = node(nodes, "ShaderNodeVolumeScatter", Density=1.5)
    geometry = nodes.new("ShaderNodeNewGeometry")
    separate = nodes.new("ShaderNodeSeparateXYZ")
    link(geometry.outputs["Normal"], separate.inputs[0])
    link(separate.outputs["Z"], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    compiled = nodes_module.compile_material(mat, load_pixels=False)
    assert not compiled.medium.density_varies and compiled.medium.scatter[0][0] == pytest.approx(1.5)
    assert compiled.shader.volume_density < 0
    assert any("Material 'Rim'" in w and "Density driven by nodes that read Normal" in w and "1.5" in w
               for w in compiled.warnings), compiled.warnings
    link(geometry.outputs["Backfacing"], volume.inputs["Density"])
    compiled = nodes_module.compile_material(mat, load_pixels=False)
    assert any("Density driven by nodes that read Backfacing, which" in w for w in compiled.warnings), compiled.warnings

    # an Attribute node is read at points: a Volume object's grid (inside a mesh, 0 as Cycles reads it there)
    slots_module = importlib.import_module(f"{prism_addon.__name__}.engine.export.nodes.slots")
    slots = slots_module.AttributeSlots(["UVMap"], ["Col"])
    read = nodes.new("ShaderNodeAttribute")
    read.attribute_name = "flame"
    link(read.outputs["Fac"], volume.inputs["Density"])
    compiled = nodes_module.compile_material(mat, slots=slots, load_pixels=False)
    assert compiled.warnings == [] and compiled.medium.density_varies
    assert compiled.medium.density_attributes == {"flame": 1}
    vertex_colour = nodes.new("ShaderNodeVertexColor")  # Cycles reads it as 0 in a volume, grids or not
    vertex_colour.layer_name = "smoke"
    link(vertex_colour.outputs["Alpha"], volume.inputs["Density"])
    compiled = nodes_module.compile_material(mat, slots=slots, load_pixels=False)
    assert compiled.medium.density_varies and compiled.medium.density_attributes == {}


def _tables(prism_addon):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    renderer = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.renderer")
    settings = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.settings")
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), [])
    return scene, renderer.Renderer(scene, settings.RenderSettings(samples=1)).tables


def test_baked_voxels_hold_the_node_tree_at_their_centres(prism_addon, fresh_scene):
    """A cube turned 30° about z and scaled (1.5, 1, 0.5), Density 3 × Generated X: every baked voxel centre
    inside the cube holds 3 × its Generated X, found from its object-space position."""
    baked_density = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.media.baked_density")
    black_world().node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    obj = _cube("Ramp", _gradient_material("Ramp", 3.0), location=(0.3, -0.2, 1.0), rotation=(0.0, 0.0, 0.5236),
                scale=(1.5, 1.0, 0.5))
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), resolution=(8, 8))
    scene, tables = _tables(prism_addon)
    table = tables.material_table
    m = int(np.flatnonzero(table.volume_density >= 0)[0])
    spec = scene.materials[m].medium
    grid = baked_density.bake_density(tables.geometry, table.arrays, table.volume_density, table.register_count, m,
                                      spec, tables.geometry.attributes.offset)
    counts = np.array(grid.values.shape)
    assert counts.min() > 20 and grid.values.size <= baked_density.MAX_BAKED_VOXELS
    index = np.stack(np.meshgrid(*[np.arange(n) for n in counts], indexing="ij"), axis=-1).reshape(-1, 3)
    world = index @ grid.index_to_world[:3, :3].T + grid.index_to_world[:3, 3]
    local = (world - np.asarray(obj.location)) @ np.asarray(obj.matrix_world.to_3x3().inverted()).T
    inside = np.all(np.abs(local) <= 1.0, axis=1)
    expected = 3.0 * (local[inside, 0] + 1.0) / 2.0
    assert inside.sum() > 1000
    np.testing.assert_allclose(grid.values.ravel()[inside], expected, atol=2e-4)


def test_an_absorbing_gradient_cube_transmits_the_closed_form(prism_addon, fresh_scene):
    """Density k × Generated X in a black Volume Absorption cube (2 m), seen along y by an orthographic camera
    against a white world: a pixel column over [x0, x1] transmits the mean of exp(-k (x + 1)) over it (the
    density integrated over the 2 m depth), exactly, as the grid holds the linear ramp exactly."""
    k = 1.5
    world = black_world()
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    _cube("Ramp", _gradient_material("Ramp", k, Color=(0.0, 0.0, 0.0)))
    cam = camera((0.0, -6.0, 0.0), (0.0, 0.0, 0.0), resolution=(16, 4))
    cam.data.type, cam.data.ortho_scale = "ORTHO", 2.0
    image = luminance(render_prism_rgba(fresh_scene, 256))
    columns = image.mean(axis=0)
    x0 = -1.0 + np.arange(16) / 8.0
    expected = (np.exp(-k * (x0 + 1.0)) - np.exp(-k * (x0 + 1.125))) / (k * 0.125)
    print("MEASURED gradient cube columns / closed form:", np.round(columns / expected, 4).tolist())
    print(f"MEASURED gradient cube mean: Prism {columns.mean():.5f}, closed form {expected.mean():.5f}")
    ratio = columns / expected  # ratio tracking's noise: about 1 % a column where bright, 3 % where dark
    assert columns.mean() == pytest.approx(expected.mean(), rel=0.01)
    assert ratio[:8].mean() == pytest.approx(1.0, abs=0.025) and ratio[8:].mean() == pytest.approx(1.0, abs=0.025)
    np.testing.assert_allclose(ratio, 1.0, atol=0.1)


def test_a_noise_textured_smoke_cube_matches_cycles(prism_addon, fresh_scene):
    """A Principled Volume of Density 2 × Noise Texture (scale 3) in a 2 m cube under a white world and a sun:
    the mean luminance of the cube's pixels matches Cycles' (ray marching at Step Rate 0.5) within 3 %."""
    world = black_world()
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    mat, nodes, link = material("Smoke")
    mat.cycles.volume_step_rate = 0.5
    noise = node(nodes, "ShaderNodeTexNoise", Scale=3.0, Detail=2.0)
    scale = node(nodes, "ShaderNodeMath", Value_001=2.0)
    scale.operation = "MULTIPLY"
    volume = node(nodes, "ShaderNodeVolumePrincipled", Color=(0.8, 0.7, 0.55), Absorption_Color=(0.3, 0.4, 0.6))
    link(noise.outputs["Fac"], scale.inputs[0])
    link(scale.outputs[0], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    _cube("Smoke", mat, location=(0.0, 0.0, 1.0))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.4)
    fresh_scene.collection.objects.link(sun)
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    region = (slice(6, 18), slice(6, 18))
    ratio, prism, cycles = compare_mean_luminance(fresh_scene, 256, region, "noise smoke cube")
    blocks = (prism[region] / cycles[region]).reshape(3, 4, 3, 4).mean(axis=(1, 3))
    print(f"MEASURED noise smoke cube, 4x4 blocks Prism / Cycles: {np.round(blocks, 3).tolist()}")
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_a_node_driven_density_of_world_fog_is_warned_and_rendered_at_the_socket_value(prism_addon, fresh_scene):
    world_volume = importlib.import_module(f"{prism_addon.__name__}.engine.export.world_volume")
    world = black_world()
    nodes, links = world.node_tree.nodes, world.node_tree.links
    fog = node(nodes, "ShaderNodeVolumeScatter", Density=0.2)
    noise = nodes.new("ShaderNodeTexNoise")
    links.new(noise.outputs["Fac"], fog.inputs["Density"])
    links.new(fog.outputs[0], nodes["World Output"].inputs["Volume"])
    warnings = []
    spec = world_volume.export_world_volume(world, world.node_tree, warnings)
    assert not spec.density_varies and spec.scatter[0][0] == pytest.approx(0.2)
    assert any("World 'World'" in w and "inside meshes only" in w and "0.2" in w for w in warnings), warnings


def test_objects_far_apart_that_share_a_textured_volume_get_a_grid_each(prism_addon, fresh_scene):
    """Two 2 m cubes 40 m apart with one material of Density 3 × Generated X: each is baked over its own
    bounds (81³ voxels at Step Rate 1, as one cube alone), not over the 42 m between them; so is a shared
    Emission Strength driven by nodes."""
    baked_density = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.media.baked_density")
    black_world().node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    mat = _gradient_material("Ramp", 3.0)
    _cube("Near", mat)
    _cube("Far", mat, location=(40.0, 0.0, 0.0))
    camera((20.0, -60.0, 0.0), (20.0, 0.0, 0.0), resolution=(8, 8))
    scene, tables = _tables(prism_addon)
    table = tables.material_table
    rows = np.flatnonzero(table.volume_density >= 0)
    assert len(rows) == 2 and {scene.materials[m].name for m in rows} == {"Ramp"}
    lows = []
    for m in rows:
        grid = baked_density.bake_density(tables.geometry, table.arrays, table.volume_density, table.register_count,
                                          int(m), scene.materials[m].medium, tables.geometry.attributes.offset)
        assert grid.values.shape == (81, 81, 81)
        assert np.allclose(np.diag(grid.index_to_world)[:3] * 80, 2.0)
        lows.append(grid.index_to_world[0, 3])
    assert sorted(lows) == pytest.approx([-1.0, 39.0])
    glow = glow_material("Glow", lambda nodes: nodes.new("ShaderNodeTexNoise").outputs["Fac"], 2.0, (1.0, 1.0, 1.0))
    for name in ("Near", "Far"):  # a shared Emission Strength driven by nodes is baked per object too
        bpy.data.objects[name].data.materials[0] = glow
    _, tables = _tables(prism_addon)
    assert len(np.flatnonzero(tables.material_table.volume_emission >= 0)) == 2


def test_a_noise_textured_emission_strength_glows_as_in_cycles(prism_addon, fresh_scene):
    """A 2 m cube of Principled Volume (Density 0.5, grey) whose Emission Strength is 3 × Noise Texture, in the
    dark: the strength is baked on the grid (over a density of ones, the density being constant) and the glow's
    mean luminance matches Cycles 4.5 (Step Rate 0.5) within 3 %."""
    black_world()
    mat = glow_material("Glow", lambda nodes: node(nodes, "ShaderNodeTexNoise", Scale=3.0, Detail=2.0).outputs["Fac"],
                        3.0, (1.0, 0.6, 0.3))
    mat.cycles.volume_step_rate = 0.5
    _cube("Glow", mat, location=(0.0, 0.0, 1.0))
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    scene, tables = _tables(prism_addon)
    m = int(np.flatnonzero(tables.material_table.volume_emission >= 0)[0])
    spec = scene.materials[m].medium
    assert not spec.density_varies and spec.emission == [] and len(spec.emission_field) == 1
    assert spec.emission_field[0] == (1.0, pytest.approx((1.0, 0.6, 0.3)))
    assert tables.material_table.volume_density[m] < 0
    region = (slice(6, 18), slice(6, 18))
    ratio, _, _ = compare_mean_luminance(fresh_scene, 256, region, "noise-textured emission cube")
    assert ratio == pytest.approx(1.0, abs=0.03)
