"""Sample chunks of a batch render: EXR files that carry their sample count, and their merge.

A chunk ``k`` of ``N`` samples renders samples ``k*N .. (k+1)*N - 1`` of one
render's sample sequence (same seed). Merging chunks weights each by its sample
count, so chunks ``0 .. K-1`` merge to the image of one ``K*N``-sample render.
The mean is stored as float32 ``R, G, B`` (any EXR viewer shows the chunk) plus
the float32 remainder of the float64 mean in ``prism_lo_R/G/B``, so the merge
works in float64 and its float32 result is bit-identical to the single render
(see ``docs`` of ``merge_chunks`` for when).

EXR I/O uses OpenImageIO, which Blender bundles (``bpy.utils.system_resource``).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .tracer.errors import PrismInputError

SAMPLES_ATTRIBUTE = "prism:samples"
OFFSET_ATTRIBUTE = "prism:sample_offset"
SEED_ATTRIBUTE = "prism:seed"
CHANNELS = ("R", "G", "B", "A", "prism_lo_R", "prism_lo_G", "prism_lo_B")


def _oiio():
    try:
        import OpenImageIO
    except ImportError:
        import bpy

        sys.path.append(str(Path(bpy.utils.system_resource("PYTHON")) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"))
        import OpenImageIO
    return OpenImageIO


@dataclass
class Chunk:
    """A chunk's float64 mean [H, W, 3] (row 0 = top), sample count, offset and seed."""

    mean: np.ndarray
    samples: int
    sample_offset: int = 0
    seed: int = 0
    path: str = ""


def write_exr(path, mean: np.ndarray, samples: int, sample_offset: int = 0, seed: int = 0) -> None:
    """Write ``mean`` (float64 [H, W, 3], row 0 = top) and its sample count to an EXR."""
    oiio = _oiio()
    mean = np.asarray(mean, dtype=np.float64)
    height, width, _ = mean.shape
    high = mean.astype(np.float32)
    low = (mean - high.astype(np.float64)).astype(np.float32)
    pixels = np.concatenate([high, np.ones((height, width, 1), np.float32), low], axis=2)
    spec = oiio.ImageSpec(width, height, len(CHANNELS), "float")
    spec.channelnames = CHANNELS
    spec.attribute("compression", "zip")
    spec.attribute(SAMPLES_ATTRIBUTE, int(samples))
    spec.attribute(OFFSET_ATTRIBUTE, int(sample_offset))
    spec.attribute(SEED_ATTRIBUTE, int(seed))
    output = oiio.ImageOutput.create(str(path))
    if output is None or not output.open(str(path), spec):
        raise PrismInputError(f"Cannot write '{path}': {oiio.geterror() or 'check the folder exists and is writable'}.")
    try:
        if not output.write_image(np.ascontiguousarray(pixels)):
            raise PrismInputError(f"Cannot write '{path}': {output.geterror()}.")
    finally:
        output.close()


def read_chunk(path) -> Chunk:
    """Read a chunk written by ``write_exr``; a clear error for anything else."""
    oiio = _oiio()
    if not Path(path).is_file():
        raise PrismInputError(f"Chunk '{path}' does not exist: check the path.")
    image = oiio.ImageInput.open(str(path))
    if image is None:
        raise PrismInputError(f"Chunk '{path}' is not a readable EXR image: {oiio.geterror()}.")
    try:
        spec = image.spec()
        samples = spec.get_int_attribute(SAMPLES_ATTRIBUTE, 0)
        if samples < 1:
            raise PrismInputError(
                f"'{path}' has no Prism sample count: merge only chunks written with --chunk-seed."
            )
        names = list(spec.channelnames)
        pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    finally:
        image.close()
    pixels = np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)
    mean = np.stack([pixels[..., names.index(c)] for c in "RGB"], axis=-1).astype(np.float64)
    if all(f"prism_lo_{c}" in names for c in "RGB"):
        mean += np.stack([pixels[..., names.index(f"prism_lo_{c}")] for c in "RGB"], axis=-1).astype(np.float64)
    return Chunk(
        mean=mean,
        samples=int(samples),
        sample_offset=spec.get_int_attribute(OFFSET_ATTRIBUTE, 0),
        seed=spec.get_int_attribute(SEED_ATTRIBUTE, 0),
        path=str(path),
    )


def merge_chunks(chunks: list[Chunk]) -> Chunk:
    """Sample-weighted mean of ``chunks`` (float64).

    Bit-identical (after rounding to float32) to one render of all the samples
    when the chunks are consecutive blocks of the same seed's sequence (offsets
    0, N, 2N, ...; ``--chunk-seed 0, 1, 2 ...`` with the same ``--samples``), the
    block size is a multiple of the scene's samples per pass, and the single
    render was a batch render (no quick first pass). Otherwise (different seeds,
    overlapping blocks) the merge is still an unbiased, sample-weighted mean.
    """
    if not chunks:
        raise PrismInputError("Nothing to merge: give at least one chunk EXR.")
    shape = chunks[0].mean.shape
    for chunk in chunks[1:]:
        if chunk.mean.shape != shape:
            raise PrismInputError(
                f"Chunk '{chunk.path}' is {chunk.mean.shape[1]}x{chunk.mean.shape[0]} pixels but "
                f"'{chunks[0].path}' is {shape[1]}x{shape[0]}: merge chunks of the same render only."
            )
    blocks = sorted((c.seed, c.sample_offset, c.sample_offset + c.samples, c.path) for c in chunks)
    for (seed_a, _, end, first), (seed_b, start, _, second) in zip(blocks, blocks[1:]):
        if seed_a == seed_b and start < end:
            raise PrismInputError(
                f"Chunks '{first}' and '{second}' contain the same samples: give each chunk its own --chunk-seed."
            )
    total = sum(c.samples for c in chunks)
    weighted = sum(c.mean * c.samples for c in chunks)
    return Chunk(mean=weighted / total, samples=total, sample_offset=min(c.sample_offset for c in chunks), seed=chunks[0].seed)
