"""Render a .blend file with Prism from the command line.

    blender -b scene.blend -P render.py -- --samples 64 --output out.png
    python render.py scene.blend --samples 64 --output out.exr      (bpy module)

Options: ``--samples N``, ``--seed S``, ``--threads T``, ``--noise-threshold T`` and
``--min-samples N`` (adaptive sampling), ``--time-limit SECONDS``, ``--frames A..B`` (``#``
in ``--output`` becomes the zero-padded frame number, else ``_NNNN`` is
appended; without ``--frames``, ``#`` becomes the current frame's number, as in
Blender), ``--output`` ``.png`` (the scene's view transform) or ``.exr``
(scene-linear, 32-bit float; a multilayer EXR with every pass when the view
layer has passes besides Combined). ``--lens-diagram out.png`` writes the lens overlay
drawing (cross-section, wavelength-coloured ray fans, spot diagram) of the
camera's real lens, with or without a render.

Chunked renders: ``--chunk-seed K --samples N [--frames F] --output chunk_K.exr``
renders samples ``K*N .. (K+1)*N-1`` of the seed's sequence of frame F (default:
the current frame) and writes an EXR carrying its sample range, seed, a
fingerprint of the frame, scene and settings, and the settings the scene writes
PNGs with; ``--merge a.exr b.exr ... [--expect-samples TOTAL] --output
merged.exr|.png`` checks the chunks belong to one render (and, with
``--expect-samples``, hold samples ``0..TOTAL-1`` with none missing) and combines
them weighted by their samples. Chunks ``0..K-1`` merge to the same image, bit
for bit, as one render of ``K*N`` samples written with ``--chunk-seed 0`` (see
``engine/render/chunks.py`` for when that holds); a merged PNG has the pixels of that
render's PNG.

``--spectral-output spectra.exr`` also writes a multispectral EXR (the layout
of Fichet et al. 2021, read by colour-science): radiance in wavelength bands
across 360-830 nm, band width from Render ▸ Prism ▸ Spectral Output.

Every output is written whole or not at all (a temporary file, then one rename).
Ctrl-C (or SIGTERM) stops the render after the current chunk: the file being
rendered is not written (``--keep-partial`` keeps it as ``NAME.partial.exr``),
files already finished stay, and the exit status is 130 (143 for SIGTERM).

Progress goes to stderr: a ``Time: …`` line per pass (Blender's own format, which
render farms such as Flamenco count as progress steps) and ``Saved: '…'`` naming
each finished file. Exit status: 0 done, 1 the scene or a file cannot be used
(one line naming the object and the fix), 2 a wrong argument, 130/143
interrupted.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import sys
from contextlib import contextmanager
from pathlib import Path

ADDON_PACKAGE = "prism_spectral"
ADDON_ROOT = Path(__file__).resolve().parent
OUTPUT_FORMATS = {".png": "PNG", ".exr": "OPEN_EXR"}


def addon_package_shell():
    """This directory as the package ``prism_spectral`` without running its ``__init__`` (which
    imports bpy): enough to import ``prism_spectral.engine...`` in a process without Blender."""
    if ADDON_PACKAGE not in sys.modules:
        spec = importlib.util.spec_from_file_location(
            ADDON_PACKAGE, ADDON_ROOT / "__init__.py", submodule_search_locations=[str(ADDON_ROOT)]
        )
        sys.modules[ADDON_PACKAGE] = importlib.util.module_from_spec(spec)
    return sys.modules[ADDON_PACKAGE]


def load_addon_package():
    """Import this directory as the add-on package ``prism_spectral`` (once)."""
    module = addon_package_shell()
    if not hasattr(module, "register"):  # a shell until now: run the add-on's ``__init__`` in it
        module.__spec__.loader.exec_module(module)
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


class Prism:
    """The modules of the registered Prism add-on the batch script drives."""

    def __init__(self, package: str):
        self.package = package
        self.arguments = self.module("engine.batch.arguments")
        self.output_files = self.module("engine.batch.output_files")
        self.stop_signals = self.module("engine.batch.stop_signals")
        self.requests = self.module("engine.render.request")
        self.export = self.module("engine.export")
        self.errors = self.module("engine.tracer.errors")

    def module(self, name: str):
        """``engine.render.chunks`` etc. of the add-on (imported on first use: some pull in OpenImageIO or the GPU)."""
        return importlib.import_module(f"{self.package}.{name}")

    def chunks(self):
        return self.module("engine.render.chunks")


def open_blend_file(path: str, prism: Prism) -> None:
    import bpy

    if Path(path).is_dir():
        raise prism.errors.PrismInputError(f"Blend file '{path}' is a folder: give the .blend file itself.")
    if not Path(path).is_file():
        raise prism.errors.PrismInputError(f"Blend file '{path}' does not exist: check the path.")
    try:
        bpy.ops.wm.open_mainfile(filepath=str(Path(path).resolve()))
    except RuntimeError as error:
        raise prism.errors.PrismInputError(
            f"Blend file '{path}' cannot be opened ({_blender_message(error)}): check it is a .blend file "
            "saved by this or an earlier Blender."
        ) from None


def _blender_message(error: Exception) -> str:
    """Blender's operator errors read ``Error: ...\n``: keep the text."""
    text = str(error).strip()
    return text[len("Error:"):].strip() if text.startswith("Error:") else text


