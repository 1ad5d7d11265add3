"""Sample chunks of a batch render: EXR files that say what they were rendered from, and their merge.

A chunk ``k`` of ``N`` samples renders samples ``k*N .. (k+1)*N - 1`` of one
render's sample sequence (same seed). Merging chunks weights each by its sample
count, so chunks ``0 .. K-1`` merge to the image of one ``K*N``-sample render.
The mean is stored as float32 ``R, G, B`` (any EXR viewer shows the chunk) plus
the float32 remainder of the float64 mean in ``prism_lo_R/G/B``, so the merge
works in float64 and its float32 result is bit-identical to the single render
(see ``merge_chunks`` for when).

Each chunk carries, as EXR string attributes (exact for any 64-bit number): the
fingerprint of its frame, scene and settings (``engine.render.fingerprint``), its seed,
the sample ranges it holds, the settings its scene writes a PNG with
(``engine.output.png``: a merge can write the frame's PNG without the .blend
file), and a checksum over all of that and the pixels. A merge refuses chunks of
different renders, overlapping samples, damaged or edited files and non-finite
pixels, naming the file.

EXR I/O uses OpenImageIO, which Blender bundles (``bpy.utils.system_resource``).
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .fingerprint import differing_parts
from ..output.openimageio import import_openimageio as _oiio
from ..tracer.errors import PrismInputError

FORMAT_ATTRIBUTE = "prism:chunk"
FORMAT_VERSION = "3"  # 3: the fingerprint holds the frame; the PNG settings
FINGERPRINT_ATTRIBUTE = "prism:fingerprint"
SEED_ATTRIBUTE = "prism:seed"
RANGES_ATTRIBUTE = "prism:sample_ranges"
SAMPLES_ATTRIBUTE = "prism:samples"  # the total, for people reading the header
PNG_SETTINGS_ATTRIBUTE = "prism:png_settings"
CHECKSUM_ATTRIBUTE = "prism:checksum"
CHANNELS = ("R", "G", "B", "A", "prism_lo_R", "prism_lo_G", "prism_lo_B")


@dataclass
class Chunk:
    """A chunk's float64 mean [H, W, 3] (row 0 = top), seed, the half-open sample
    ranges ``[(start, end), ...]`` it holds, the fingerprint of its render, and the
    settings its scene writes a PNG with (``engine.output.png.png_settings``)."""

    mean: np.ndarray
    seed: int
    sample_ranges: tuple[tuple[int, int], ...]
    fingerprint: dict[str, str]
    png_settings: dict
    path: str = ""

    @property
    def samples(self) -> int:
        return sum(end - start for start, end in self.sample_ranges)

    @property
    def sample_offset(self) -> int:
        return self.sample_ranges[0][0]

    @property
    def frame(self) -> str:
        """The frame it was rendered at, as written in its fingerprint (``"7"``, ``"7.5"``)."""
        return self.fingerprint.get("frame", "")


def chunk_of_film(film, png_settings: dict) -> Chunk:
    """The chunk of a finished render's ``FilmSnapshot``, whose scene writes PNGs with ``png_settings``."""
    return Chunk(
        mean=film.mean,
        seed=int(film.seed),
        sample_ranges=((int(film.sample_offset), int(film.sample_offset + film.samples)),),
        fingerprint=dict(film.fingerprint),
        png_settings=dict(png_settings),
    )


def _attributes(chunk: Chunk) -> dict[str, str]:
    return {
        FORMAT_ATTRIBUTE: FORMAT_VERSION,
        FINGERPRINT_ATTRIBUTE: json.dumps(chunk.fingerprint, sort_keys=True),
        SEED_ATTRIBUTE: str(int(chunk.seed)),
        RANGES_ATTRIBUTE: json.dumps([[int(a), int(b)] for a, b in chunk.sample_ranges]),
        SAMPLES_ATTRIBUTE: str(chunk.samples),
        PNG_SETTINGS_ATTRIBUTE: json.dumps(chunk.png_settings, sort_keys=True),
    }


def _checksum(pixels: np.ndarray, attributes: dict[str, str]) -> str:
    digest = hashlib.sha256(np.ascontiguousarray(pixels, dtype="<f4").tobytes())
    digest.update(json.dumps(attributes, sort_keys=True).encode())
    return digest.hexdigest()


