"""Blender Volume objects (OpenVDB files) render as grid media: a 16³ density sphere written with the
``openvdb`` module Blender bundles, loaded as a Volume object (moved, turned and squashed), its Principled
Volume's Density scaled by the "density" grid as Cycles does.

- The export places the grid where Blender does (its transform against Blender's own ``matrix_object``, each
  voxel at the centre of its index cell as Cycles samples it) and warns nothing for a plain Principled Volume;
  it reads the "temperature" grid a blackbody Principled Volume names, and warns, with the share of the box
  Cycles leaves dark, light that fills the box (Emission Strength).
- A lit smoke sphere and a fire (blackbody light at the Temperature × the "temperature" grid) are rendered
  by Prism and by Cycles 4.5 from the same scene in the test: mean luminance of the pixels around
  the volume within 2 %, and per 4 × 4 block within what the noise of two Prism seeds allows. Cycles 4.5 ray
  marches heterogeneous volumes: its step is the voxel size × Render ▸ Light Paths ▸ Volumes ▸ Step Rate,
  set to 0.1 here (0.0125 m steps, 1/10 voxel; Max Steps 4096), with the volume's grids held at full
  precision (Volume ▸ Render ▸ Precision Full), so that its marching bias is well under the noise.
- In Volume ▸ Render ▸ Space "Object" (the default) the density and emission follow the object's scale as
  Cycles' do; "World" keeps them per metre.
"""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world, camera, glow_material, material, node

VOXEL_M = 0.125
SIZE = 16


def _openvdb(prism_addon):
    grids = importlib.import_module(f"{prism_addon.__name__}.engine.export.volume_grids")
    vdb = grids.openvdb_module()
    assert vdb is not None, "the bpy module ships OpenVDB's Python module"
    return vdb


def _write_sphere(vdb, path):
    """A 16³ grid of voxels 0.125 m over [-1, 1]³: density 1 inside r = 0.6 m, falling to 0 at r = 0.95 m."""
    centres = (np.arange(SIZE) + 0.5) * VOXEL_M - 1.0
    r = np.sqrt(centres[:, None, None] ** 2 + centres[None, :, None] ** 2 + centres[None, None, :] ** 2)
    values = np.clip((0.95 - r) / 0.35, 0.0, 1.0).astype(np.float32)
    grid = vdb.FloatGrid()
    grid.name = "density"
    grid.copyFromArray(values, ijk=(0, 0, 0))
    transform = vdb.createLinearTransform(voxelSize=VOXEL_M)
    transform.postTranslate((centres[0], centres[0], centres[0]))
    grid.transform = transform
    vdb.write(str(path), grids=[grid])
    return values


FIRE_K = 1500.0  # the Principled Volume's Temperature, times the "temperature" grid (up to 1.5)


def _write_fire(vdb, path):
    """The sphere's "density" grid and a "temperature" grid of 1.5 × it, in one file."""
    values = _write_sphere(vdb, path)
    heat = 1.5 * values
    grids = []
    for name, array in (("density", values), ("temperature", heat)):
        grid = vdb.FloatGrid()
        grid.name = name
        grid.copyFromArray(array, ijk=(0, 0, 0))
        transform = vdb.createLinearTransform(voxelSize=VOXEL_M)
        transform.postTranslate((VOXEL_M / 2 - 1.0,) * 3)
        grid.transform = transform
        grids.append(grid)
    vdb.write(str(path), grids=grids)
    return values, heat


def _fire():
    return _smoke(Color=(0.5, 0.5, 0.5), Density=0.5, Blackbody_Intensity=1.0, Temperature=FIRE_K)


def _volume_object(path, mat=None):
    volume = bpy.data.volumes.new("Sphere")
    volume.filepath = str(path)
    volume.render.precision = "FULL"
    obj = bpy.data.objects.new("Cloud", volume)
    obj.location = (0.1, 0.0, 1.0)
    obj.rotation_euler = (0.0, 0.3, 0.5)
    obj.scale = (1.3, 1.0, 0.8)
    if mat is not None:
        volume.materials.append(mat)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _object_space(obj):
    """Cycles 4.5's density factor of a Volume object in Object space (its scene/object.cpp)."""
    return 1.0 / np.linalg.norm(np.array(obj.matrix_world)[:3, :3] @ np.full(3, 3.0 ** -0.5))


