"""What the warm-up runs: the smallest render that compiles the kernels a typical F12 needs, and the
constant folder the export runs on node materials.

Built as an ``engine.tracer.scene.Scene`` (no Blender): a clay-coloured floor and back wall (diffuse; a
colour that is not grey, as in most scenes, is upsampled from the kernels' table: ``rgb_lut``), a
dispersive glass wedge (dielectric with a catalogue glass: wavelength termination, refraction), an
area light and a point light, a dim constant world, seen by a pinhole camera. Kernels are typed by the
arrays' dtypes and the tables' layout, not by their sizes or values, so this stands for larger scenes of
the same kinds; every array has the dtype the Blender export hands over (``engine.export``). The scene's
materials are not node trees, so ``fold_once`` compiles the folder separately (called from Python, it is
its own compiled entry: 11 s of the first F12's export when it was missing).
"""

from __future__ import annotations

import numpy as np

from ..tracer.scene import Camera, Light, Material, Scene, World

RESOLUTION = (8, 8)  # pixels: the kernels' cost is compiling them, not running them


def _quad(p0, p1, p2, p3):
    return [p0, p1, p2, p3], [[0, 1, 2], [0, 2, 3]]


def _wedge():
    """A closed triangular prism (m): 6 corners, 8 triangles, outward faces."""
    a, b, c = (-0.3, -0.2, 0.0), (0.3, -0.2, 0.0), (0.0, 0.3, 0.0)
    top = [(x, y, 0.6) for x, y, _ in (a, b, c)]
    corners = [a, b, c, *top]
    triangles = [[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]
    return corners, triangles


def _camera() -> Camera:
    # 3 m in front of the wedge looking along +Y (a Blender camera looks down its local -Z, +Y up).
    camera_to_world = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, -3.0], [0.0, 1.0, 0.0, 0.4],
                                [0.0, 0.0, 0.0, 1.0]])
    return Camera(name="Camera", camera_to_world=camera_to_world, resolution=RESOLUTION, focal_length_mm=50.0,
                  film_width_mm=36.0, film_height_mm=36.0)


def warmup_scene() -> Scene:
    """The warm-up scene (see the module docstring), validated."""
    parts = [
        (_quad((-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)), 0),  # floor
        (_quad((-2, 1, 0), (2, 1, 0), (2, 1, 2), (-2, 1, 2)), 0),  # back wall
        (_wedge(), 1),
    ]
    vertices, triangles, material, owner = [], [], [], []
    for index, ((corners, faces), material_index) in enumerate(parts):
        triangles.append(np.asarray(faces, np.int32) + sum(len(v) for v in vertices))
        vertices.append(np.asarray(corners, np.float64))
        material.append(np.full(len(faces), material_index, np.int32))
        owner.append(np.full(len(faces), index, np.int32))
    lights = [
        Light(name="Area", kind="area", position=np.array([0.0, -0.5, 1.8]), power_w=40.0, size_u_m=0.5,
              size_v_m=0.5),
        Light(name="Point", kind="point", position=np.array([1.0, -1.0, 1.0]), power_w=20.0, radius_m=0.05),
    ]
    scene = Scene(
        vertices=np.concatenate(vertices),
        triangles=np.concatenate(triangles),
        triangle_material=np.concatenate(material),
        materials=[Material(name="Clay", base_color=(0.6, 0.5, 0.4)),
                   Material(name="Glass", kind="dielectric", glass="N-SF11")],
        camera=_camera(),
        lights=lights,
        world=World(color=(0.05, 0.05, 0.05)),
        triangle_object=np.concatenate(owner),
        object_names=["Floor", "Wall", "Wedge"],
    )
    scene.validate()
    return scene


def fold_once() -> None:
    """Run the export's constant folder (``materials.folding``) on an empty program: compiles it."""
    from ..tracer.materials.folding import fold_evaluator
    from ..tracer.materials.opcodes import INSTRUCTION

    fold_evaluator()(np.zeros((0, INSTRUCTION), np.int32), np.zeros(1))