def write_chunk(path, chunk: Chunk) -> None:
    """Write ``chunk`` to the EXR ``path`` (callers make it atomic: ``batch.output_files``)."""
    oiio = _oiio()
    mean = np.asarray(chunk.mean, dtype=np.float64)
    if not np.isfinite(mean).all():
        raise ValueError("a chunk's mean must be finite: the film drops non-finite samples")
    height, width, _ = mean.shape
    high = mean.astype(np.float32)
    low = (mean - high.astype(np.float64)).astype(np.float32)
    pixels = np.ascontiguousarray(np.concatenate([high, np.ones((height, width, 1), np.float32), low], axis=2))
    attributes = _attributes(chunk)
    spec = oiio.ImageSpec(width, height, len(CHANNELS), "float")
    spec.channelnames = CHANNELS
    spec.attribute("compression", "zip")
    for name, value in attributes.items():
        spec.attribute(name, value)
    spec.attribute(CHECKSUM_ATTRIBUTE, _checksum(pixels, attributes))
    output = oiio.ImageOutput.create(str(path))
    if output is None or not output.open(str(path), spec):
        raise PrismInputError(f"Cannot write '{path}': {oiio.geterror() or 'check the folder exists and is writable'}.")
    try:
        if not output.write_image(pixels):
            raise PrismInputError(f"Cannot write '{path}': {output.geterror()}.")
    finally:
        output.close()


def _render_again(path, problem: str) -> PrismInputError:
    return PrismInputError(f"Chunk '{path}' {problem}: render this chunk again (same --seed, --chunk-seed and --samples).")


def read_chunk(path) -> Chunk:
    """Read and check a chunk written by ``write_chunk``; a clear error naming the file otherwise."""
    oiio = _oiio()
    if Path(path).is_dir():
        raise PrismInputError(f"Chunk '{path}' is a folder: give the chunk EXR files themselves.")
    if not Path(path).is_file():
        raise PrismInputError(f"Chunk '{path}' does not exist: check the path.")
    image = oiio.ImageInput.open(str(path))
    if image is None:
        raise PrismInputError(
            f"Chunk '{path}' is not a readable EXR image ({oiio.geterror().strip() or 'unknown format'}): "
            "merge only chunks written with --chunk-seed."
        )
    try:
        spec = image.spec()
        attributes = _read_attributes(path, spec)
        names = list(spec.channelnames)
        if sorted(names) != sorted(CHANNELS):
            raise _render_again(path, f"is damaged: its channels are {', '.join(names)}, not Prism's {', '.join(CHANNELS)}")
        pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
        if pixels is None:
            raise _render_again(path, f"is damaged: its pixels cannot be read ({image.geterror().strip()})")
    finally:
        image.close()
    pixels = np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)
    pixels = pixels[..., [names.index(c) for c in CHANNELS]]
    _check_finite(path, pixels)
    if spec.get_string_attribute(CHECKSUM_ATTRIBUTE) != _checksum(pixels, attributes):
        raise _render_again(path, "does not match its checksum: it was damaged or edited after Prism wrote it")
    mean = pixels[..., :3].astype(np.float64) + pixels[..., 4:7].astype(np.float64)
    return Chunk(
        mean=mean,
        seed=int(attributes[SEED_ATTRIBUTE]),
        sample_ranges=tuple(tuple(r) for r in json.loads(attributes[RANGES_ATTRIBUTE])),
        fingerprint=json.loads(attributes[FINGERPRINT_ATTRIBUTE]),
        png_settings=json.loads(attributes[PNG_SETTINGS_ATTRIBUTE]),
        path=str(path),
    )


