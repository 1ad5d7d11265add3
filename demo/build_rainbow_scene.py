"""Build Prism's rainbow demo and save it as a .blend file.

    python demo/build_rainbow_scene.py renders/rainbow.blend      (bpy module)
    python demo/build_rainbow_scene.py renders/rainbow_pt.blend --path-tracing-only   (the comparison)

A slit lamp (a narrow area light at the back of a black tube) shines on a 60° flint prism (N-SF11) on a
pedestal near minimum deviation, and the spectrum lands on a white wall; a glass ball (N-BK7) on the
floor focuses a spot light into a coloured caustic. Both are caustics — light → glass → diffuse
surface → camera — which Prism renders by light tracing (Render ▸ Light Paths ▸ Caustics: Auto).
Needs the Prism add-on registered (its settings live on the data-blocks).
"""

import math
import sys
from pathlib import Path

import bpy
import numpy as np
from mathutils import Matrix

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from build_demo_scene import new_scene, principled, run, save_with_world  # noqa: E402

N_D = 1.78472  # N-SF11 at 587.6 nm: the lamp is aimed for minimum deviation
SIDE, HEIGHT = 0.12, 0.15  # prism triangle side and length (m)
PEDESTAL = 0.3  # the prism stands on a block this high (m)


def glass(name, catalogue_name, ior):
    material = principled(name, (1, 1, 1), Roughness=0.0, **{"Transmission Weight": 1.0, "IOR": ior})
    material.prism.glass_source, material.prism.glass_name = "CATALOGUE", catalogue_name
    return material


def mesh_object(name, vertices, faces, material, matrix=None):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(map(float, v)) for v in vertices], [], faces)
    obj = bpy.data.objects.new(name, mesh)
    obj.data.materials.append(material)
    if matrix is not None:
        obj.matrix_world = Matrix(matrix.tolist())
    bpy.context.scene.collection.objects.link(obj)
    return obj


def rotation_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def frame(x, y, z, origin):
    """4x4 world matrix with columns x, y, z (unit) at ``origin``."""
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = x, y, z, origin
    return m


def slit_lamp_and_prism(scene, at, lamp_distance=0.6, slit=0.004):
    """The prism at ``at`` (its base centre), the lamp and its tube (lamp on the left of the beam);
    returns where the beam leaves the prism."""
    right = np.array([math.sqrt(3) / 2, 0.5, 0.0])  # the light enters this face and leaves by the left one
    incidence = math.asin(N_D * 0.5)
    d_in = rotation_z(-incidence) @ -right
    out = rotation_z(2 * incidence - math.pi / 3) @ d_in
    turn = rotation_z(math.pi / 2 - math.atan2(out[1], out[0]))  # the spectrum goes toward +Y
    d_in, out = turn @ d_in, turn @ out
    corners = [turn @ p for p in ((-SIDE / 2, 0, 0), (SIDE / 2, 0, 0), (0, SIDE * math.sqrt(3) / 2, 0))]
    vertices = [c + at + (0, 0, z) for z in (0.0, HEIGHT) for c in corners]
    prism = mesh_object("Flint prism", vertices, [(0, 2, 1), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)],
                        glass("N-SF11 flint", "N-SF11", N_D))
    prism.data.polygons.foreach_set("use_smooth", [False] * 5)
    up = np.array([0.0, 0.0, 1.0])
    entry = 0.5 * (corners[1] + corners[2]) + at + up * HEIGHT / 2
    across = np.cross(d_in, up)
    lamp_at = entry - lamp_distance * d_in
    data = bpy.data.lights.new("Slit lamp", "AREA")
    data.shape, data.size, data.size_y, data.energy = "RECTANGLE", slit, 0.1, 20.0
    data.prism.color_source, data.prism.temperature_k = "BLACKBODY", 5800.0
    lamp = bpy.data.objects.new("Slit lamp", data)
    lamp.matrix_world = Matrix(frame(across, up, -d_in, lamp_at).tolist())
    scene.collection.objects.link(lamp)
    length = lamp_distance - 0.08
    tube = [lamp_at + d_in * s * length + across * a * slit + up * b * (0.05 + slit)
            for s in (0, 1) for a in (-1, 1) for b in (-1, 1)]
    mesh_object("Lamp tube", tube, [(0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5), (0, 2, 3, 1)],
                principled("Black", (0.02, 0.02, 0.02), Roughness=1.0))
    return 0.5 * (corners[0] + corners[2]) + at + up * HEIGHT / 2, out


def build(path: Path, light_tracing: str = "AUTO") -> None:
    scene = new_scene(640, 360)
    scene.render.engine = "PRISM"
    scene.prism.samples, scene.prism.samples_per_pass = 64, 8
    scene.prism.light_tracing = light_tracing

    white = principled("White wall", (0.8, 0.8, 0.8), Roughness=1.0)
    grey = principled("Floor", (0.25, 0.25, 0.27), Roughness=1.0)
    mesh_object("Floor", [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)], [(0, 1, 2, 3)], grey)
    pedestal_at = np.array([-0.2, 0.0, 0.0])
    s = 0.12
    block = [pedestal_at + (x, y, z) for z in (0, PEDESTAL) for y in (-s, s) for x in (-s, s)]
    mesh_object("Pedestal", block, [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                                    (1, 3, 7, 5)], principled("Dark pedestal", (0.06, 0.06, 0.07), Roughness=0.8))
    exit_point, out = slit_lamp_and_prism(scene, pedestal_at + (0, 0, PEDESTAL))
    wall_y = exit_point[1] + 1.2
    mesh_object("White wall", [(-2.5, wall_y, 0), (2.5, wall_y, 0), (2.5, wall_y, 1.6), (-2.5, wall_y, 1.6)],
                [(0, 3, 2, 1)], white)

    bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=0.12, location=(0.5, -0.3, 0.12))
    ball = bpy.context.active_object
    ball.name = "Glass ball"
    bpy.ops.object.shade_smooth()
    ball.data.materials.append(glass("N-BK7 crown", "N-BK7", 1.5168))
    spot_data = bpy.data.lights.new("Spot", "SPOT")
    spot_data.energy, spot_data.spot_size, spot_data.spot_blend, spot_data.shadow_soft_size = 60.0, 0.45, 0.3, 0.0
    spot_data.prism.color_source, spot_data.prism.temperature_k = "BLACKBODY", 4500.0
    spot = bpy.data.objects.new("Spot", spot_data)
    spot_at = np.array([1.45, -0.95, 0.62])
    aim = np.array([0.5, -0.3, 0.12]) - spot_at
    aim /= np.linalg.norm(aim)
    side = np.cross(aim, (0, 0, 1.0))
    side /= np.linalg.norm(side)
    spot.matrix_world = Matrix(frame(side, np.cross(-aim, side), -aim, spot_at).tolist())
    scene.collection.objects.link(spot)

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 30.0
    eye, target = np.array([0.55, -2.3, 1.05]), np.array([0.0, 0.7, 0.22])
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, (0, 0, 1.0))
    right /= np.linalg.norm(right)
    camera.matrix_world = Matrix(frame(right, np.cross(right, forward), -forward, eye).tolist())
    scene.collection.objects.link(camera)
    scene.camera = camera

    save_with_world(scene, (0.02, 0.02, 0.025), path)


if __name__ == "__main__":
    run(build, "renders/rainbow.blend", "Rainbow scene",
        light_tracing="OFF" if "--path-tracing-only" in sys.argv else "AUTO")