def check_scene(scene, prism: Prism) -> None:
    """Failures Blender would report before Prism runs, or without naming the fix."""
    prism.export.export_camera(scene)  # Blender's own "no camera" error names nothing; ours does
    width, height = prism.export.render_resolution(scene)
    prism.export.render_border(scene, width, height)  # Blender says only "Image too small"


def batch_request(arguments, prism: Prism, signals, spectral_output: Path | None = None):
    """The RenderRequest of one batch frame: the command line's overrides, no quick first pass."""
    chunked = arguments.chunk_seed is not None
    return prism.requests.RenderRequest(
        spectral_output=str(spectral_output) if spectral_output else None,
        samples=arguments.samples,
        seed=arguments.seed,
        threads=arguments.threads,
        noise_threshold=arguments.noise_threshold,
        min_samples=arguments.min_samples,
        time_limit_s=arguments.time_limit,
        sample_offset=arguments.chunk_seed * arguments.samples if chunked else 0,
        quick_first_pass=False,
        keep_film=chunked,
        progress_stream=sys.stderr,
        stop_requested=signals.stop_requested,
    )


def render_frame(arguments, output: Path, prism: Prism, signals, frame: int | None = None) -> Path:
    """Render the current frame to ``output`` (whole, or not at all); frame ``frame`` of a --frames run."""
    import bpy

    scene = bpy.context.scene
    check_scene(scene, prism)
    scene.render.engine = "PRISM"
    chunked = arguments.chunk_seed is not None
    if chunked:  # what `--output x.png` would write with, for a merge into a PNG
        with output_format(scene, "PNG"):
            png_settings = prism.module("engine.output.png").png_settings(scene)
    file_format = OUTPUT_FORMATS[output.suffix.lower()]
    if file_format == "OPEN_EXR" and not chunked and prism.module("engine.render.result_passes").enabled_passes(scene):
        file_format = "OPEN_EXR_MULTILAYER"  # every pass, named as Blender names them
    with (
        output_format(scene, file_format),
        prism.output_files.atomic_output(output, signals) as temporary,
    ):
        blender_error = None
        spectral = None
        if arguments.spectral_output:
            spectral = Path(arguments.spectral_output).resolve()
            files = prism.output_files  # '#' becomes the frame number, as in --output
            spectral = files.numbered_output(spectral, scene.frame_current) if frame is None else files.frame_output(
                spectral, frame)
        with prism.requests.render_request(batch_request(arguments, prism, signals, spectral)) as report:
            try:
                # No write_still: Blender would announce the temporary file ("Saved: '.out.prism-…'").
                bpy.ops.render.render(write_still=False)
            except RuntimeError as error:
                blender_error = _blender_message(error)
        if report.error or not report.started:
            raise prism.errors.PrismInputError(report.error or blender_error or "Blender did not start the render.")
        if report.cancelled or signals.stop_requested():
            if arguments.keep_partial:
                try:
                    save_render_result(scene, temporary, output, prism)
                except prism.errors.PrismInputError:
                    pass  # the message then says the unfinished image could not be kept
            raise _interrupted(arguments, output, temporary, prism, signals)
        if chunked:
            chunks = prism.chunks()
            chunks.write_chunk(temporary, chunks.chunk_of_film(report.film, png_settings))
        else:
            save_render_result(scene, temporary, output, prism)
    if report.spectral_output:
        _wrote(Path(report.spectral_output))
    if report.output_errors:  # the main image is written; a secondary output failed: say so, exit 1
        _wrote(output)
        raise prism.errors.PrismInputError(" ".join(report.output_errors))
    return output