def _read_attributes(path, spec) -> dict[str, str]:
    version = spec.get_string_attribute(FORMAT_ATTRIBUTE)
    if not version:
        if spec.get_int_attribute(SAMPLES_ATTRIBUTE, 0) > 0:
            raise _render_again(path, "was written by an earlier Prism and carries no fingerprint of its render")
        raise PrismInputError(
            f"'{path}' has no Prism sample count: it is not a chunk. Merge only chunks written with --chunk-seed."
        )
    if version != FORMAT_VERSION:
        raise _render_again(path, f"has chunk format {version}, which this Prism does not read (it writes {FORMAT_VERSION})")
    attributes = {name: spec.get_string_attribute(name) for name in (
        FORMAT_ATTRIBUTE, FINGERPRINT_ATTRIBUTE, SEED_ATTRIBUTE, RANGES_ATTRIBUTE, SAMPLES_ATTRIBUTE,
        PNG_SETTINGS_ATTRIBUTE)}
    try:
        int(attributes[SEED_ATTRIBUTE])
        ranges = json.loads(attributes[RANGES_ATTRIBUTE])
        fingerprint = json.loads(attributes[FINGERPRINT_ATTRIBUTE])
        png_settings = json.loads(attributes[PNG_SETTINGS_ATTRIBUTE])
        valid = (
            isinstance(fingerprint, dict)
            and isinstance(png_settings, dict)
            and isinstance(ranges, list)
            and ranges
            and all(isinstance(a, int) and isinstance(b, int) and 0 <= a < b for a, b in ranges)
        )
    except (ValueError, TypeError):
        valid = False
    if not valid:
        raise _render_again(path, "has damaged Prism attributes (seed, sample ranges, fingerprint or PNG settings)")
    return attributes


def _check_finite(path, pixels: np.ndarray) -> None:
    bad = ~np.isfinite(pixels).all(axis=2)
    if bad.any():
        y, x = (int(v) for v in np.argwhere(bad)[0])
        raise _render_again(path, f"holds {int(bad.sum())} pixel(s) that are NaN or infinite (the first at x={x}, y={y} from the top)")


def merge_chunks(chunks: list[Chunk], expect_samples: int | None = None) -> Chunk:
    """Sample-weighted mean of ``chunks`` (float64), after checking they belong together and,
    given ``expect_samples``, that they hold samples ``0 .. expect_samples - 1``, every one.

    Bit-identical (after rounding to float32) to one render of all the samples
    when the chunks are consecutive blocks of the same seed's sequence (offsets
    0, N, 2N, ...; ``--chunk-seed 0, 1, 2 ...`` with the same ``--samples``), the
    block size is a multiple of the scene's samples per pass, and the single
    render was a batch render (no quick first pass).
    """
    if not chunks:
        raise PrismInputError("Nothing to merge: give at least one chunk EXR.")
    first = chunks[0]
    for chunk in chunks[1:]:
        _check_same_render(first, chunk)
    ranges = sorted((start, end, c.path) for c in chunks for start, end in c.sample_ranges)
    for (_, end, path_a), (start, _, path_b) in zip(ranges, ranges[1:]):
        if start < end:
            raise PrismInputError(
                f"Chunks '{path_a}' and '{path_b}' contain the same samples (from sample {start}): "
                "give each chunk its own --chunk-seed."
            )
    joined = _joined([(start, end) for start, end, _ in ranges])
    if expect_samples is not None:
        _check_complete(chunks, joined, expect_samples)
    total = sum(c.samples for c in chunks)
    weighted = sum(c.mean * c.samples for c in chunks)
    return Chunk(
        mean=weighted / total,
        seed=first.seed,
        sample_ranges=joined,
        fingerprint=dict(first.fingerprint),
        png_settings=dict(first.png_settings),
    )


def _check_complete(chunks: list[Chunk], joined, expected: int) -> None:
    """The chunks hold samples ``0 .. expected - 1`` and nothing else; else name what is missing or extra."""
    if joined == ((0, expected),):
        return
    for chunk in chunks:
        beyond = [(max(start, expected), end) for start, end in chunk.sample_ranges if end > expected]
        if beyond:
            raise PrismInputError(
                f"Chunk '{chunk.path}' holds {_samples_text(beyond)}, past the {expected} samples --expect-samples "
                "asks for: leave it out, or give the frame's real total to --expect-samples."
            )
    missing, cursor = [], 0
    for start, end in joined:
        if start > cursor:
            missing.append((cursor, start))
        cursor = end
    if cursor < expected:
        missing.append((cursor, expected))
    held = sum(end - start for start, end in joined)
    holders = "The chunk holds" if len(chunks) == 1 else f"The {len(chunks)} chunks hold"
    raise PrismInputError(
        f"{holders} {held} of the {expected} samples --expect-samples asks for: "
        f"{_samples_text(missing)} {'is' if held == expected - 1 else 'are'} missing{_chunks_to_render(chunks, missing)}."
    )


