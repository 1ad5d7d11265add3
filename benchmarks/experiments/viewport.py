"""The rendered viewport's responsiveness: time to the first image and to 16 samples per pixel after
a change, on the grey Cornell box and on the 1M-triangle scene.

Drives the viewport's render thread (``engine.viewport.progressive``) the way the Blender session
does, with the benchmark scenes as tracer scenes: Blender's export of a change (milliseconds for a
material or a light, a mesh read for an edit) is not in these times. Each change is posted to an idle
render (the previous one reached its 16 samples); times run from the post to the frame's publication:

- start: a new viewport (Renderer set-up, BVH build included);
- orbit: the view turns 10 degrees about the scene (camera tables only);
- material: a wall colour changes (spectra, materials and lights rebuilt; triangles kept);
- light: the area light moves (as material);
- object: an object moves (its triangles placed again: geometry and BVH rebuilt).

``python -m benchmarks.experiments.viewport [--quick]`` prints the table.
"""

from __future__ import annotations

import sys
import threading
import time
from dataclasses import replace

import numpy as np

from benchmarks import scenes
from engine.tracer.settings import RenderSettings
from engine.viewport.progressive import Change, ProgressiveRender

TITLE = "Rendered viewport: time to the first image and to 16 spp after a change"
TARGET_SAMPLES = 16
SCENES = {"Cornell box": ("cornell_grey", "ShortBlock"), "1M triangles": ("mesh_1m", "Bumpy")}


class _Recorder:
    """Every published frame with its time; ``wait`` blocks until a frame of a change meets a test."""

    def __init__(self):
        self.frames = []
        self.event = threading.Event()
        self.render = ProgressiveRender(on_frame=self._on_frame)

    def _on_frame(self):
        self.frames.append(self.render.frame)
        self.event.set()

    def post(self, change: Change, timeout: float = 600.0) -> dict:
        """Post ``change`` and time its first frame, first full-resolution frame and 16 spp (s)."""
        started = time.perf_counter()
        number = self.render.update(change)
        first = full = None
        while True:
            if not self.event.wait(timeout):
                raise TimeoutError(f"no frame for change {number}: {self.render.status}")
            self.event.clear()
            if self.render.error:
                raise RuntimeError(self.render.error)
            for frame in [f for f in self.frames if f is not None and f.change == number]:
                first = first or frame
                if frame.divider == 1:
                    full = full or frame
                    if frame.samples >= TARGET_SAMPLES:
                        return {
                            "first image s": round(first.time - started, 4),
                            "first size": f"{first.width}x{first.height}",
                            "full resolution s": round(full.time - started, 4),
                            f"{TARGET_SAMPLES} spp s": round(frame.time - started, 4),
                        }

    def stop(self):
        self.render.stop()


def _orbit(camera, degrees, centre=(0.0, 0.0, 1.0)):
    angle = np.radians(degrees)
    rotation = np.eye(4)
    rotation[:2, :2] = [[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]]
    to_centre, back = np.eye(4), np.eye(4)
    to_centre[:3, 3], back[:3, 3] = -np.asarray(centre), centre
    return replace(camera, camera_to_world=back @ rotation @ to_centre @ camera.camera_to_world)


def _moved_object(scene, name, offset_m):
    index = scene.object_names.index(name)
    vertices = scene.vertices.copy()
    used = np.unique(scene.triangles[scene.triangle_object == index])
    vertices[used] += offset_m
    return replace(scene, vertices=vertices)


def _changes(scene, camera, moving_object):
    """(name, Change) in the order they are measured (each after the previous reached 16 spp)."""
    materials = list(scene.materials)
    materials[0] = replace(materials[0], base_color=(0.7, 0.5, 0.4))
    recoloured = replace(scene, materials=materials)
    light = replace(scene.lights[0], position=scene.lights[0].position + np.array([0.3, 0.2, 0.0]))
    relit = replace(recoloured, lights=[light])
    return [
        ("orbit", Change(camera=_orbit(camera, 10.0))),
        ("material", Change(scene=recoloured)),
        ("light", Change(scene=relit)),
        ("object", Change(scene=_moved_object(relit, moving_object, np.array([0.0, 0.0, 0.1])), geometry=True)),
    ]


def _warm_up(settings):
    recorder = _Recorder()
    try:
        scene = scenes.cornell_grey(resolution=(32, 32))
        recorder.post(Change(scene=scene, geometry=True, camera=scene.camera, settings=settings,
                             samples=TARGET_SAMPLES))
    finally:
        recorder.stop()


def run(quick: bool) -> dict:
    """Rows per scene and change; the region is 320 x 180 (quick) or 960 x 540 pixels."""
    region = (320, 180) if quick else (960, 540)
    settings = RenderSettings(max_bounces=4, threads=0)  # the viewport's default bounces, every core
    _warm_up(settings)  # compile or load the kernels, import the tracer: untimed
    rows = []
    for label, (name, moving_object) in SCENES.items():
        built = time.perf_counter()
        scene = scenes.build(name, resolution=region)
        built = time.perf_counter() - built
        camera = scene.camera
        recorder = _Recorder()
        start = Change(scene=scene, geometry=True, camera=camera, settings=settings, samples=TARGET_SAMPLES)
        try:
            for change_name, change in [("start", start)] + _changes(scene, camera, moving_object):
                rows.append({"scene": label, "triangles": scene.triangle_count, "change": change_name,
                             "region": f"{region[0]}x{region[1]}", **recorder.post(change)})
                print(f"viewport: {rows[-1]}", file=sys.stderr, flush=True)
        finally:
            recorder.stop()
        rows[-5]["scene build s (untimed)"] = round(built, 3)
    return {"rows": rows, "summary": _summary(rows)}


def _summary(rows) -> str:
    def row(scene, change):
        return next(r for r in rows if r["scene"] == scene and r["change"] == change)

    parts = []
    for label in SCENES:
        start, orbit, material, obj = (row(label, c) for c in ("start", "orbit", "material", "object"))
        parts.append(
            f"{label} ({start['triangles']:,} triangles, {start['region']}): a new viewport shows its first "
            f"image after {start['first image s']:.2f} s and {TARGET_SAMPLES} spp after "
            f"{start[f'{TARGET_SAMPLES} spp s']:.2f} s; after an orbit {orbit['first image s'] * 1000:.0f} ms / "
            f"{orbit[f'{TARGET_SAMPLES} spp s']:.2f} s, a material edit {material['first image s'] * 1000:.0f} ms / "
            f"{material[f'{TARGET_SAMPLES} spp s']:.2f} s, an object move {obj['first image s'] * 1000:.0f} ms / "
            f"{obj[f'{TARGET_SAMPLES} spp s']:.2f} s."
        )
    return " ".join(parts)


def main(argv=None) -> None:
    quick = "--quick" in (argv if argv is not None else sys.argv[1:])
    result = run(quick)
    rows = result["rows"]
    keys = list(dict.fromkeys(k for r in rows for k in r))
    print(" | ".join(keys))
    for r in rows:
        print(" | ".join(str(r.get(k, "")) for k in keys))
    print(result["summary"])


if __name__ == "__main__":
    main()
