"""The batch script's command line: every argument checked before Blender opens a file.

A wrong argument exits with status 2 and one line naming the option, the value
and what would work (argparse's convention).
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

OUTPUT_SUFFIXES = (".png", ".exr")
#: Blender's frame limits (MINAFRAME, MAXFRAME): ``frame_set`` clamps anything beyond them.
FRAME_RANGE = (-1048574, 1048574)
#: Prism's random sequences take 32-bit seeds (larger ones would repeat smaller ones' images).
MAX_SEED = 2**32 - 1
#: Sample numbers past 2^32 lose the low-discrepancy sequence's precision.
SAMPLE_SEQUENCE_LENGTH = 2**32
#: The Samples setting's own limit (a 32-bit IntProperty).
MAX_SAMPLES = 2**31 - 1
#: The Threads setting's own limit.
MAX_THREADS = 1024

_FRAMES = re.compile(r"\s*(-?\d+)\s*(?:\.\.\s*(-?\d+)\s*)?")


def frame_range(text: str) -> tuple[int, int]:
    """``"1..24"`` → (1, 24), ``"7"`` → (7, 7), ``"-5..-2"`` → (-5, -2), within Blender's frame limits."""
    match = _FRAMES.fullmatch(text)
    if not match:
        raise argparse.ArgumentTypeError(f"frames must look like 1..24 or 7 (got '{text}')")
    first = int(match.group(1))
    last = int(match.group(2)) if match.group(2) is not None else first
    if last < first:
        raise argparse.ArgumentTypeError(f"'{text}': the last frame comes before the first")
    low, high = FRAME_RANGE
    for frame in (first, last):
        if not low <= frame <= high:
            raise argparse.ArgumentTypeError(
                f"frame {frame} is outside Blender's frame range {low}..{high}"
            )
    return first, last


def _attach_negative_frames(argv: list[str]) -> list[str]:
    """``--frames -5..-2`` → ``--frames=-5..-2``: argparse reads a value starting with '-' as an option."""
    joined, index = [], 0
    while index < len(argv):
        token = argv[index]
        if token == "--frames" and index + 1 < len(argv) and _FRAMES.fullmatch(argv[index + 1]):
            joined.append(f"--frames={argv[index + 1]}")
            index += 2
            continue
        joined.append(token)
        index += 1
    return joined


def _parser(in_blender: bool) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="render.py",
        description="Render a .blend file with Prism.",
        epilog="Inside Blender: blender -b file.blend -P render.py -- [options]",
    )
    if not in_blender:
        parser.add_argument("blend_file", nargs="?", help="the .blend file to render (not with --merge)")
    parser.add_argument("--samples", type=int, help="samples per pixel (default: the scene's setting)")
    parser.add_argument("--seed", type=int, help=f"random seed, 0..{MAX_SEED} (default: the scene's setting)")
    parser.add_argument("--threads", type=int, help="CPU threads (0 = all cores; default: the scene's setting)")
    parser.add_argument("--noise-threshold", type=float, metavar="T",
                        help="adaptive sampling: pixels stop once their relative noise is below T (0 = off, "
                        "0.01 typical; default: the scene's setting)")
    parser.add_argument("--min-samples", type=int, metavar="N",
                        help="adaptive sampling: samples every pixel takes first (0 = automatic)")
    parser.add_argument("--time-limit", type=float, metavar="SECONDS",
                        help="stop sampling after this many seconds per frame (0 = no limit)")
    parser.add_argument("--frames", type=frame_range, help="render frames A..B (inclusive) instead of the current one")
    parser.add_argument(
        "--chunk-seed", type=int, help="render sample chunk K (samples K*N..(K+1)*N-1) of one frame to an EXR"
    )
    parser.add_argument("--merge", nargs="+", metavar="CHUNK", help="merge chunk EXRs weighted by their samples")
    parser.add_argument(
        "--expect-samples",
        type=int,
        metavar="TOTAL",
        help="with --merge: the chunks must hold samples 0..TOTAL-1, every one (refuses a missing chunk)",
    )
    parser.add_argument("--output", help="output image, .png or .exr")
    parser.add_argument(
        "--spectral-output",
        metavar="EXR",
        help="also write a multispectral EXR (wavelength bands of Render ▸ Prism ▸ Spectral Output's width, "
        "Fichet et al. 2021 layout); # becomes the frame number as in --output",
    )
    parser.add_argument(
        "--keep-partial",
        action="store_true",
        help="when interrupted, keep the unfinished image as NAME.partial.png/.exr (never under --output's name)",
    )
    parser.add_argument(
        "--lens-diagram",
        metavar="PNG",
        help="also write the lens overlay drawing (cross-section, ray fans, spot diagram) of the camera's real lens",
    )
    return parser


def parse_arguments(argv: list[str], in_blender: bool) -> argparse.Namespace:
    """The checked arguments; ``SystemExit(2)`` with argparse's one-line message otherwise."""
    parser = _parser(in_blender)
    arguments = parser.parse_args(_attach_negative_frames(list(argv)))
    _check_numbers(parser, arguments)
    if arguments.lens_diagram is not None and Path(arguments.lens_diagram).suffix.lower() != ".png":
        parser.error(f"--lens-diagram must end in .png (got '{arguments.lens_diagram}')")
    if arguments.spectral_output is not None:
        _check_spectral_output(parser, arguments)
    if arguments.output is None:
        if arguments.lens_diagram is None or arguments.merge:
            parser.error("give --output (an image to render), --lens-diagram, or both")
        if not in_blender and not arguments.blend_file:
            parser.error("give the .blend file to draw")
        if arguments.keep_partial:
            parser.error("--keep-partial keeps an unfinished --output image: give --output")
        return arguments
    _check_output(parser, arguments)
    if arguments.merge:
        if not in_blender and arguments.blend_file:
            parser.error("--merge takes chunk EXRs, not a .blend file")
        if arguments.keep_partial:
            parser.error("--merge writes the whole merged image or nothing: leave out --keep-partial")
        return arguments
    if not in_blender and not arguments.blend_file:
        parser.error("give the .blend file to render")
    if arguments.chunk_seed is not None:
        _check_chunk(parser, arguments)
    return arguments