def _samples_text(ranges) -> str:
    """``[(2, 4), (6, 7)]`` → ``samples 2..3 and sample 6`` (inclusive, as people count)."""
    parts = [f"sample {start}" if end - start == 1 else f"samples {start}..{end - 1}" for start, end in ranges[:4]]
    if len(ranges) > 4:
        parts.append(f"{len(ranges) - 4} more range(s)")
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]


def _chunks_to_render(chunks: list[Chunk], missing) -> str:
    """`` (render --chunk-seed 1 and 3 with --samples 2)`` when every chunk is one block of the same size.

    Counted from the ranges, never listed one by one: ``--expect-samples`` may ask for 2**32 samples."""
    sizes = {chunk.samples for chunk in chunks}
    if len(sizes) != 1 or any(len(chunk.sample_ranges) != 1 for chunk in chunks):
        return ""
    size = sizes.pop()
    if any(start % size or end % size for start, end in missing):
        return ""
    seed_ranges = [(start // size, end // size) for start, end in missing]  # chunk seeds, end exclusive
    count = sum(end - start for start, end in seed_ranges)
    if count <= 8:
        seeds = [str(seed) for start, end in seed_ranges for seed in range(start, end)]
        listed = seeds[0] if len(seeds) == 1 else ", ".join(seeds[:-1]) + " and " + seeds[-1]
        return f" (render --chunk-seed {listed} with --samples {size})"
    if len(seed_ranges) == 1:
        (start, end), = seed_ranges
        return f" (render the {count} chunks from --chunk-seed {start} to {end - 1} with --samples {size})"
    shown = [f"{start}" if end - start == 1 else f"{start}..{end - 1}" for start, end in seed_ranges[:4]]
    if len(seed_ranges) > 4:
        shown.append(f"{len(seed_ranges) - 4} more range(s)")
    return (f" (render the {count} chunks --chunk-seed {', '.join(shown[:-1])} and {shown[-1]} "
            f"with --samples {size})")


def _check_same_render(first: Chunk, chunk: Chunk) -> None:
    if chunk.mean.shape != first.mean.shape:
        raise PrismInputError(
            f"Chunk '{chunk.path}' is {chunk.mean.shape[1]}x{chunk.mean.shape[0]} pixels but "
            f"'{first.path}' is {first.mean.shape[1]}x{first.mean.shape[0]}: merge chunks of the same render only."
        )
    if chunk.frame != first.frame:
        raise PrismInputError(
            f"Chunk '{chunk.path}' is frame {chunk.frame} but '{first.path}' is frame {first.frame}: merge the "
            "chunks of one frame only (--chunk-seed with --frames F renders a chunk of frame F)."
        )
    differ = differing_parts(first.fingerprint, chunk.fingerprint)
    if differ:
        raise PrismInputError(
            f"Chunks '{first.path}' and '{chunk.path}' come from different renders (their {', '.join(differ)} "
            "differ): merge only chunks rendered from the same .blend file, frame and settings."
        )
    if chunk.png_settings != first.png_settings:
        raise PrismInputError(
            f"Chunks '{first.path}' and '{chunk.path}' come from scenes with different Color Management or PNG "
            "output settings (view transform, look, exposure, dither, colour depth, ...): merge only chunks "
            "rendered from the same .blend file and settings."
        )
    if chunk.seed != first.seed:
        raise PrismInputError(
            f"Chunks '{first.path}' (seed {first.seed}) and '{chunk.path}' (seed {chunk.seed}) have different seeds: "
            "render every chunk with the same --seed (--chunk-seed gives each its own samples)."
        )


def _joined(ranges: list[tuple[int, int]]) -> tuple[tuple[int, int], ...]:
    """Sorted, non-overlapping ranges with touching neighbours joined: (0, 2), (2, 4) → (0, 4)."""
    joined: list[tuple[int, int]] = []
    for start, end in ranges:
        if joined and joined[-1][1] == start:
            joined[-1] = (joined[-1][0], end)
        else:
            joined.append((start, end))
    return tuple(joined)
