"""Peak memory of very large frames rendered through Blender (render.py with the bpy module), tiled."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TITLE = "Frames of any size: peak memory of a 16384 x 16384 render"

REPO = Path(__file__).resolve().parents[2]
GB = 1024**3

_BUILD = r"""
import sys, bpy
sys.path.insert(0, {repo!r})
from render import load_addon_package
load_addon_package().register()
bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
scene = bpy.context.scene
scene.render.engine = "PRISM"
bpy.ops.mesh.primitive_plane_add(size=4.0)
material = bpy.data.materials.new("glow")
material.use_nodes = True
principled = material.node_tree.nodes["Principled BSDF"]
principled.inputs["Emission Color"].default_value = (1.0, 0.8, 0.6, 1.0)
principled.inputs["Emission Strength"].default_value = 1.0
bpy.context.object.data.materials.append(material)
camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
camera.location = (0.0, 0.0, 3.0)
scene.collection.objects.link(camera)
scene.camera = camera
scene.render.resolution_x = scene.render.resolution_y = {size}
scene.render.resolution_percentage = 100
scene.prism.max_bounces = 0
scene.prism.samples_per_pass = 1
if {all_passes}:
    layer = scene.view_layers[0]
    for name in ("z", "position", "normal", "emit", "environment", "diffuse_direct", "diffuse_indirect",
                 "diffuse_color", "glossy_direct", "glossy_indirect", "glossy_color", "transmission_direct",
                 "transmission_indirect", "transmission_color"):
        setattr(layer, "use_pass_" + name, True)
    scene.prism.use_pass_denoising_data = True
bpy.ops.wm.save_as_mainfile(filepath={blend!r})
from render import exit_now
exit_now(0)  # the bpy module can hang at interpreter exit
"""


def _render(size: int, all_passes: bool, folder: Path) -> dict:
    blend = folder / f"frame_{size}.blend"
    subprocess.run([sys.executable, "-c", _BUILD.format(repo=str(REPO), size=size, blend=str(blend),
                                                         all_passes=all_passes)],
                   check=True, capture_output=True, timeout=300)
    output = folder / f"frame_{size}.exr"
    started = time.perf_counter()
    process = subprocess.Popen([sys.executable, str(REPO / "render.py"), str(blend), "--samples", "1", "--threads",
                                "2", "--output", str(output)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True)
    _, status, usage = os.wait4(process.pid, 0)
    seconds = time.perf_counter() - started
    stderr = process.stderr.read()
    process.stderr.close()
    exit_code = os.waitstatus_to_exitcode(status)
    lines = [line for line in stderr.splitlines() if line.strip()]
    verdict = lines[-1] if lines else ""
    row = {"frame": f"{size} x {size}", "passes": "all" if all_passes else "Combined", "exit status": exit_code,
           "seconds": round(seconds, 1), "peak memory (GB)": round(usage.ru_maxrss * 1024 / GB, 2),
           "file (GB)": round(output.stat().st_size / GB, 2) if output.exists() else 0.0}
    if exit_code:
        row["message"] = verdict.removeprefix("Prism: error: ")
    output.unlink(missing_ok=True)
    return row


def run(quick: bool) -> dict:
    from engine.tracer.frame_plan import available_memory_bytes

    sizes = [(4096, False), (20000, True)] if quick else [(16384, False), (20000, True)]
    with tempfile.TemporaryDirectory() as directory:
        rows = [_render(size, passes, Path(directory)) for size, passes in sizes]
    available = available_memory_bytes()
    big = rows[0]
    refused = rows[1]
    summary = (
        f"One emissive plane filling the frame, 1 sample per pixel, 2 threads, tiles of 2048 px (the default), "
        f"rendered by `render.py` with the bpy module to a 32-bit EXR; peak memory is the process's maximum "
        f"resident set (`wait4`). A {big['frame']} frame peaked at {big['peak memory (GB)']} GB and took "
        f"{big['seconds']} s (exit status {big['exit status']}). The {refused['frame']} frame with every pass on "
        f"{'was refused after ' + str(refused['seconds']) + ' s: ' + refused.get('message', '') if refused['exit status'] else 'rendered'}"
        f" (memory available when measured: {available / GB:.1f} GB)."
    )
    return {"rows": rows, "summary": summary}
