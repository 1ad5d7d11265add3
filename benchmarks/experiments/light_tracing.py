"""Rainbow on a wall: how much sooner light tracing brings the rainbow to a given error than path
tracing alone, measured in the same run.

The scene: a slit lamp (a narrow area light at the back of a black hood) shines on a 60° N-SF11
prism near minimum deviation; the spectrum falls on a white wall 0.8 m away, which the camera looks
at. Every pixel of the rainbow is a caustic path (wall → prism → prism → slit), which a path tracer
finds only when a diffuse bounce from the wall happens to leave toward the prism and the refracted
ray happens to end in the slit.

A long light-traced render (its own seed) is the reference; the rainbow region is where its
light-traced part is brighter than 5 % of its peak. Both strategies then render pass after pass;
after each pass the relMSE over the region (``benchmarks.metrics.relmse``) is recorded against the
render's own time. The target relMSE is what light tracing reaches after a few seconds; path tracing
gets at least 10x that time (``PT_BUDGET``): its time to the target is measured if it gets there,
else bounded from below by its budget.

``python -m benchmarks.experiments.light_tracing [--quick]`` prints the curves and the summary.
"""

from __future__ import annotations

import time

import numpy as np

from benchmarks.geometry import MeshBuilder, quad
from benchmarks.metrics import relmse
from benchmarks.scenes import look_at
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, Scene, World
from engine.tracer.settings import RenderSettings

TITLE = "Light tracing: time for the rainbow of a prism to reach a relMSE, with and without light tracing"
PT_BUDGET = 12.0  # path tracing renders this many times light tracing's time to the target
GLASS = "N-SF11"
N_D = 1.78472  # the glass's n_d: the lamp is aimed for minimum deviation at 587.6 nm


def _quad(centre, u, v):
    """The parallelogram centre ± u ± v (metres) as a ``geometry`` part."""
    c, u, v = (np.asarray(a, float) for a in (centre, u, v))
    return quad(c - u - v, c + u - v, c + u + v, c - u + v)


