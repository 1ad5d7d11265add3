"""The benchmark scenes, built by script as ``engine.tracer.scene.Scene``.

All scenes are in metres, Z up, Blender conventions. The Cornell-box family is a
2 m box ([-1, 1] x [-1, 1] x [0, 2], open towards -Y) lit by a 0.5 m square
area light under the ceiling and seen by a 50 mm camera on a 36 mm square film.

The same geometry goes to the peers through converters that read these Scene
objects (so the peers can never drift from Prism's geometry):
``benchmarks.peers.mitsuba.scene_dict(scene)`` (a Mitsuba 3 scene dict) and
``benchmarks.peers.cycles.build_blender_scene(scene)`` (a bpy scene for Cycles).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from engine.tracer.scene import Camera, Light, Material, Scene, World

from .geometry import MeshBuilder, box, displaced_sphere, icosphere, quad, triangular_prism

REPO_ROOT = Path(__file__).resolve().parents[1]
WALL_GREY = (0.6, 0.6, 0.6)
LIGHT_RADIANCE = 15.0  # W / (m^2 sr) of the Cornell-box area light
LIGHT_SIZE_M = 0.5
GLASS_NAME = "N-SF11"


def look_at(eye, target, up=(0.0, 0.0, 1.0)):
    """4x4 camera-to-world of a Blender camera at ``eye`` looking at ``target``
    (the camera looks down its local -Z with +Y up)."""
    eye = np.asarray(eye, dtype=np.float64)
    forward = np.asarray(target, dtype=np.float64) - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(up, dtype=np.float64))
    right /= np.linalg.norm(right)
    cam_up = np.cross(right, forward)
    matrix = np.eye(4)
    matrix[:3, 0], matrix[:3, 1], matrix[:3, 2], matrix[:3, 3] = right, cam_up, -forward, eye
    return matrix


def cornell_camera(resolution, **lens):
    """The Cornell-box camera: 3.8 m in front of the box's mouth, 50 mm on a square 36 mm film."""
    return Camera(
        name="Camera",
        camera_to_world=look_at((0.0, -3.8, 1.0), (0.0, 0.0, 1.0)),
        resolution=resolution,
        focal_length_mm=50.0,
        film_width_mm=36.0,
        film_height_mm=36.0,
        **lens,
    )


def cornell_light():
    """A 0.5 m square area light 2 cm under the ceiling pointing down, radiance LIGHT_RADIANCE."""
    area = LIGHT_SIZE_M * LIGHT_SIZE_M
    return Light(
        name="Area",
        kind="area",
        position=np.array([0.0, 0.0, 1.98]),
        direction=np.array([0.0, 0.0, -1.0]),
        axis_u=np.array([1.0, 0.0, 0.0]),
        axis_v=np.array([0.0, 1.0, 0.0]),
        power_w=LIGHT_RADIANCE * np.pi * area,
        size_u_m=LIGHT_SIZE_M,
        size_v_m=LIGHT_SIZE_M,
    )


def _cornell_shell(builder: MeshBuilder, wall: int):
    builder.add("Floor", wall, quad((-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)))
    builder.add("Ceiling", wall, quad((-1, -1, 2), (-1, 1, 2), (1, 1, 2), (1, -1, 2)))
    builder.add("Back", wall, quad((-1, 1, 0), (1, 1, 0), (1, 1, 2), (-1, 1, 2)))
    builder.add("Left", wall, quad((-1, -1, 0), (-1, 1, 0), (-1, 1, 2), (-1, -1, 2)))
    builder.add("Right", wall, quad((1, -1, 0), (1, -1, 2), (1, 1, 2), (1, 1, 0)))


def _scene(builder, materials, camera, lights, world=None, smooth=True):
    vertices, triangles, material, objects, normals = builder.arrays(smooth=smooth)
    return Scene(
        vertices=vertices,
        triangles=triangles,
        triangle_material=material,
        materials=materials,
        camera=camera,
        lights=lights,
        world=world or World(),
        triangle_object=objects,
        object_names=builder.object_names,
        corner_normals=normals,
    )


