"""Blender Cycles (through the ``bpy`` module, CPU) on a benchmark scene, as a peer.

The Prism ``Scene`` is rebuilt in Blender: one mesh per material (vertices set
with ``foreach_set``), a Diffuse BSDF per grey material, Blender area lights of
the same power, size and transform, the same camera (focal length, sensor,
transform). Cycles settings: CPU, fixed thread count, no adaptive sampling, no
denoising, no light clamping, ``max_bounces`` for every bounce type, default
Blackman-Harris pixel filter (1.5 px; Prism and Mitsuba use a box: each renderer
is scored against its own reference, so the filter changes the image, not the
error). Cycles is an RGB renderer; with grey surfaces and a white light it
computes the same image as a spectral renderer up to its light units.

Run: ``python -m benchmarks.peers.cycles --scene cornell_grey --spp 1 4 16 --out x.npz``
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

import numpy as np


def _mesh_object(bpy, name, vertices, triangles, material, smooth):
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", np.asarray(vertices, np.float32).ravel())
    mesh.loops.add(3 * len(triangles))
    mesh.loops.foreach_set("vertex_index", np.asarray(triangles, np.int32).ravel())
    mesh.polygons.add(len(triangles))
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * len(triangles), 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(triangles), 3, dtype=np.int32))
    # Blender 4.1+ shades faces smooth unless told: flat-shaded Prism meshes stay flat
    mesh.polygons.foreach_set("use_smooth", np.full(len(triangles), smooth, dtype=bool))
    mesh.update(calc_edges=True)
    mesh.validate()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _diffuse_material(bpy, material):
    mat = bpy.data.materials.new(material.name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*material.base_color, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    mat.node_tree.links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    return mat


def build_blender_scene(scene, threads=2, max_bounces=8):
    """Fill the current (emptied) bpy scene with the Prism ``Scene`` for Cycles."""
    import bpy
    from mathutils import Matrix

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    bl = bpy.context.scene
    for index, material in enumerate(scene.materials):
        chosen = scene.triangle_material == index
        if not chosen.any():
            continue
        if material.kind != "diffuse" or material.emission_strength > 0:
            raise ValueError(f"Cycles peer: material '{material.name}' ({material.kind}) is not compared")
        used, tris = np.unique(scene.triangles[chosen], return_inverse=True)
        _mesh_object(bpy, material.name, scene.vertices[used], tris.reshape(-1, 3),
                     _diffuse_material(bpy, material), scene.corner_normals is not None)
    for light in scene.lights:
        if light.kind != "area" or light.area_shape != "rectangle" or light.spectrum.kind != "rgb":
            raise ValueError(f"Cycles peer: light '{light.name}' is not a white rectangular area light")
        data = bpy.data.lights.new(light.name, "AREA")
        data.shape = "RECTANGLE"
        data.size, data.size_y = light.size_u_m, light.size_v_m
        data.energy = light.power_w
        data.color = light.spectrum.rgb
        obj = bpy.data.objects.new(light.name, data)
        m = np.eye(4)
        m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = light.axis_u, light.axis_v, -np.asarray(light.direction), light.position
        obj.matrix_world = Matrix(m.tolist())
        bl.collection.objects.link(obj)
    cam = scene.camera
    if cam.model != "pinhole":
        raise ValueError(f"Cycles peer: camera model '{cam.model}' is not compared")
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.lens = cam.focal_length_mm
    cam_data.sensor_fit = "HORIZONTAL"
    cam_data.sensor_width, cam_data.sensor_height = cam.film_width_mm, cam.film_height_mm
    cam_obj = bpy.data.objects.new("Camera", cam_data)
    cam_obj.matrix_world = Matrix(np.asarray(cam.camera_to_world).tolist())
    bl.collection.objects.link(cam_obj)
    bl.camera = cam_obj
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*scene.world.color, 1.0)
    background.inputs["Strength"].default_value = scene.world.strength
    bl.world = world

    bl.render.engine = "CYCLES"
    bl.cycles.device = "CPU"
    bl.render.threads_mode = "FIXED"
    bl.render.threads = threads
    bl.render.resolution_x, bl.render.resolution_y = cam.resolution
    bl.render.resolution_percentage = 100
    bl.cycles.use_adaptive_sampling = False
    bl.cycles.use_denoising = False
    bl.cycles.sample_clamp_direct = 0.0
    bl.cycles.sample_clamp_indirect = 0.0
    for name in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                 "volume_bounces", "transparent_max_bounces"):
        setattr(bl.cycles, name, max_bounces)
    bl.view_settings.view_transform = "Standard"
    bl.render.image_settings.file_format = "OPEN_EXR"
    bl.render.image_settings.color_depth = "32"
    bl.render.image_settings.exr_codec = "NONE"
    return bl


def main():
    from . import common

    args = common.parse_args("Render a benchmark scene with Cycles (bpy, CPU)")
    import bpy

    from benchmarks.scenes import build

    scene = build(args.scene, (args.resolution, args.resolution))
    bl = build_blender_scene(scene, args.threads, args.max_bounces)
    folder = tempfile.mkdtemp()
    path = os.path.join(folder, "render.exr")
    bl.render.filepath = path

    def render(spp, seed):
        bl.cycles.samples = int(spp)
        bl.cycles.seed = int(seed)
        start = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        elapsed = time.perf_counter() - start
        image = bpy.data.images.load(path, check_existing=False)
        w, h = image.size
        pixels = np.empty(w * h * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        bpy.data.images.remove(image)
        return pixels.reshape(h, w, 4)[::-1, :, :3].copy(), elapsed

    render(1, 1)  # warm-up (kernel and scene sync), untimed
    seconds, images = common.sweep(render, args.spp, args.repeats, args.first_repeat)
    ref = common.reference(render, args.reference_spp, args.reference_chunks) if args.reference_spp else None
    info = {"renderer": f"Cycles (bpy {bpy.app.version_string})", "threads": args.threads,
            "filter": "Blackman-Harris 1.5 px"}
    common.save(args.out, args, args.spp, seconds, images, info, ref)
    print(f"cycles: {args.scene} done", file=sys.stderr)
    from render import exit_now

    exit_now(0)


if __name__ == "__main__":
    main()
