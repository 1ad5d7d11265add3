"""An HDRI with a small hot region (issue 13): light-sampling the world (its luminance distribution, MIS
against BSDF sampling) against finding it by BSDF-sampled escapes only, at equal render time."""

from __future__ import annotations

import statistics
import time

import numpy as np

from benchmarks.geometry import MeshBuilder, icosphere, quad
from benchmarks.prism_runs import settings_for
from benchmarks.scenes import look_at
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, Scene, World

TITLE = "HDRI with a hot spot: environment sampling against BSDF sampling at equal time"

SUN_RADIANCE = 2000.0  # the hot region's texels, against a sky of 0.3: ~75 % of the light from 0.1 % of the sphere


def hot_spot_image(height: int = 64, width: int = 128) -> np.ndarray:
    """A dim bluish sky and a 2 x 2 texel sun 40° above the horizon (Blender's equirectangular layout)."""
    image = np.empty((height, width, 3), np.float32)
    image[...] = (0.2, 0.3, 0.45)
    row = int(round((0.5 - 40.0 / 180.0) * height))
    column = int(width * 0.6)
    image[row:row + 2, column:column + 2] = SUN_RADIANCE
    return image


def build(resolution: int, sampled: bool) -> Scene:
    """A grey floor with three spheres under the hot-spot HDRI; ``sampled``: light sampling of the world."""
    builder = MeshBuilder()
    builder.add("Floor", 0, quad((-4, -4, 0), (4, -4, 0), (4, 4, 0), (-4, 4, 0)))
    for i, (x, y, r) in enumerate(((-0.9, 0.3, 0.5), (0.4, -0.2, 0.35), (1.1, 0.8, 0.6))):
        builder.add(f"Sphere{i}", 1 + i % 2, icosphere((x, y, r), r, 3))
    vertices, triangles, material, objects, normals = builder.arrays()
    camera = Camera(name="Camera", camera_to_world=look_at((0.0, -5.0, 2.2), (0.0, 0.2, 0.4)),
                    resolution=(resolution, resolution), focal_length_mm=35.0, film_width_mm=36.0,
                    film_height_mm=36.0)
    materials = [Material(name="Floor", base_color=(0.5, 0.5, 0.5)),
                 Material(name="Red", base_color=(0.7, 0.15, 0.1)),
                 Material(name="White", base_color=(0.8, 0.8, 0.8))]
    world = World(kind="image", image_rgb=hot_spot_image(), sampled=sampled, name="HDRI")
    return Scene(vertices=vertices, triangles=triangles, triangle_material=material, materials=materials,
                 camera=camera, world=world, triangle_object=objects, object_names=builder.object_names,
                 corner_normals=normals)


def _render(scene, seconds: float, seed: int, samples_per_pass: int = 4):
    """(image, samples reached, seconds) of a render stopped once ``seconds`` of sampling have passed."""
    settings = settings_for({"samples_per_pass": samples_per_pass}, 1 << 20, seed, threads=2)
    with Renderer(scene, settings) as renderer:
        renderer.render_pass()  # compiles and warms up: not timed
        renderer.restart()
        started = time.perf_counter()
        while time.perf_counter() - started < seconds:
            renderer.render_pass()
        return renderer.image_rgb().astype(np.float64), renderer.samples_done, time.perf_counter() - started


def _rel_mse(image, reference):
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))


def run(quick: bool) -> dict:
    resolution = 32 if quick else 64
    seconds = 4.0 if quick else 20.0
    seeds = (1, 2) if quick else (1, 2, 3)
    reference, ref_spp, _ = _render(build(resolution, True), 3 * seconds if quick else 120.0, 99, 16)
    rows = []
    for sampled in (True, False):
        errors, spp = [], []
        for seed in seeds:
            image, done, _ = _render(build(resolution, sampled), seconds, seed)
            errors.append(_rel_mse(image, reference))
            spp.append(done)
        rows.append({"strategy": "environment sampling + MIS" if sampled else "BSDF sampling only",
                     "seconds": seconds, "samples per pixel": int(statistics.median(spp)),
                     "relMSE": statistics.median(errors)})
    return {"rows": rows, "summary": _summary(rows, resolution, seconds, seeds, ref_spp)}


def _summary(rows, resolution, seconds, seeds, ref_spp) -> str:
    light, bsdf = rows
    factor = bsdf["relMSE"] / light["relMSE"]
    return (
        f"A grey floor and three diffuse spheres ({resolution} x {resolution}, cie x4, 2 threads) under a 128 x 64 "
        f"HDRI whose 2 x 2 texel sun (radiance {SUN_RADIANCE:g} against a sky of ~0.3) gives most of the light. "
        f"Each strategy rendered for {seconds:g} s of sampling (median of {len(seeds)} seeds), relMSE against a "
        f"light-sampled reference of {ref_spp} spp. Environment sampling with MIS reached {light['samples per pixel']} "
        f"spp and relMSE {light['relMSE']:.3g}; BSDF sampling alone {bsdf['samples per pixel']} spp and relMSE "
        f"{bsdf['relMSE']:.3g}: environment sampling is {factor:.3g}x better at equal time."
    )


if __name__ == "__main__":
    from benchmarks.experiments import print_run

    print_run(run, quick=True)