def _smoke(**inputs):
    mat, nodes, link = material("Smoke")
    volume = node(nodes, "ShaderNodeVolumePrincipled", **inputs)
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    return mat


def _sun(scene):
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.4)
    scene.collection.objects.link(sun)


def _export(prism_addon, warnings):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)


def test_a_volume_object_exports_its_grid_where_blender_places_it(prism_addon, fresh_scene, tmp_path):
    values = _write_sphere(_openvdb(prism_addon), tmp_path / "sphere.vdb")
    obj = _volume_object(tmp_path / "sphere.vdb", _smoke(Density=2.0))
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 1.0), resolution=(8, 8))
    _sun(fresh_scene)
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    rows = [i for i, name in enumerate(scene.object_names) if name == "Cloud"]
    triangles = np.flatnonzero(np.isin(scene.triangle_object, rows))
    assert len(triangles) == 12  # the closed box of the grid's voxels
    material = scene.materials[scene.triangle_material[triangles[0]]]
    grid = material.medium.density_grid
    active = values > 0
    low = np.argwhere(active).min(0)
    assert grid.values.shape == tuple(np.argwhere(active).max(0) - low + 1)
    assert np.array_equal(grid.values, values[tuple(slice(lo, lo + n) for lo, n in zip(low, grid.values.shape))])
    obj.data.grids.load()
    shift = np.eye(4)
    shift[:3, 3] = low + 0.5  # the array's first voxel, at the centre of its index cell as Cycles samples it
    blender = np.array(obj.matrix_world) @ np.array(obj.data.grids["density"].matrix_object) @ shift
    assert np.allclose(grid.index_to_world, blender, atol=1e-6)
    # Volume ▸ Render ▸ Space "Object": the density follows the object's scale as in Cycles, 1 / |M (1,1,1)/√3|
    assert material.kind == "null" and material.medium.scatter[0][0] == pytest.approx(2.0 * _object_space(obj))
    obj.data.render.space = "WORLD"
    scene = _export(prism_addon, [])
    medium = next(m.medium for m in scene.materials if m.medium is not None and m.medium.density_grid is not None)
    assert medium.scatter[0][0] == pytest.approx(2.0)


def test_emission_that_fills_the_box_is_warned_with_what_was_measured(prism_addon, fresh_scene, tmp_path):
    values = _write_sphere(_openvdb(prism_addon), tmp_path / "sphere.vdb")
    obj = _volume_object(tmp_path / "sphere.vdb", _smoke(Emission_Strength=1.0))
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 1.0), resolution=(8, 8))
    _sun(fresh_scene)
    warnings = []
    scene = _export(prism_addon, warnings)
    empty = 100 * np.mean(values <= 0.0)  # the sphere's active voxels span the whole 16³ box
    assert warnings == [f"Volume 'Cloud': its material emits light where its grids read 0 (Emission Strength, or "
                        f"blackbody light a Blackbody Intensity below 1 keeps at 0 K); Prism fills the box around "
                        f"its voxels with that light evenly and Cycles a smaller region (a 16³ grid with every voxel "
                        f"active glows 1.2 × Cycles' light in Prism), and {empty:.0f} % of this box holds no "
                        f"density, which Cycles may leave dark too."]
    used = {int(m) for m in scene.triangle_material}
    assert [scene.materials[m].medium.emission for m in used] == [[(pytest.approx(_object_space(obj)), (1.0, 1.0, 1.0),
                                                                    None)]]


def test_a_temperature_grid_sets_the_blackbody_temperature_voxel_by_voxel(prism_addon, fresh_scene, tmp_path):
    values, heat = _write_fire(_openvdb(prism_addon), tmp_path / "fire.vdb")
    obj = _volume_object(tmp_path / "fire.vdb", _fire())
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 1.0), resolution=(8, 8))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []  # blackbody light that vanishes at 0 K, where the temperature grid is 0
    medium = scene.materials[int(scene.triangle_material[np.isin(scene.triangle_object, [
        i for i, n in enumerate(scene.object_names) if n == "Cloud"])][0])].medium
    assert medium.temperature_grid is not None
    assert medium.blackbody == [(pytest.approx(_object_space(obj)), 1.0, FIRE_K, (1.0, 1.0, 1.0))]
    low = np.argwhere(heat > 0).min(0)
    assert np.array_equal(medium.temperature_grid.values,
                          heat[tuple(slice(lo, lo + n) for lo, n in zip(low, medium.temperature_grid.values.shape))])
    assert np.allclose(medium.temperature_grid.index_to_world, medium.density_grid.index_to_world)