@contextmanager
def output_format(scene, file_format: str):
    """The scene's output set to ``file_format`` (EXR: 32-bit float) for the block, then as it was."""
    settings = scene.render.image_settings
    before = settings.file_format, settings.color_depth
    settings.file_format = file_format
    if file_format.startswith("OPEN_EXR"):
        settings.color_depth = "32"
    try:
        yield settings
    finally:
        settings.file_format, settings.color_depth = before


def save_render_result(scene, path: Path, output: Path, prism: Prism) -> None:
    """Write Blender's Render Result to ``path`` as ``scene``'s output settings ask, exactly as
    ``write_still`` does (view transform for PNG, scene-linear EXR), without announcing ``path``."""
    import bpy

    result = next((image for image in bpy.data.images if image.type == "RENDER_RESULT"), None)
    if result is None:
        raise prism.errors.PrismInputError(f"Prism rendered but Blender kept no Render Result to write to '{output}'.")
    try:
        result.save_render(filepath=str(path), scene=scene)
    except RuntimeError as error:
        raise prism.errors.PrismInputError(
            f"Cannot write '{output}': {_blender_message(error)}. Choose a folder that exists and that you can write to."
        ) from None


def _interrupted(arguments, output: Path, temporary: Path, prism: Prism, signals):
    """The exception that ends an interrupted frame; the partial image is kept first if asked."""
    cause = signals.signal_name() if signals.stop_requested() else "Esc"
    message = f"interrupted by {cause}: '{output}' was not written"
    if arguments.keep_partial:
        partial = prism.output_files.partial_output(output)
        try:
            os.replace(temporary, partial)
            message += f"; the unfinished image is in '{partial}'"
        except OSError as error:
            message += f"; the unfinished image could not be kept as '{partial}' ({error.strerror or error})"
    return prism.stop_signals.Interrupted(message + ".", signals.exit_status)


def write_lens_diagram(arguments, prism: Prism, signals) -> Path:
    """The lens overlay drawing of the active camera, as a PNG (offscreen GPU)."""
    import bpy

    drawing = prism.module("ui.lens_overlay_export")
    path = Path(arguments.lens_diagram).resolve()
    with prism.output_files.atomic_output(path, signals) as temporary:
        drawing.write_lens_diagram_png(bpy.context.scene, str(temporary))
    return path


def _wrote(path: Path) -> None:
    """Blender's own line for a written file, naming the final file (Flamenco's worker reads it)."""
    print(f"Saved: '{path}'", file=sys.stderr, flush=True)


