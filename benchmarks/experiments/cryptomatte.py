"""Cryptomatte's cost: one render with the three kinds off and on (the per-chunk counting and the final
ranking), median of three, two threads."""

from __future__ import annotations

import time

import numpy as np

from engine.tracer.pass_table import PassRequest
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, Scene, World
from engine.tracer.settings import RenderSettings

TITLE = "Cryptomatte: cost of the Object, Material and Asset passes"


def _scene(size: int) -> Scene:
    """Two quads side by side 3 m in front of a pinhole (a quarter of the frame), background around."""
    to_world = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], float)  # looking along +Y
    camera = Camera("cam", to_world, (size, size), focal_length_mm=15.0, film_width_mm=36.0, film_height_mm=36.0)
    corners = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], float)
    left = corners * [1.0, 0.0, 1.8] + [-1.0, 3.0, 0.0]
    right = corners * [1.0, 0.0, 1.8] + [1.0, 3.0, 0.0]
    quad = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    return Scene(vertices=np.concatenate([left, right]), triangles=np.concatenate([quad, quad + 4]),
                 triangle_material=np.array([0, 0, 1, 1], np.int32),
                 materials=[Material("red", base_color=(0.8, 0.1, 0.1)), Material("blue", base_color=(0.1, 0.1, 0.8))],
                 camera=camera, world=World((0.2, 0.2, 0.2), 1.0), triangle_object=np.array([0, 0, 1, 1], np.int32),
                 object_names=["Left", "Right"])


def _seconds(size: int, spp: int, per_pass: int, request: PassRequest) -> float:
    times = []
    for _ in range(3):
        settings = RenderSettings(samples=spp, samples_per_pass=per_pass, seed=1, threads=2, passes=request)
        with Renderer(_scene(size), settings) as renderer:
            renderer.render_pass()  # kernels loaded, threads started
            renderer.restart()
            started = time.perf_counter()
            while not renderer.finished:
                renderer.render_pass()
            renderer.pass_images()
            times.append(time.perf_counter() - started)
    return sorted(times)[1]


def run(quick: bool) -> dict:
    cases = [(128, 4, 4)] if quick else [(512, 16, 4), (1024, 4, 1)]
    rows = []
    for size, spp, per_pass in cases:
        off = _seconds(size, spp, per_pass, PassRequest())
        on = _seconds(size, spp, per_pass, PassRequest(cryptomatte=("Object", "Material", "Asset")))
        rows.append({"frame": f"{size} x {size}", "spp": spp, "spp a pass": per_pass, "off (s)": off, "on (s)": on,
                     "cost (%)": 100.0 * (on / off - 1.0)})
    worst = max(row["cost (%)"] for row in rows)
    return {"rows": rows, "summary": f"Two quads covering a quarter of the frame, two threads, median of three "
                                     f"renders; the three Cryptomatte kinds cost at most {worst:.0f} % here."}
