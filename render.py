"""Render a .blend file with Prism from the command line.

    blender -b scene.blend -P render.py -- --samples 64 --output out.png
    python render.py scene.blend --samples 64 --output out.exr      (bpy module)

Options: ``--samples N``, ``--seed S``, ``--threads T``, ``--frames A..B`` (``#``
in ``--output`` becomes the zero-padded frame number, else ``_NNNN`` is
appended), ``--output`` ``.png`` (the scene's view transform) or ``.exr``
(scene-linear, 32-bit float). ``--lens-diagram out.png`` writes the lens overlay
drawing (cross-section, wavelength-coloured ray fans, spot diagram) of the
camera's real lens, with or without a render.

Chunked renders: ``--chunk-seed K --samples N --output chunk_K.exr`` renders
samples ``K*N .. (K+1)*N-1`` of the seed's sequence and writes an EXR carrying
its sample count; ``--merge a.exr b.exr ... --output merged.exr`` combines
chunks weighted by their samples. Chunks ``0..K-1`` merge to the same image,
bit for bit, as one render of ``K*N`` samples written with ``--chunk-seed 0``
(see ``engine/chunks.py`` for when that holds).

Progress goes to stderr. Exits non-zero with a one-line message when the file
is missing, the scene cannot render, or an argument is wrong.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import os
import re
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
        # Only a registered class counts: importing a copy of the add-on defines one too.
        if getattr(engine_class, "bl_idname", None) == "PRISM" and getattr(engine_class, "is_registered", False):
            return engine_class.__module__.rsplit(".engine.", 1)[0]
    load_addon_package().register()
    return ADDON_PACKAGE


def _frame_range(text: str) -> tuple[int, int]:
    match = re.fullmatch(r"\s*(-?\d+)\s*(?:\.\.\s*(-?\d+)\s*)?", text)
    if not match:
        raise argparse.ArgumentTypeError(f"--frames must look like 1..24 or 7 (got '{text}')")
    first = int(match.group(1))
    last = int(match.group(2)) if match.group(2) is not None else first
    if last < first:
        raise argparse.ArgumentTypeError(f"--frames {text}: the last frame comes before the first")
    return first, last


def parse_arguments(argv: list[str], in_blender: bool) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="render.py",
        description="Render a .blend file with Prism.",
        epilog="Inside Blender: blender -b file.blend -P render.py -- [options]",
    )
    if not in_blender:
        parser.add_argument("blend_file", nargs="?", help="the .blend file to render (not with --merge)")
    parser.add_argument("--samples", type=int, help="samples per pixel (default: the scene's setting)")
    parser.add_argument("--seed", type=int, help="random seed (default: the scene's setting)")
    parser.add_argument("--threads", type=int, help="CPU threads (0 = all cores; default: the scene's setting)")
    parser.add_argument("--frames", type=_frame_range, help="render frames A..B (inclusive) instead of the current one")
    parser.add_argument("--chunk-seed", type=int, help="render sample chunk K (samples K*N..(K+1)*N-1) to an EXR")
    parser.add_argument("--merge", nargs="+", metavar="CHUNK", help="merge chunk EXRs weighted by their samples")
    parser.add_argument("--output", help="output image, .png or .exr")
    parser.add_argument(
        "--lens-diagram",
        metavar="PNG",
        help="also write the lens overlay drawing (cross-section, ray fans, spot diagram) of the camera's real lens",
    )
    arguments = parser.parse_args(argv)
    if arguments.lens_diagram is not None and Path(arguments.lens_diagram).suffix.lower() != ".png":
        parser.error(f"--lens-diagram must end in .png (got '{arguments.lens_diagram}')")
    if arguments.output is None:
        if arguments.lens_diagram is None or arguments.merge:
            parser.error("give --output (an image to render), --lens-diagram, or both")
        if not in_blender and not arguments.blend_file:
            parser.error("give the .blend file to draw")
        return arguments
    suffix = Path(arguments.output).suffix.lower()
    if suffix not in OUTPUT_FORMATS:
        parser.error(f"--output must end in .png or .exr (got '{arguments.output}')")
    if arguments.samples is not None and arguments.samples < 1:
        parser.error(f"--samples must be at least 1 (got {arguments.samples})")
    if arguments.threads is not None and arguments.threads < 0:
        parser.error(f"--threads cannot be negative (got {arguments.threads})")
    if arguments.merge:
        if suffix != ".exr":
            parser.error("--merge writes an EXR: give --output a .exr name")
        if not in_blender and arguments.blend_file:
            parser.error("--merge takes chunk EXRs, not a .blend file")
        return arguments
    if not in_blender and not arguments.blend_file:
        parser.error("give the .blend file to render")
    if arguments.chunk_seed is not None:
        if arguments.chunk_seed < 0:
            parser.error(f"--chunk-seed must be 0 or more (got {arguments.chunk_seed})")
        if arguments.samples is None:
            parser.error("--chunk-seed needs --samples (the chunk's sample count)")
        if suffix != ".exr":
            parser.error("--chunk-seed writes an EXR: give --output a .exr name")
        if arguments.frames is not None:
            parser.error("--chunk-seed renders one frame: leave out --frames")
    return arguments


def open_blend_file(path: str) -> None:
    import bpy

    if not Path(path).is_file():
        raise BatchError(f"Blend file '{path}' does not exist: check the path.")
    try:
        bpy.ops.wm.open_mainfile(filepath=str(Path(path).resolve()))
    except RuntimeError as error:
        raise BatchError(f"Blend file '{path}' cannot be opened: {str(error).strip()}") from None


def frame_output(output: Path, frame: int) -> Path:
    """``out_###.png`` → ``out_007.png``; without ``#``, ``out.png`` → ``out_0007.png``."""
    name = output.name
    runs = list(re.finditer(r"#+", name))
    if runs:
        run = runs[-1]
        name = f"{name[: run.start()]}{frame:0{len(run.group())}d}{name[run.end():]}"
    else:
        name = f"{output.stem}_{frame:04d}{output.suffix}"
    return output.with_name(name)