def cornell_grey(resolution=(64, 64), camera=None):
    """Grey (spectrally flat, albedo 0.6) Cornell box with a short and a tall block."""
    builder = MeshBuilder()
    materials = [Material(name="Grey", base_color=WALL_GREY)]
    _cornell_shell(builder, 0)
    builder.add("ShortBlock", 0, box((0.35, -0.3, 0.3), (0.6, 0.6, 0.6), -0.3))
    builder.add("TallBlock", 0, box((-0.35, 0.3, 0.6), (0.6, 0.6, 1.2), 0.3))
    return _scene(builder, materials, camera or cornell_camera(resolution), [cornell_light()], smooth=False)


def cornell_glass(resolution=(64, 64)):
    """The grey box with a dispersive N-SF11 ball (radius 0.45 m) beside the short block."""
    builder = MeshBuilder()
    materials = [
        Material(name="Grey", base_color=WALL_GREY),
        Material(name="Glass", kind="dielectric", glass=GLASS_NAME),
    ]
    _cornell_shell(builder, 0)
    builder.add("ShortBlock", 0, box((0.45, 0.35, 0.3), (0.5, 0.5, 0.6), -0.3))
    builder.add("GlassBall", 1, icosphere((-0.3, -0.2, 0.45), 0.45, 4))
    return _scene(builder, materials, cornell_camera(resolution), [cornell_light()])


def soap_bubble(resolution=(64, 64)):
    """The grey box with a free-standing soap film sphere (450 nm, n = 1.33)."""
    builder = MeshBuilder()
    materials = [
        Material(name="Grey", base_color=WALL_GREY),
        Material(name="Soap", kind="thin_film", film_thickness_nm=450.0, film_ior=1.33),
    ]
    _cornell_shell(builder, 0)
    builder.add("TallBlock", 0, box((-0.45, 0.45, 0.6), (0.5, 0.5, 1.2), 0.3))
    builder.add("Bubble", 1, icosphere((0.15, -0.2, 0.8), 0.5, 4))
    return _scene(builder, materials, cornell_camera(resolution), [cornell_light()])


def mesh_1m(resolution=(64, 64)):
    """The grey box holding a bumpy displaced sphere of 1,000,000 flat triangles."""
    builder = MeshBuilder()
    materials = [Material(name="Grey", base_color=WALL_GREY)]
    _cornell_shell(builder, 0)
    builder.add("Bumpy", 0, displaced_sphere((0.0, 0.0, 0.75), 0.65, rings=501, segments=1000))
    return _scene(builder, materials, cornell_camera(resolution), [cornell_light()], smooth=False)


def double_gauss_lens_file() -> str:
    """The repository's double Gauss lens prescription (lenses/*gauss*), absolute path."""
    candidates = sorted((REPO_ROOT / "lenses").glob("*gauss*.lens")) + sorted(
        (REPO_ROOT / "lenses").glob("*gauss*")
    )
    if not candidates:
        raise FileNotFoundError("no double Gauss lens file under lenses/ yet")
    return str(candidates[0])


def lens_cornell(resolution=(64, 64)):
    """The grey Cornell box seen through the real double Gauss lens at f/2.8,
    focused on the tall block (about 4.9 m)."""
    camera = cornell_camera(
        resolution, model="real_lens", lens_file=double_gauss_lens_file(), fstop=2.8, focus_distance_m=4.9
    )
    return cornell_grey(resolution, camera=camera)


# Prism set-up: a tall white slit light shines on a 60 degree N-SF11 prism near
# minimum deviation (incidence ~63 deg, deviation ~66 deg towards the base); the
# dispersed fan falls on a white screen. The camera stands inside the fan, between
# prism and screen, looking back into the prism: there the slit appears as a
# spectrum (the rainbow the screen receives, seen at its source). A camera on the
# screen itself would need a caustic path (screen -> prism -> slit), which a
# unidirectional path tracer finds with probability ~1e-3 per sample.
PRISM_ROTATION_RAD = np.radians(-33.0)
PRISM_DEVIATION_RAD = np.radians(-66.0)