def _rotate_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rainbow_scene(resolution=(96, 64), side_m=0.12, height_m=0.15, slit_m=(0.006, 0.1), lamp_distance_m=1.0,
                  wall_distance_m=0.8, lamp_power_w=20.0) -> Scene:
    """The prism-and-wall scene (metres, Z up; the prism's apex points +Y, light enters its left face).
    The lamp sits at the back of a black tube that ends just before the prism, so the light reaches the
    prism nearly parallel (within about 1°) and nothing else directly."""
    a, b, c = np.array([-side_m / 2, 0, 0]), np.array([side_m / 2, 0, 0]), np.array([0, side_m * np.sqrt(3) / 2, 0])
    prism = (np.array([[*p[:2], z] for z in (0.0, height_m) for p in (a, b, c)], np.float32),
             np.array([[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]), None)
    left = np.array([-np.sqrt(3) / 2, 0.5, 0.0])
    incidence = np.arcsin(N_D * 0.5)  # minimum deviation: symmetric passage
    d_in = _rotate_z(incidence) @ -left
    up = np.array([0.0, 0.0, 1.0])
    entry = 0.5 * (a + c) + up * height_m / 2
    out = _rotate_z(-(2 * incidence - np.pi / 3)) @ d_in  # deviated by 2 θ - A toward the base
    exit_point = entry + np.array([side_m / 2, 0.0, 0.0])
    wall_centre, wall_normal = exit_point + wall_distance_m * out, -out
    across = np.cross(d_in, up)
    lamp = entry - lamp_distance_m * d_in
    builder = MeshBuilder()
    builder.add("Prism", 1, prism)
    builder.add("Wall", 0, _quad(wall_centre, np.cross(up, wall_normal) * 0.6, up * 0.4))
    tube_length, gap = lamp_distance_m - 0.08, slit_m[0]
    mouth = lamp + d_in * tube_length / 2
    for side in (-1, 1):
        builder.add("Hood", 2, _quad(mouth + side * across * gap, d_in * tube_length / 2, up * (slit_m[1] / 2 + gap)))
        builder.add("Hood", 2, _quad(mouth + side * up * (slit_m[1] / 2 + gap), d_in * tube_length / 2, across * gap))
    builder.add("Hood", 2, _quad(lamp - d_in * 1e-3, across * gap, up * (slit_m[1] / 2 + gap)))
    vertices, triangles, material, objects, _ = builder.arrays(smooth=False)
    eye = wall_centre + 0.55 * wall_normal + 0.25 * up
    focal, film = 35.0, 36.0
    camera = Camera("Camera", look_at(eye, eye - wall_normal), resolution, focal_length_mm=focal, film_width_mm=film,
                    film_height_mm=film * resolution[1] / resolution[0], shift_y=-0.25 / 0.55 * focal / film)
    light = Light("Slit", "area", lamp, direction=d_in, axis_u=up, axis_v=across, power_w=lamp_power_w,
                  size_u_m=slit_m[1], size_v_m=slit_m[0])
    materials = [Material("Wall", base_color=(0.8, 0.8, 0.8)), Material("Prism", kind="dielectric", glass=GLASS),
                 Material("Hood", base_color=(0.02, 0.02, 0.02))]
    return Scene(vertices=vertices.astype(np.float64), triangles=triangles, triangle_material=material,
                 materials=materials, camera=camera, lights=[light], world=World(), triangle_object=objects,
                 object_names=builder.object_names)


def _settings(mode, samples, seed, per_pass=4):
    return RenderSettings(samples=samples, samples_per_pass=per_pass, seed=seed, threads=0, max_bounces=8,
                          light_tracing=mode)


def _curve(scene, mode, region, reference, seconds, target, seed):
    """(seconds, relMSE) after each pass of ``mode`` until ``seconds`` of rendering (or the target for
    light tracing)."""
    points = []
    with Renderer(scene, _settings(mode, 1 << 30, seed)) as r:
        r.render_pass()  # warms caches and thread buffers; not counted
        r.restart()
        while True:
            r.render_pass()
            image = r.film.mean()[region][:, None, :]
            points.append((r.stats["seconds"], relmse(image, reference), r.film.counts.max()))
            if points[-1][0] >= seconds or (mode == "on" and points[-1][1] <= target):
                return points, r.strategy


def _time_to(points, target):
    for seconds, error, _ in points:
        if error <= target:
            return seconds
    return None


def run(quick: bool) -> dict:
    resolution = (64, 40) if quick else (96, 64)
    scene = rainbow_scene(resolution)
    started = time.perf_counter()
    with Renderer(scene, _settings("on", 256 if quick else 1024, 99, per_pass=64)) as ref:
        while ref.samples_done < ref.settings.samples:
            ref.render_pass()
        film = ref.film
        light_part = (film._light_sum / film.light_paths).reshape(film.height, film.width, 3).mean(-1)
        region = light_part > 0.05 * light_part.max()
        reference = ref.film.mean()[region][:, None, :]
    reference_seconds = time.perf_counter() - started
    target = 0.05 if quick else 0.02
    lt, lt_strategy = _curve(scene, "on", region, reference, 60.0, target, 1)
    t_lt = _time_to(lt, target)
    budget = PT_BUDGET * (t_lt or lt[-1][0])
    pt, pt_strategy = _curve(scene, "off", region, reference, budget, target, 1)
    t_pt = _time_to(pt, target)
    rows = []
    for name, points in (("light tracing + path tracing", lt), ("path tracing alone", pt)):
        for seconds, error, spp in points:
            rows.append(dict(strategy=name, seconds=round(seconds, 3), spp=int(spp), relmse=float(error)))
    if t_pt is None:
        guess = pt[-1][0] * pt[-1][1] / target  # if it fell as 1/t from its last point: a rough guess
        ratio = f"> {pt[-1][0] / t_lt:.0f}x sooner (path tracing had not reached it after {pt[-1][0]:.1f} s, " \
                f"relMSE {pt[-1][1]:.3g}; falling as 1/t from there it would need ~{guess:.0f} s)"
    else:
        ratio = f"{t_pt / t_lt:.0f}x sooner (path tracing: {t_pt:.1f} s)"
    summary = (f"Rainbow region ({int(region.sum())} px of {resolution[0]}x{resolution[1]}): relMSE {target} in "
               f"{t_lt:.2f} s with light tracing, {ratio}. Reference: {reference_seconds:.0f} s of light tracing "
               f"(seed 99). Strategies: [{lt_strategy}] vs [{pt_strategy}].")
    return {"rows": rows, "summary": summary}


if __name__ == "__main__":
    from benchmarks.experiments import print_run

    print_run(run)
