"""Prism against Cycles 4.5 on Volume objects that emit: the probe behind docs/media.md "Fire" and
``export.volume_emission.FULL_BOX_GLOW_VS_CYCLES``.

    .venv/bin/python tools/volume_emission_vs_cycles.py [VARIANT ...]

Each variant writes the 16³ sphere of tests/blender/test_volume_objects.py (or, for "box…", a full box of
ones) with a "temperature" grid, loads it as that test's Volume object (moved, turned, squashed) with a
Principled Volume (Color 0.5, Blackbody Intensity 1) and renders it in the dark with both engines (24 × 24
px; Cycles 256 spp at Step Rate 0.1, Prism 64 spp), printing the mean luminance of the middle 16 × 16
pixels and their ratio. "cube" is the same light in a mesh cube of the box's size (homogeneous in both
engines); "boxconst" the full box without a temperature grid (the Temperature alone fills the volume).
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

#: name: (temperature grid from the density values, Temperature K, Density)
VARIANTS = {
    "test": (lambda v: 1.5 * v, 1500.0, 0.5),
    "thin": (lambda v: 1.5 * v, 1500.0, 0.01),
    "flat": (lambda v: (v > 0) * 1.0, 2000.0, 0.01),
    "hot": (lambda v: 1.5 * v, 4000.0, 0.01),
    "warm": (lambda v: 1.0 * v, 1000.0, 0.01),
    "thinplain": (lambda v: 1.5 * v, 1500.0, 0.01),
    "boxconstplain": (lambda v: np.ones_like(v), 2000.0, 0.01),
    "boxconst": (lambda v: np.ones_like(v), 2000.0, 0.01),
    "cube": (lambda v: np.ones_like(v), 2000.0, 0.01),
    "box": (lambda v: np.ones_like(v), 2000.0, 0.01),
    "boxramp": (lambda v: np.broadcast_to(np.linspace(0.2, 1.0, 16)[:, None, None], v.shape).copy(), 2000.0, 0.01),
}


def _write_grids(vdb, t, path, label, heat_of):
    values = t._write_sphere(vdb, path)
    if label.startswith("box"):
        values = np.ones_like(values)
    grids = []
    for name, array in (("density", values), ("temperature", heat_of(values).astype(np.float32))):
        grid = vdb.FloatGrid()
        grid.name = name
        grid.copyFromArray(array, ijk=(0, 0, 0))
        transform = vdb.createLinearTransform(voxelSize=t.VOXEL_M)
        transform.postTranslate((t.VOXEL_M / 2 - 1.0,) * 3)
        grid.transform = transform
        grids.append(grid)
    vdb.write(path, grids=grids)


def run(bpy, package, label):
    import test_volume_objects as t
    from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
    from helpers.node_scenes import black_world, camera

    heat_of, temperature, density = VARIANTS[label]
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    vdb = importlib.import_module(f"{package.__name__}.engine.export.volume_grids").openvdb_module()
    path = f"/tmp/prism_volume_emission_{label}.vdb"
    _write_grids(vdb, t, path, label, heat_of)
    mat = t._smoke(Color=(0.5, 0.5, 0.5), Density=density, Blackbody_Intensity=1.0, Temperature=temperature)
    principled = next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeVolumePrincipled")
    if label.startswith("boxconst"):
        principled.inputs["Temperature Attribute"].default_value = ""
    if label == "cube":
        bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0.1, 0.0, 1.0), rotation=(0.0, 0.3, 0.5),
                                        scale=(1.3, 1.0, 0.8))
        bpy.context.active_object.data.materials.append(mat)
    else:
        obj = t._volume_object(path, mat)
        if label.endswith("plain"):  # unturned and unscaled: its index axes along the world's
            obj.rotation_euler, obj.scale = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
    black_world()
    camera((0.0, -6.0, 1.0), (0.1, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    scene.cycles.volume_step_rate, scene.cycles.volume_max_steps = 0.1, 4096
    cycles = render_cycles_rgba(scene, 256, max_bounces=32)
    scene.prism.max_bounces = 32
    prism = render_prism_rgba(scene, 64, seed=0)
    region = (slice(4, 20), slice(4, 20))
    p, c = luminance(prism)[region].mean(), luminance(cycles)[region].mean()
    print(f"{label}: Prism {p:.5f} Cycles {c:.5f} ratio {p / c:.4f}", flush=True)


def main():
    sys.path[:0] = [str(ROOT), str(ROOT / "tests"), str(ROOT / "tests" / "blender")]
    import bpy

    from render import load_addon_package

    package = load_addon_package()
    package.register()
    for label in sys.argv[1:] or list(VARIANTS):
        run(bpy, package, label)


if __name__ == "__main__":
    main()
