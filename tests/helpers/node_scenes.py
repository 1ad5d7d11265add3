"""bpy scenes built in code for the node-material tests: materials wired node by node, a board of
emissive texture tiles, UV-mapped planes and spheres."""

from __future__ import annotations

import bpy
import numpy as np


def material(name):
    """A new material with nodes, emptied but for its Material Output: (material, nodes, link)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    output.name = "Output"

    def link(a, b):
        mat.node_tree.links.new(a, b)

    return mat, nodes, link


def node(nodes, kind, **inputs):
    """A new node with input default values set (names as Blender's, spaces replaced by _)."""
    n = nodes.new(kind)
    for key, value in inputs.items():
        name = key.replace("_", " ")
        socket = next((s for s in n.inputs if s.name == name or s.identifier in (key, name)), None)
        if isinstance(value, tuple) and len(value) == 3 and socket.type == "RGBA":
            value = (*value, 1.0)
        socket.default_value = value
    return n



def noise_ball(nodes, link, scale, detail, threshold):
    """A round lumpy field: max(Noise Texture (``scale``, ``detail``) − ``threshold``, 0) × a Quadratic Sphere
    Gradient Texture over Object coordinates (1 at the centre, 0 from 1 m out). Returns (the field's output
    socket, the sphere gradient's Fac)."""
    coordinates = nodes.new("ShaderNodeTexCoord")
    ball = nodes.new("ShaderNodeTexGradient")
    ball.gradient_type = "QUADRATIC_SPHERE"
    noise = node(nodes, "ShaderNodeTexNoise", Scale=scale, Detail=detail)
    cut = node(nodes, "ShaderNodeMath", Value_001=threshold)
    cut.operation = "SUBTRACT"
    cut.use_clamp = True
    shaped = node(nodes, "ShaderNodeMath")
    shaped.operation = "MULTIPLY"
    link(coordinates.outputs["Object"], ball.inputs["Vector"])
    link(noise.outputs["Fac"], cut.inputs[0])
    link(cut.outputs[0], shaped.inputs[0])
    link(ball.outputs["Fac"], shaped.inputs[1])
    return shaped.outputs[0], ball.outputs["Fac"]

def socket(n, key, output=False):
    """Input (or output) socket ``key`` of ``n`` by name or identifier."""
    sockets = n.outputs if output else n.inputs
    return next(s for s in sockets if s.identifier == key or s.name == key)


def emission_material(name, build):
    """A material whose surface is an Emission of strength 1 with ``build(nodes, link)`` → colour socket."""
    mat, nodes, link = material(name)
    emission = nodes.new("ShaderNodeEmission")
    link(build(nodes, link), emission.inputs["Color"])
    link(emission.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def surface_material(name, build):
    """A material whose Surface is the shader socket ``build(nodes, link)`` returns."""
    mat, nodes, link = material(name)
    link(build(nodes, link), nodes["Output"].inputs["Surface"])
    return mat


def plane(name, size, location=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0), mat=None, segments=1):
    """A square plane (UV map 'UVMap' 0-1 across it) facing +Z before ``rotation``."""
    mesh = bpy.data.meshes.new(name)
    n = segments + 1
    ys, xs = np.mgrid[0:n, 0:n] / segments
    vertices = np.stack([(xs - 0.5) * size, (ys - 0.5) * size, np.zeros_like(xs)], -1).reshape(-1, 3)
    faces = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i) for j in range(segments)
             for i in range(segments)]
    mesh.from_pydata(vertices.tolist(), [], faces)
    uv = mesh.uv_layers.new(name="UVMap")
    corners = np.array([v for f in faces for v in f])
    coords = np.stack([xs.ravel()[corners], ys.ravel()[corners]], -1).astype(np.float32)
    uv.uv.foreach_set("vector", coords.ravel())
    if mat is not None:
        mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    obj.location, obj.rotation_euler = location, rotation
    bpy.context.scene.collection.objects.link(obj)
    return obj


def uv_sphere(name, radius, location, mat=None, segments=48, rings=24):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=segments, ring_count=rings)
    obj = bpy.context.active_object
    obj.name = name
    bpy.ops.object.shade_smooth()
    if mat is not None:
        obj.data.materials.append(mat)
    return obj


def linear_keys(datablock):
    """Make every keyframe of ``datablock``'s action interpolate linearly (constant speed between keys)."""
    for curve in datablock.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = "LINEAR"


def slide_during_shutter(obj, scene, speed_m=0.4, x=0.0):
    """Key ``obj`` to move ``speed_m`` along x a frame at constant speed, at ``x`` on frame 1, and set ``scene`` to
    frame 1 with Render ▸ Motion Blur on, Shutter 0.5 frame centred on it (``speed_m`` / 2 of travel while it is
    open)."""
    for frame in (0, 2):
        obj.location.x = x + speed_m * (frame - 1)
        obj.keyframe_insert("location", index=0, frame=frame)
    linear_keys(obj)
    scene.frame_set(1)
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 0.5


def camera(location, look_at, lens_mm=50.0, resolution=(64, 48), sensor_mm=36.0):
    scene = bpy.context.scene
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens, cam.data.sensor_width = lens_mm, sensor_mm
    cam.location = location
    direction = np.asarray(look_at, float) - np.asarray(location, float)
    from mathutils import Vector

    cam.rotation_euler = Vector(direction).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    return cam


def black_world():
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    bpy.context.scene.world = world
    return world


def sun_and_sky(scene, sun_rotation):
    """A grey-blue world of strength 0.6 and a sun of 3 W/m² turned by ``sun_rotation`` (Euler, radians)."""
    world = black_world()
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.5, 0.55, 0.6, 1.0)
    background.inputs["Strength"].default_value = 0.6
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = sun_rotation
    scene.collection.objects.link(sun)


def checker_image(name, size, colours, colorspace="sRGB", alpha=None, float_buffer=False):
    """A ``size`` × ``size`` image of 2 × 2 cells (bottom-left ``colours[0]``), 8-bit unless ``float_buffer``;
    ``alpha`` [size, size] replaces its alpha."""
    image = bpy.data.images.new(name, size, size, alpha=True, float_buffer=float_buffer)
    image.colorspace_settings.name = colorspace
    half = size // 2
    pixels = np.zeros((size, size, 4), np.float32)
    pixels[..., 3] = 1.0
    for cy in range(2):
        for cx in range(2):
            pixels[cy * half:(cy + 1) * half, cx * half:(cx + 1) * half, :3] = colours[(cx + cy) % 2]
    if alpha is not None:
        pixels[..., 3] = alpha
    image.pixels.foreach_set(pixels.ravel())
    return image


def glow_material(name, make_source, k, emission_colour):
    """A grey Principled Volume (Density 0.5) whose Emission Strength is k × the output ``make_source(nodes)``
    returns (a Noise Texture's Fac, an Attribute's Fac): a volume that glows where the nodes say."""
    mat, nodes, link = material(name)
    scale = node(nodes, "ShaderNodeMath", Value_001=k)
    scale.operation = "MULTIPLY"
    volume = node(nodes, "ShaderNodeVolumePrincipled", Color=(0.5, 0.5, 0.5), Density=0.5,
                  Emission_Color=emission_colour)
    link(make_source(nodes), scale.inputs[0])
    link(scale.outputs[0], volume.inputs["Emission Strength"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    return mat