def render_all(arguments, prism: Prism, signals) -> None:
    import bpy

    if arguments.lens_diagram:
        _wrote(write_lens_diagram(arguments, prism, signals))
    if arguments.output is None:
        return
    output = Path(arguments.output).resolve()
    scene = bpy.context.scene
    if arguments.frames is None:  # the current frame; '#' in the name becomes its number, as in Blender
        output = prism.output_files.numbered_output(output, scene.frame_current)
        _wrote(render_frame(arguments, output, prism, signals))
        return
    first, last = arguments.frames
    for frame in range(first, last + 1):
        signals.raise_if_stopped(f"frame {frame} and the frames after it")
        print(f"Prism: frame {frame} ({frame - first + 1}/{last - first + 1})", file=sys.stderr, flush=True)
        scene.frame_set(frame)
        _wrote(render_frame(arguments, prism.output_files.frame_output(output, frame), prism, signals, frame))


def merge(arguments, prism: Prism, signals) -> None:
    """Merge the chunks into one EXR, or a PNG written as their scene writes PNGs."""
    chunks = prism.chunks()
    merged = chunks.merge_chunks([chunks.read_chunk(path) for path in arguments.merge], arguments.expect_samples)
    frame = int(float(merged.frame or 0))
    output = prism.output_files.numbered_output(Path(arguments.output).resolve(), frame)  # '#': the chunks' frame
    with prism.output_files.atomic_output(output, signals) as temporary:
        if output.suffix.lower() == ".png":
            png = prism.module("engine.output.png")
            png.write_png(merged.mean, merged.png_settings, temporary, source=arguments.merge[0], frame=frame)
        else:
            chunks.write_chunk(temporary, merged)
        signals.raise_if_stopped(f"'{output}'")
    print(f"Prism: merged {len(arguments.merge)} chunks of frame {merged.frame}, {merged.samples} samples per pixel",
          file=sys.stderr)
    _wrote(output)


def run(arguments, in_blender: bool, prism: Prism, signals) -> None:
    if arguments.merge:
        merge(arguments, prism, signals)
        return
    if not in_blender:
        open_blend_file(arguments.blend_file, prism)
    signals.raise_if_stopped("nothing")
    render_all(arguments, prism, signals)


def main(argv: list[str], in_blender: bool) -> int:
    # Registered before any .blend file opens: a file saved with Prism as its engine
    # would otherwise print "Engine 'PRISM' not available" while loading.
    prism = Prism(prism_package_name())
    try:
        arguments = prism.arguments.parse_arguments(argv, in_blender)
    except SystemExit as exit_request:
        return int(exit_request.code or 0)
    with prism.stop_signals.StopSignals() as signals:
        try:
            run(arguments, in_blender, prism, signals)
        except prism.stop_signals.Interrupted as stop:
            print(f"Prism: {stop}", file=sys.stderr)
            return stop.status
        except prism.errors.PrismInputError as error:
            print(f"Prism: error: {error}", file=sys.stderr)
            return 1
        except Exception as error:  # noqa: BLE001 - a bug: the traceback, then one line saying so
            import traceback

            traceback.print_exc()
            print(f"Prism: error: unexpected {type(error).__name__} (a bug in Prism; please report it with the "
                  f"traceback above): {error}", file=sys.stderr)
            return 1
    return 0


def _running_inside_blender() -> bool:
    """True under ``blender -P render.py``: argv[0] is Blender, not this script."""
    return Path(sys.argv[0]).resolve() != Path(__file__).resolve()


def _script_arguments(in_blender: bool) -> list[str]:
    """Arguments after ``--`` inside Blender, else everything after the script name."""
    if in_blender:
        return sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    return sys.argv[1:]


def exit_now(status: int) -> None:
    """End a process that loaded bpy with ``status`` at once (``engine/batch/process_exit.py`` says why)."""
    load_addon_package()
    importlib.import_module(f"{ADDON_PACKAGE}.engine.batch.process_exit").exit_now(status)


if __name__ == "__main__":
    inside_blender = _running_inside_blender()
    exit_now(main(_script_arguments(inside_blender), inside_blender))
