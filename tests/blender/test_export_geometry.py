"""Evaluated geometry → tracer triangles: every surface once, hair as round curves (whatever Render ▸ Curves ▸
Shape says), instances placed exactly (mirrored ones still facing out),
float64 world positions, and a warning for geometry Prism does not render."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.batch import run_batch, run_batch_stderr
from helpers.bpy_scenes import add_camera, add_point_light


def _export(prism_addon, warnings=None):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)


def _triangles_of(scene, name):
    ids = [i for i, n in enumerate(scene.object_names) if n == name]
    return np.flatnonzero(np.isin(scene.triangle_object, ids))


def _evaluated_triangle_count(obj) -> int:
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    mesh.calc_loop_triangles()
    count = len(mesh.loop_triangles)
    evaluated.to_mesh_clear()
    return count


@pytest.fixture
def lit(fresh_scene):
    add_point_light("Bulb", 100.0, (0.0, -2.0, 4.0))
    add_camera((0.0, -12.0, 2.0), (1.45, 0.0, 0.0), resolution=(16, 12))
    return fresh_scene


def test_text_curves_surfaces_and_metaballs_are_exported_once(prism_addon, lit):
    bpy.ops.object.text_add(location=(-3.0, 0.0, 0.0))
    bpy.ops.curve.primitive_bezier_circle_add(location=(0.0, 0.0, 0.0))
    bpy.context.object.data.bevel_depth = 0.1
    bpy.ops.surface.primitive_nurbs_surface_sphere_add(location=(3.0, 0.0, 0.0))
    bpy.ops.object.metaball_add(type="BALL", location=(6.0, 0.0, 0.0))
    scene = _export(prism_addon)
    for name in ("Text", "BézierCircle", "SurfSphere", "Mball"):
        expected = _evaluated_triangle_count(bpy.data.objects[name])
        assert expected > 0
        assert len(_triangles_of(scene, name)) == expected, name  # not twice (object + its mesh instance)
    assert scene.triangle_count == sum(_evaluated_triangle_count(bpy.data.objects[n]) for n in
                                       ("Text", "BézierCircle", "SurfSphere", "Mball"))


def _cube_instances(count_x, count_y, mirrored=False):
    """A grid of (``count_x`` + 1) x (``count_y`` + 1) vertices instancing a rotated, scaled 0.2 m cube."""
    bpy.ops.mesh.primitive_cube_add(size=0.2, location=(0.0, 0.0, 0.0))
    cube = bpy.context.object
    cube.rotation_euler = (0.3, 0.2, 0.1)
    cube.scale = (-1.5, 1.0, 1.0) if mirrored else (1.5, 1.0, 1.0)
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=count_x, y_subdivisions=count_y, size=4.0, location=(0, 0, 1))
    grid = bpy.context.object
    grid.rotation_euler = (0.0, 0.0, 0.4)
    grid.instance_type = "VERTS"
    cube.parent = grid
    return cube, grid


@pytest.mark.parametrize("mirrored", [False, True], ids=["plain", "mirrored"])
def test_instances_are_placed_like_blender_places_them(prism_addon, lit, mirrored):
    cube, grid = _cube_instances(10, 10, mirrored)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    expected = []
    for instance in depsgraph.object_instances:
        if instance.object.original == cube and instance.show_self:  # the cube itself too, as Blender shows it
            matrix = np.array(instance.matrix_world)
            local = np.array([v.co for v in cube.data.vertices])
            expected.append(local @ matrix[:3, :3].T + matrix[:3, 3])
    assert len(expected) == 11 * 11 + 1
    scene = _export(prism_addon)
    rows = _triangles_of(scene, cube.name)
    assert len(rows) == len(expected) * 12
    assert scene.vertices.dtype == np.float64
    used = np.unique(scene.triangles[rows])
    assert np.allclose(np.sort(scene.vertices[used], axis=0), np.sort(np.concatenate(expected), axis=0), atol=1e-12)
    # Outward geometric normals (from the winding) on every instance, mirrored or not: glass keeps its inside.
    corners = scene.vertices[scene.triangles[rows]]
    geometric = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    centres = {tuple(np.round(e.mean(axis=0), 9)) for e in expected}
    centre_of = np.array([min(centres, key=lambda c: np.linalg.norm(np.array(c) - t)) for t in corners.mean(axis=1)])
    assert (np.einsum("ij,ij->i", geometric, corners.mean(axis=1) - centre_of) > 0).all()
    shading = scene.corner_normals[rows]
    assert np.allclose(np.linalg.norm(shading, axis=2), 1.0, atol=1e-5)
    assert (np.einsum("tcj,tj->tc", shading, geometric) > 0).all()


def test_rounded_ribbons_render_as_round_curves(prism_addon, lit, capsys):
    """Render ▸ Curves ▸ Shape "Rounded Ribbons" (a new scene's): the strands are round curves of their radius, as
    with "3D Curves" (``export.hair``), no triangles; a render runs; without a radius attribute, 5 mm as Cycles."""
    bpy.context.scene.cycles_curves.shape = "RIBBONS"
    curves = bpy.data.hair_curves.new("Fur")
    curves.add_curves([4, 3])
    positions = [(0, 0, 0), (0, 0, 0.5), (0.1, 0, 1.0), (0.2, 0, 1.5), (1, 0, 0), (1, 0, 0.5), (1, 0.2, 1.0)]
    curves.points.foreach_set("position", np.array(positions, np.float32).ravel())
    curves.attributes.new("radius", "FLOAT", "POINT")
    curves.points.foreach_set("radius", np.full(7, 0.02, np.float32))
    obj = bpy.data.objects.new("Fur", curves)
    bpy.context.scene.collection.objects.link(obj)
    scene = _export(prism_addon)
    assert len(_triangles_of(scene, "Fur")) == 0 and len(scene.curves) == 3 + 2  # a segment between each two points
    assert np.allclose(scene.curves.radii, 0.02)
    status, line = run_batch(capsys, "--samples", 1, "--output", bpy.app.tempdir + "fur.png")
    assert (status, line) == (0, f"Saved: '{bpy.app.tempdir}fur.png'")

    curves.attributes.remove(curves.attributes["radius"])  # no radius attribute: 5 mm, as Cycles
    assert np.allclose(_export(prism_addon).curves.radii, 0.005)


def test_far_from_the_origin_small_objects_keep_their_shape(prism_addon, lit):
    bpy.ops.mesh.primitive_plane_add(size=0.002, location=(1.0e7, 0.0, 0.0))
    scene = _export(prism_addon)
    xs = np.unique(scene.vertices[_triangles_of_vertices(scene, "Plane"), 0])
    assert xs.tolist() == [1.0e7 - 0.001, 1.0e7 + 0.001]  # float32 would round both to 1e7


def _triangles_of_vertices(scene, name):
    return np.unique(scene.triangles[_triangles_of(scene, name)])


def _volume():
    bpy.context.scene.collection.objects.link(bpy.data.objects.new("Smoke", bpy.data.volumes.new("Smoke")))


WARNING_CASES = {
    "volume": (_volume, "Volume 'Smoke' is not rendered: it has no OpenVDB file"),
}


@pytest.mark.parametrize("case", list(WARNING_CASES))
def test_geometry_prism_skips_is_named_in_a_warning(prism_addon, lit, tmp_path, capsys, bad_input, case):
    add, message = WARNING_CASES[case]
    bpy.ops.mesh.primitive_plane_add(size=4.0)  # something to render besides
    add()
    warnings = []
    _export(prism_addon, warnings)
    assert [w for w in warnings if message in w] == [warnings[0]] and len(warnings) == 1
    status, stderr = run_batch_stderr(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert status == 0 and (tmp_path / "x.png").is_file()
    shown = f"Prism: warning: {warnings[0]}"
    assert stderr.count(shown) == 1
    bad_input(f"a scene with a {case} (a warning; the render goes on)", status, shown)