def _check_numbers(parser, arguments) -> None:
    if arguments.samples is not None and arguments.samples < 1:
        parser.error(f"--samples must be at least 1 (got {arguments.samples})")
    if arguments.samples is not None and arguments.samples > MAX_SAMPLES:
        parser.error(f"--samples must be at most {MAX_SAMPLES}, the Samples setting's limit (got {arguments.samples})")
    if arguments.seed is not None and not 0 <= arguments.seed <= MAX_SEED:
        parser.error(f"--seed must be between 0 and {MAX_SEED}: Prism's seeds are 32-bit (got {arguments.seed})")
    if arguments.threads is not None and not 0 <= arguments.threads <= MAX_THREADS:
        parser.error(f"--threads must be between 0 (all cores) and {MAX_THREADS} (got {arguments.threads})")
    if arguments.chunk_seed is not None and arguments.chunk_seed < 0:
        parser.error(f"--chunk-seed must be 0 or more (got {arguments.chunk_seed})")
    if arguments.noise_threshold is not None and not 0 <= arguments.noise_threshold < 1:
        parser.error(f"--noise-threshold must be between 0 (off) and 1, e.g. 0.01 (got {arguments.noise_threshold})")
    if arguments.min_samples is not None and arguments.min_samples < 0:
        parser.error(f"--min-samples must be 0 (automatic) or more (got {arguments.min_samples})")
    if arguments.time_limit is not None and not arguments.time_limit >= 0:
        parser.error(f"--time-limit must be 0 (no limit) or a number of seconds (got {arguments.time_limit})")
    if arguments.expect_samples is not None:
        if not arguments.merge:
            parser.error("--expect-samples checks what --merge adds up to: use it with --merge")
        if not 1 <= arguments.expect_samples <= SAMPLE_SEQUENCE_LENGTH:
            parser.error(f"--expect-samples must be between 1 and {SAMPLE_SEQUENCE_LENGTH} "
                         f"(got {arguments.expect_samples})")


def _check_output(parser, arguments) -> None:
    output = Path(arguments.output)
    if output.suffix.lower() not in OUTPUT_SUFFIXES:
        parser.error(f"--output must end in .png or .exr (got '{arguments.output}')")
    if output.is_dir():
        parser.error(f"--output '{arguments.output}' is a folder: give a file name ending in .png or .exr")
    if arguments.merge and any(Path(chunk).resolve() == output.resolve() for chunk in arguments.merge):
        parser.error(f"--output '{arguments.output}' is one of the chunks to merge: give the merge another name")
    if arguments.lens_diagram is not None and Path(arguments.lens_diagram).resolve() == output.resolve():
        parser.error("--lens-diagram and --output name the same file: give them different names")
    if arguments.chunk_seed is not None and output.suffix.lower() != ".exr":
        parser.error("--chunk-seed writes an EXR (a chunk to merge): give --output a .exr name")


def _check_spectral_output(parser, arguments) -> None:
    spectral = Path(arguments.spectral_output)
    if spectral.suffix.lower() != ".exr":
        parser.error(f"--spectral-output must end in .exr (got '{arguments.spectral_output}')")
    if spectral.is_dir():
        parser.error(f"--spectral-output '{arguments.spectral_output}' is a folder: give a file name ending in .exr")
    if arguments.output is None:
        parser.error("--spectral-output is written with a render: give --output too")
    if spectral.resolve() == Path(arguments.output).resolve():
        parser.error("--spectral-output and --output name the same file: give them different names")
    if arguments.merge or arguments.chunk_seed is not None:
        option = "--merge" if arguments.merge else "--chunk-seed"
        parser.error(f"--spectral-output needs a whole render, which {option} does not make: leave out one of them")


def _check_chunk(parser, arguments) -> None:
    if arguments.samples is None:
        parser.error("--chunk-seed needs --samples (the chunk's sample count)")
    if arguments.frames is not None and arguments.frames[0] != arguments.frames[1]:
        first, last = arguments.frames
        parser.error(f"--chunk-seed renders one frame: give --frames a single frame, e.g. --frames {first} "
                     f"(got {first}..{last})")
    if arguments.keep_partial:
        parser.error("--chunk-seed writes a whole chunk or nothing (a partial chunk cannot merge): leave out --keep-partial")
    if arguments.noise_threshold or arguments.time_limit:
        parser.error("--chunk-seed renders every sample of its chunk in every pixel (or the chunks could not merge): "
                     "leave out --noise-threshold and --time-limit")
    end = (arguments.chunk_seed + 1) * arguments.samples
    if end > SAMPLE_SEQUENCE_LENGTH:
        parser.error(
            f"--chunk-seed {arguments.chunk_seed} with --samples {arguments.samples} ends at sample {end}, past "
            f"the {SAMPLE_SEQUENCE_LENGTH} samples of a pixel's sequence: use a smaller --chunk-seed or --samples"
        )