def _modules():
    package = prism_package_name()
    session = importlib.import_module(f"{package}.engine.session")
    export = importlib.import_module(f"{package}.engine.export")
    chunks = importlib.import_module(f"{package}.engine.chunks")
    return session, export, chunks


def render_frame(arguments: argparse.Namespace, output: Path) -> Path:
    """Render the current frame to ``output``; raise BatchError on failure."""
    import bpy

    session, export, chunks = _modules()
    scene = bpy.context.scene
    try:
        export.export_camera(scene)  # Blender's own "no camera" error names nothing; ours does
    except export.PrismInputError as error:
        raise BatchError(str(error)) from None
    scene.render.engine = "PRISM"
    chunked = arguments.chunk_seed is not None
    session.request = session.RenderRequest(
        samples=arguments.samples,
        seed=arguments.seed,
        threads=arguments.threads,
        sample_offset=arguments.chunk_seed * arguments.samples if chunked else 0,
        quick_first_pass=False,
        keep_film=chunked,
        progress_stream=sys.stderr,
    )
    output.parent.mkdir(parents=True, exist_ok=True)
    image_settings = scene.render.image_settings
    image_settings.file_format = OUTPUT_FORMATS[output.suffix.lower()]
    if image_settings.file_format == "OPEN_EXR":
        image_settings.color_depth = "32"
    scene.render.filepath = str(output)
    scene.render.use_file_extension = False
    try:
        bpy.ops.render.render(write_still=not chunked)
    except RuntimeError as error:
        raise BatchError(session.last_error or str(error).strip()) from None
    finally:
        session.request = None
    if session.last_error:
        raise BatchError(session.last_error)
    if chunked:
        film = session.last_film
        if film is None:
            raise BatchError("The chunk render was cancelled: nothing was written.")
        try:
            chunks.write_exr(output, film.mean, film.samples, film.sample_offset, film.seed)
        except export.PrismInputError as error:
            raise BatchError(str(error)) from None
    if not output.is_file():
        raise BatchError(f"Prism rendered but no image was written to '{output}'.")
    return output


def write_lens_diagram(arguments: argparse.Namespace) -> Path:
    """The lens overlay drawing of the active camera, as a PNG (offscreen GPU)."""
    import bpy

    package = prism_package_name()
    export = importlib.import_module(f"{package}.engine.export")
    drawing = importlib.import_module(f"{package}.ui.lens_overlay_export")
    path = Path(arguments.lens_diagram).resolve()
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        drawing.write_lens_diagram_png(bpy.context.scene, str(path))
    except export.PrismInputError as error:
        raise BatchError(str(error)) from None
    return path


def render_all(arguments: argparse.Namespace) -> list[Path]:
    import bpy

    written = [write_lens_diagram(arguments)] if arguments.lens_diagram else []
    if arguments.output is None:
        return written
    output = Path(arguments.output).resolve()
    if arguments.frames is None:
        return written + [render_frame(arguments, output)]
    scene = bpy.context.scene
    first, last = arguments.frames
    for frame in range(first, last + 1):
        print(f"Prism: frame {frame} ({frame - first + 1}/{last - first + 1})", file=sys.stderr, flush=True)
        scene.frame_set(frame)
        written.append(render_frame(arguments, frame_output(output, frame)))
    return written


def merge(arguments: argparse.Namespace) -> list[Path]:
    _, export, chunks = _modules()
    output = Path(arguments.output).resolve()
    try:
        merged = chunks.merge_chunks([chunks.read_chunk(path) for path in arguments.merge])
        output.parent.mkdir(parents=True, exist_ok=True)
        chunks.write_exr(output, merged.mean, merged.samples, merged.sample_offset, merged.seed)
    except export.PrismInputError as error:
        raise BatchError(str(error)) from None
    print(f"Prism: merged {len(arguments.merge)} chunks, {merged.samples} samples per pixel", file=sys.stderr)
    return [output]


def main(argv: list[str], in_blender: bool) -> int:
    try:
        arguments = parse_arguments(argv, in_blender)
    except SystemExit as exit_request:
        return int(exit_request.code or 0)
    try:
        if arguments.merge:
            written = merge(arguments)
        else:
            if not in_blender:
                open_blend_file(arguments.blend_file)
            written = render_all(arguments)
    except BatchError as error:
        print(f"Prism: error: {error}", file=sys.stderr)
        return 1
    except Exception as error:  # noqa: BLE001 - one line, never only a traceback
        print(f"Prism: error: unexpected {type(error).__name__}: {error}", file=sys.stderr)
        return 1
    for path in written:
        print(f"Prism: wrote {path}", file=sys.stderr)
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
    inside_blender = _running_inside_blender()
    status = main(_script_arguments(inside_blender), inside_blender)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)
