"""Volume Scatter's phase functions against Cycles 4.5, in absolute light: a scattering cube (Color 0.9,
Density 1) under a white world of strength 0.5 and a sun of 3 W/m² from behind and to the side (its light
leaves 30° below the horizon, turned 46° about z), so that the camera sees sunlight scattered at angles
where the phase functions differ. For Rayleigh and Draine one render each (512 spp) agrees with Cycles'
within 3 % in the mean luminance of the cube's pixels. Mie (20 µm droplets) and Fournier-Forand peak so
sharply forward that single renders scatter by up to 14 % from seed to seed in Prism (a scattering toward the
sun's disc weighs much); the mean of four Prism seeds and two Cycles seeds agree within 8 % (Cycles 4.5 also
samples Fournier-Forand by a Newton iteration that misplaces its forward peak: docs/media.md, "Phase
functions"). The export warns of nothing."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world, camera, material, node

#: (inputs, seeds Prism and Cycles average over, tolerance of Prism / Cycles)
PHASES = {
    "RAYLEIGH": ({}, 1, 0.03),
    "FOURNIER_FORAND": ({"IOR": 1.1, "Backscatter": 0.05}, 4, 0.08),
    "DRAINE": ({"Anisotropy": 0.6, "Alpha": 0.5}, 1, 0.03),
    "MIE": ({"Diameter": 20.0}, 4, 0.08),
}


def _scatter_cube(phase, inputs):
    mat, nodes, link = material(f"Haze {phase}")
    scatter = node(nodes, "ShaderNodeVolumeScatter", Color=(0.9, 0.9, 0.9), Density=1.0, **inputs)
    scatter.phase = phase
    link(scatter.outputs[0], nodes["Output"].inputs["Volume"])
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0.0, 0.0, 1.0))
    bpy.context.active_object.data.materials.append(mat)
    return mat


@pytest.mark.parametrize("phase", PHASES)
def test_volume_scatter_phase_function_matches_cycles(prism_addon, fresh_scene, phase):
    nodes_module = importlib.import_module(f"{prism_addon.__name__}.engine.export.nodes")
    inputs, seeds, tolerance = PHASES[phase]
    black_world().node_tree.nodes["Background"].inputs["Strength"].default_value = 0.5
    mat = _scatter_cube(phase, inputs)
    compiled = nodes_module.compile_material(mat, load_pixels=False)
    assert compiled.warnings == [] and compiled.medium.phase[0][1] == phase
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (-0.5236, 0.0, 0.8)
    fresh_scene.collection.objects.link(sun)
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    region = (slice(6, 18), slice(6, 18))
    fresh_scene.prism.max_bounces = 32
    prism = [luminance(render_prism_rgba(fresh_scene, 512 // seeds, seed))[region].mean() for seed in range(seeds)]
    cycles = [luminance(render_cycles_rgba(fresh_scene, 512 // seeds, seed, max_bounces=32))[region].mean()
              for seed in range(max(seeds // 2, 1))]
    ratio = np.mean(prism) / np.mean(cycles)
    print(f"MEASURED {phase} scattering cube: Prism {np.round(prism, 5).tolist()}, Cycles "
          f"{np.round(cycles, 5).tolist()}, ratio of the means {ratio:.4f}")
    assert ratio == pytest.approx(1.0, abs=tolerance)
