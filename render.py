"""Render a .blend file with Prism from the command line.

    blender -b scene.blend -P render.py -- --samples 64 --output out.png
    python render.py scene.blend --samples 64 --output out.exr      (bpy module)

PNG gets the scene's view transform; EXR stays scene-linear. Exits non-zero with
a one-line message when the file is missing, the scene cannot render, or an
argument is wrong.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
from pathlib import Path

ADDON_PACKAGE = "prism_spectral"
ADDON_ROOT = Path(__file__).resolve().parent
OUTPUT_FORMATS = {".png": "PNG", ".exr": "OPEN_EXR"}


class BatchError(Exception):
    """A failure the batch script reports as one line and a non-zero exit status."""


def load_addon_package():
    """Import this directory as the add-on package ``prism_spectral`` (once)."""
    if ADDON_PACKAGE in sys.modules:
        return sys.modules[ADDON_PACKAGE]
    spec = importlib.util.spec_from_file_location(
        ADDON_PACKAGE, ADDON_ROOT / "__init__.py", submodule_search_locations=[str(ADDON_ROOT)]
    )
    module = importlib.util.module_from_spec(spec)
    sys.modules[ADDON_PACKAGE] = module
    spec.loader.exec_module(module)
    return module


def prism_package_name() -> str:
    """The package of the registered Prism engine, registering this directory's copy if needed."""
    import bpy

    for engine_class in bpy.types.RenderEngine.__subclasses__():
        if getattr(engine_class, "bl_idname", None) == "PRISM":
            return engine_class.__module__.rsplit(".engine.", 1)[0]
    load_addon_package().register()
    return ADDON_PACKAGE


def parse_arguments(argv: list[str], in_blender: bool) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="render.py",
        description="Render a .blend file with Prism.",
        epilog="Inside Blender: blender -b file.blend -P render.py -- [options]",
    )
    if not in_blender:
        parser.add_argument("blend_file", help="the .blend file to render")
    parser.add_argument("--samples", type=int, help="samples per pixel (default: the scene's setting)")
    parser.add_argument("--seed", type=int, help="random seed (default: the scene's setting)")
    parser.add_argument("--output", required=True, help="output image, .png or .exr")
    arguments = parser.parse_args(argv)
    if arguments.samples is not None and arguments.samples < 1:
        parser.error(f"--samples must be at least 1 (got {arguments.samples})")
    suffix = Path(arguments.output).suffix.lower()
    if suffix not in OUTPUT_FORMATS:
        parser.error(f"--output must end in .png or .exr (got '{arguments.output}')")
    return arguments


def open_blend_file(path: str) -> None:
    import bpy

    if not Path(path).is_file():
        raise BatchError(f"Blend file '{path}' does not exist: check the path.")
    bpy.ops.wm.open_mainfile(filepath=str(Path(path).resolve()))


def render_still(arguments: argparse.Namespace) -> Path:
    """Render the current scene to ``arguments.output``; raise BatchError on failure."""
    import bpy

    package = prism_package_name()
    session = importlib.import_module(f"{package}.engine.session")
    export = importlib.import_module(f"{package}.engine.export")
    scene = bpy.context.scene
    try:
        export.export_camera(scene)  # Blender's own "no camera" error names nothing; ours does
    except export.PrismInputError as error:
        raise BatchError(str(error)) from None
    scene.render.engine = "PRISM"
    if hasattr(scene, "prism"):
        if arguments.samples is not None:
            scene.prism.samples = arguments.samples
        if arguments.seed is not None:
            scene.prism.seed = arguments.seed
    output = Path(arguments.output).resolve()
    output.parent.mkdir(parents=True, exist_ok=True)
    image_settings = scene.render.image_settings
    image_settings.file_format = OUTPUT_FORMATS[output.suffix.lower()]
    if image_settings.file_format == "OPEN_EXR":
        image_settings.color_depth = "32"
    scene.render.filepath = str(output)
    scene.render.use_file_extension = False
    try:
        bpy.ops.render.render(write_still=True)
    except RuntimeError as error:
        raise BatchError(session.last_error or str(error).strip()) from None
    if session.last_error:
        raise BatchError(session.last_error)
    if not output.is_file():
        raise BatchError(f"Prism rendered but no image was written to '{output}'.")
    return output


def main(argv: list[str], in_blender: bool) -> int:
    try:
        arguments = parse_arguments(argv, in_blender)
    except SystemExit as exit_request:
        return int(exit_request.code or 0)
    try:
        if not in_blender:
            open_blend_file(arguments.blend_file)
        output = render_still(arguments)
    except BatchError as error:
        print(f"Prism: error: {error}", file=sys.stderr)
        return 1
    print(f"Prism: wrote {output}", file=sys.stderr)
    return 0


def _running_inside_blender() -> bool:
    """True under ``blender -P render.py``: argv[0] is Blender, not this script."""
    return Path(sys.argv[0]).resolve() != Path(__file__).resolve()


def _script_arguments(in_blender: bool) -> list[str]:
    """Arguments after ``--`` inside Blender, else everything after the script name."""
    if in_blender:
        return sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    return sys.argv[1:]


if __name__ == "__main__":
    status = 1
    try:
        inside_blender = _running_inside_blender()
        status = main(_script_arguments(inside_blender), inside_blender)
    finally:
        # bpy can hang for ever in a global destructor at exit: leave at once.
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        finally:
            os._exit(status)