def prism(resolution=(64, 64), slit_width_m=0.06, slit_height_m=0.3, slit_distance_m=0.9,
          light_radiance=5.0, camera_distance_m=0.5, screen_distance_m=1.2):
    """60 degree prism, white slit light, screen behind the camera (the rainbow scene)."""
    builder = MeshBuilder()
    materials = [
        Material(name="Screen", base_color=(0.8, 0.8, 0.8)),
        Material(name="Glass", kind="dielectric", glass=GLASS_NAME),
    ]
    z0 = 0.5
    side = 0.16
    builder.add("Prism", 1, triangular_prism((0.0, 0.0, z0), side, 0.6, PRISM_ROTATION_RAD))
    # aim the slit at the middle of the entry face (between the corners at 57 and 177 deg)
    corners = np.radians([57.0, 177.0])
    y0 = float(np.mean(np.sin(corners))) * side / np.sqrt(3.0)
    d = np.array([np.cos(PRISM_DEVIATION_RAD), np.sin(PRISM_DEVIATION_RAD), 0.0])
    across = np.array([-d[1], d[0], 0.0])
    centre = np.array([0.0, 0.0, z0]) + screen_distance_m * d
    half = 0.4
    quad_corners = [centre + sx * half * across + np.array([0, 0, sz * half])
                    for sx, sz in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    if np.dot(np.cross(quad_corners[1] - quad_corners[0], quad_corners[2] - quad_corners[0]), d) > 0:
        quad_corners = quad_corners[::-1]
    builder.add("Screen", 0, quad(*quad_corners))
    light = Light(
        name="Slit",
        kind="area",
        position=np.array([-slit_distance_m, y0, z0]),
        direction=np.array([1.0, 0.0, 0.0]),
        axis_u=np.array([0.0, 0.0, 1.0]),
        axis_v=np.array([0.0, 1.0, 0.0]),
        power_w=light_radiance * np.pi * slit_width_m * slit_height_m,
        size_u_m=slit_height_m,
        size_v_m=slit_width_m,
    )
    eye = np.array([0.0, 0.0, z0]) + camera_distance_m * d
    camera = Camera(
        name="Camera",
        camera_to_world=look_at(eye, (0.0, 0.0, z0)),
        resolution=resolution,
        focal_length_mm=50.0,
        film_width_mm=36.0,
        film_height_mm=36.0,
    )
    return _scene(builder, materials, camera, [light], world=World((1.0, 1.0, 1.0), 0.02), smooth=False)


@dataclass(frozen=True)
class BenchScene:
    """A benchmark scene: builder, and which peers can render it (same physics)."""

    name: str
    build: object
    description: str
    peers: tuple[str, ...] = ()
    dispersive: bool = False


SCENES = {
    s.name: s
    for s in (
        BenchScene("cornell_grey", cornell_grey, "grey Cornell box, area light", ("cycles", "mitsuba")),
        BenchScene("cornell_glass", cornell_glass, "Cornell box + N-SF11 glass ball", (), True),
        BenchScene("prism", prism, "60 deg N-SF11 prism, slit light seen through it", (), True),
        BenchScene("lens", lens_cornell, "grey Cornell box through the double Gauss", ()),
        BenchScene("soap_bubble", soap_bubble, "Cornell box + 450 nm soap film sphere", ()),
        BenchScene("mesh_1m", mesh_1m, "Cornell box + 1M-triangle displaced sphere", ("mitsuba",)),
    )
}


def build(name: str, resolution=(64, 64)) -> Scene:
    """Build the named benchmark scene at ``resolution`` (width, height)."""
    scene = SCENES[name].build(resolution)
    scene.validate()
    return scene