def test_a_temperature_outside_the_spectra_is_warned_truly_for_a_grid(prism_addon, fresh_scene, tmp_path):
    """Temperature 400 K × a grid of up to 1.5: the warning names the colour rule, not one colour."""
    _write_fire(_openvdb(prism_addon), tmp_path / "fire.vdb")
    _volume_object(tmp_path / "fire.vdb", _smoke(Blackbody_Intensity=1.0, Temperature=400.0))
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 1.0), resolution=(8, 8))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == ["Material 'Smoke': the 'Principled Volume' node (Principled Volume) has a Temperature of "
                        "400 K; Prism's blackbody spectra span 1000-40000 K and colour a temperature outside at the "
                        "nearer end (1000 K here), at the intensity of the temperature itself (on a Volume object "
                        "with a Temperature Attribute grid, the Temperature times the grid, point by point)."]
    assert any(m.medium is not None and m.medium.temperature_grid is not None for m in scene.materials)


def _against_cycles(scene, label):
    """Prism (two seeds, 128 spp) and Cycles (256 spp) from the scene: the mean luminance of the pixels around
    the volume within 2 %, and per 4 × 4 block within what the noise of two Prism seeds allows."""
    scene.cycles.volume_step_rate = 0.1
    scene.cycles.volume_max_steps = 4096
    cycles = luminance(render_cycles_rgba(scene, 256, max_bounces=32))
    scene.prism.max_bounces = 32
    prism = [luminance(render_prism_rgba(scene, 128, seed=seed)) for seed in (0, 1)]
    region = (slice(4, 20), slice(4, 20))
    p, c = (prism[0][region].mean() + prism[1][region].mean()) / 2, cycles[region].mean()

    def blocks(image):
        return image[region].reshape(4, 4, 4, 4).mean((1, 3))

    difference = np.sqrt(np.mean((blocks((prism[0] + prism[1]) / 2) - blocks(cycles)) ** 2))
    noise = np.sqrt(np.mean((blocks(prism[0]) - blocks(prism[1])) ** 2))
    print(f"MEASURED {label}: Prism {p:.5f}, Cycles {c:.5f}, ratio {p / c:.4f}; per 4x4 block "
          f"RMS Prism - Cycles {difference / c:.4f}, Prism seed 0 - seed 1 {noise / c:.4f} of the mean; "
          f"volume centre Prism {prism[0][10:14, 10:14].mean():.4f}, Cycles {cycles[10:14, 10:14].mean():.4f}, "
          f"corner {cycles[0, 0]:.4f}")
    assert cycles[10:14, 10:14].mean() > 2.0 * cycles[0, 0]  # the volume stands out of the world
    assert p / c == pytest.approx(1.0, abs=0.02)
    assert difference < 2.0 * noise + 0.005 * c


