"""Render a .blend with Cycles (CPU) to a PNG, for side-by-side pictures with Prism.

    python demo/render_cycles.py renders/sky.blend renders/sky_cycles.png --samples 256   (bpy module)

The scene's own view transform applies, as it does to Prism's PNG from render.py. No denoising, no
adaptive sampling: the picture shows Cycles' converged estimate of the same file.
"""

import argparse
import sys
from pathlib import Path

import bpy

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from render import exit_now, load_addon_package  # noqa: E402  (the add-on: the file's Prism settings load cleanly)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("blend")
    parser.add_argument("output")
    parser.add_argument("--samples", type=int, default=256)
    args = parser.parse_args()
    load_addon_package().register()
    bpy.ops.wm.open_mainfile(filepath=str(Path(args.blend).resolve()))
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = args.samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    settings = scene.render.image_settings
    settings.file_format, settings.color_mode, settings.color_depth = "PNG", "RGB", "8"
    scene.render.filepath = str(Path(args.output).resolve())
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    print(f"Saved: '{args.output}'", file=sys.stderr)


if __name__ == "__main__":
    main()
    exit_now(0)