def test_a_volume_object_matches_cycles(prism_addon, fresh_scene, tmp_path):
    _write_sphere(_openvdb(prism_addon), tmp_path / "sphere.vdb")
    _volume_object(tmp_path / "sphere.vdb", _smoke(Color=(0.8, 0.7, 0.55), Density=3.0, Anisotropy=0.2,
                                                   Absorption_Color=(0.3, 0.4, 0.6)))
    world = black_world()
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.1  # the sun's light dominates
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    _sun(fresh_scene)
    camera((0.0, -6.0, 1.0), (0.1, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    _against_cycles(fresh_scene, "Volume object (VDB sphere)")


def test_a_fire_matches_cycles(prism_addon, fresh_scene, tmp_path):
    """The sphere's smoke glowing at 1500 K × its "temperature" grid (up to 2250 K), in the dark."""
    _write_fire(_openvdb(prism_addon), tmp_path / "fire.vdb")
    _volume_object(tmp_path / "fire.vdb", _fire())
    black_world()
    camera((0.0, -6.0, 1.0), (0.1, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    _against_cycles(fresh_scene, "Volume object fire (blackbody x temperature grid)")


def _attribute_density(shaders, attribute, k, **inputs):
    """A material whose ``shaders`` (Volume Scatter, Volume Absorption, Principled Volume...) take their Density
    from k × the Fac of an Attribute node reading ``attribute`` (a grid of a Volume object), added together."""
    mat, nodes, link = material("Attribute smoke")
    read = nodes.new("ShaderNodeAttribute")
    read.attribute_name = attribute
    scale = node(nodes, "ShaderNodeMath", Value_001=k)
    scale.operation = "MULTIPLY"
    link(read.outputs["Fac"], scale.inputs[0])
    made = [node(nodes, kind, **inputs.get(kind, {})) for kind in shaders]
    total = made[0].outputs[0]
    for shader in made:
        link(scale.outputs[0], shader.inputs["Density"])
        if shader is not made[0]:
            add = nodes.new("ShaderNodeAddShader")
            link(total, add.inputs[0])
            link(shader.outputs[0], add.inputs[1])
            total = add.outputs[0]
    link(total, nodes["Output"].inputs["Volume"])
    return mat


def _write_sphere_and_ramp(vdb, path):
    """The sphere's "density" grid and a "ramp" grid over a larger box (from index -3, so that it is resampled
    onto the density's voxels), 0.1 × (index x + 4)."""
    values = _write_sphere(vdb, path)
    ramp = np.broadcast_to(0.1 * (np.arange(-3, SIZE + 3) + 4.0)[:, None, None], (SIZE + 6,) * 3).astype(np.float32)
    grids = []
    for name, array, first in (("density", values, 0), ("ramp", np.ascontiguousarray(ramp), -3)):
        grid = vdb.FloatGrid()
        grid.name = name
        grid.copyFromArray(array, ijk=(first, first, first))
        transform = vdb.createLinearTransform(voxelSize=VOXEL_M)
        transform.postTranslate((VOXEL_M / 2 - 1.0,) * 3)
        grid.transform = transform
        grids.append(grid)
    vdb.write(str(path), grids=grids)
    return values


def _baked_cloud(prism_addon, scene):
    """(the Volume object "Cloud"'s medium, the ``BakedFields`` (density, strength) the render bakes for it on
    its voxels)."""
    baked_density = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.media.baked_density")
    renderer = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.renderer")
    settings = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.settings")
    box = int(scene.triangle_material[np.isin(scene.triangle_object, [
        i for i, n in enumerate(scene.object_names) if n == "Cloud"])][0])
    tables = renderer.Renderer(scene, settings.RenderSettings(samples=1)).tables
    table = tables.material_table
    baked = baked_density.bake_fields(tables.geometry, table.arrays, table.volume_density, table.volume_emission,
                                      table.register_count, scene.materials, tables.geometry.attributes.offset)
    return scene.materials[box].medium, baked[box]


def test_a_density_of_nodes_reading_grids_is_baked_on_the_voxels(prism_addon, fresh_scene, tmp_path, monkeypatch):
    """A Principled Volume whose Density is 2 × the "ramp" grid (Attribute node), times its Density Attribute
    grid "density" as Cycles multiplies them: the baked voxels hold 2 × ramp × density, the ramp resampled from
    its own, larger box. Past the most voxels a bake takes, the nodes run on every few voxels, warned, and their
    result (linear in the voxel index here) is interpolated exactly. Volume Info's Density reads "density"; a
    grid the file lacks reads 0, warned."""
    values = _write_sphere_and_ramp(_openvdb(prism_addon), tmp_path / "ramp.vdb")
    obj = _volume_object(tmp_path / "ramp.vdb", _attribute_density(["ShaderNodeVolumePrincipled"], "ramp", 2.0))
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 1.0), resolution=(8, 8))
    _sun(fresh_scene)
    warnings = []
    medium, (baked, _) = _baked_cloud(prism_addon, _export(prism_addon, warnings))
    assert warnings == []
    assert medium.scatter[0][0] == pytest.approx(_object_space(obj))
    low = np.argwhere(values > 0).min(0)
    density = values[tuple(slice(lo, lo + n) for lo, n in zip(low, baked.values.shape))]
    ramp = 0.1 * (np.arange(baked.values.shape[0]) + low[0] + 4.0)
    np.testing.assert_allclose(baked.values, 2.0 * ramp[:, None, None] * density, rtol=1e-5, atol=1e-6)
    assert np.allclose(baked.index_to_world, medium.density_grid.index_to_world)

    voxel_inputs = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.media.voxel_inputs")
    n = baked.values.shape
    halved = int(np.prod([(m - 2) // 2 + 2 for m in n]))  # every other voxel and the last along each axis
    with monkeypatch.context() as patch:
        patch.setattr(voxel_inputs, "MAX_BAKED_VOXELS", halved)
        _, (coarse, _) = _baked_cloud(prism_addon, _export(prism_addon, warnings))
    assert warnings == [
        f"Volume 'Cloud': grid 'density' has {baked.values.size:,} voxels; Prism runs its material's nodes on one "
        f"voxel in 2 along each axis ({halved:,} voxels: it bakes at most {halved:,} per volume) and interpolates "
        "between them (Cycles runs them at every step); the grid's own values keep every voxel."]
    np.testing.assert_allclose(coarse.values, baked.values, rtol=1e-5, atol=1e-6)
    warnings.clear()

    mat, nodes, link = material("Volume Info")
    info, scatter = nodes.new("ShaderNodeVolumeInfo"), nodes.new("ShaderNodeVolumeScatter")
    link(info.outputs["Density"], scatter.inputs["Density"])
    link(scatter.outputs[0], nodes["Output"].inputs["Volume"])
    obj.data.materials[0] = mat
    medium, (baked, _) = _baked_cloud(prism_addon, _export(prism_addon, warnings))
    assert warnings == []
    np.testing.assert_allclose(baked.values, density, rtol=1e-6)

    obj.data.materials[0] = _attribute_density(["ShaderNodeVolumeScatter"], "smoke", 2.0)
    _export(prism_addon, warnings)
    assert warnings == ["Volume 'Cloud': its material reads no density grid (no Principled Volume Density Attribute "
                        "or Attribute node); Prism fills the box of grid 'density' with the density its nodes "
                        "compute (Cycles fills its active voxels).",
                        "Volume 'Cloud': its material reads the attribute 'smoke', which is not a float grid of its "
                        "file (float grids: ['density', 'ramp']); Cycles reads it as 0, and so does Prism."]


def test_a_volume_object_of_attribute_driven_density_matches_cycles(prism_addon, fresh_scene, tmp_path):
    """Volume Scatter and Volume Absorption, each of Density 3 × the "density" grid read by an Attribute node
    (no Density Attribute): Prism bakes it on the voxels and matches Cycles 4.5 in absolute light."""
    _write_sphere(_openvdb(prism_addon), tmp_path / "sphere.vdb")
    mat = _attribute_density(["ShaderNodeVolumeScatter", "ShaderNodeVolumeAbsorption"], "density", 3.0,
                             ShaderNodeVolumeScatter={"Color": (0.8, 0.7, 0.55), "Anisotropy": 0.2},
                             ShaderNodeVolumeAbsorption={"Color": (0.85, 0.9, 0.95)})
    _volume_object(tmp_path / "sphere.vdb", mat)
    world = black_world()
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.1
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    _sun(fresh_scene)
    camera((0.0, -6.0, 1.0), (0.1, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    _against_cycles(fresh_scene, "Volume object, Density 3 x Attribute 'density'")


def test_an_emission_strength_of_nodes_reading_a_grid_glows_as_in_cycles(prism_addon, fresh_scene, tmp_path):
    """A Principled Volume (Density 0.5 × its "density" grid) whose Emission Strength is 4 × the "density"
    grid (Attribute node), in the dark: the baked strength holds 4 × density at each voxel (not multiplied by
    the density, as Cycles' emission is not), and the glow matches Cycles 4.5 in absolute light."""
    values = _write_sphere(_openvdb(prism_addon), tmp_path / "sphere.vdb")
    def density_attribute(nodes):
        read = nodes.new("ShaderNodeAttribute")
        read.attribute_name = "density"
        return read.outputs["Fac"]

    obj = _volume_object(tmp_path / "sphere.vdb", glow_material("Glow", density_attribute, 4.0, (1.0, 0.5, 0.2)))
    black_world()
    camera((0.0, -6.0, 1.0), (0.1, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    medium, (density_field, strength) = _baked_cloud(prism_addon, scene)
    assert density_field is None  # the density is the grid's, not the nodes'
    [(weight, colour)] = medium.emission_field
    assert medium.emission == [] and weight == pytest.approx(_object_space(obj))
    assert colour == pytest.approx((1.0, 0.5, 0.2))
    low = np.argwhere(values > 0).min(0)
    density = values[tuple(slice(lo, lo + n) for lo, n in zip(low, strength.values.shape))]
    np.testing.assert_allclose(strength.values, 4.0 * density, rtol=1e-6)
    _against_cycles(fresh_scene, "Volume object, Emission Strength 4 x Attribute 'density'")
