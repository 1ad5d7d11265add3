"""Frames of any size: the tiles a frame is rendered in and the memory it needs, checked before rendering.

A frame larger than the tile size is rendered tile by tile (each tile to all its samples, as Cycles'
auto tiling does), so Prism holds one tile's film at a time; the image is the same as an untiled render
(samples are indexed by pixel, not by tile). What cannot be tiled away is the full-resolution image
Blender itself keeps (its Render Result: 4 bytes per channel of every pass, and a copy when the file is
written); when that and a tile do not fit in the memory available, the render is refused at once with
the amount it would need.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass

from .cryptomatte_film import BYTES_PER_PIXEL as CRYPTOMATTE_BYTES
from .errors import PrismInputError

GB = 1024**3
#: Bytes a film keeps per pixel for Combined: its sum and sum of squares (2 x 3 float64), the count (int64).
COMBINED_BYTES = 56
#: Prism's working memory per pixel of a tile besides its film: the pixel list, float32 images of the
#: tile handed to Blender, and their flipped copies.
TILE_WORK_BYTES = 8 + 2 * 16
#: Memory a render needs besides the frame: Python, Blender, kernels, Embree (bytes).
BASE_BYTES = 1 * GB
#: Of the memory available, how much a render may plan to use (the rest for the system and other work).
USABLE_FRACTION = 0.9
#: Bytes per pixel of the copy Blender saves an 8-bit image from (a 16384² frame measured 5.2 GB at peak
#: with Combined alone, this model says 6.4 GB: benchmarks/experiments/huge_frames.py).
SAVE_BYTES = 4
#: Render ▸ Performance ▸ Tile Size's default (Cycles' too).
DEFAULT_TILE_SIZE = 2048


@dataclass
class FramePlan:
    """``tiles``: (x0, y0, x1, y1) rectangles, rows from the top, in rendering order; ``needed_bytes`` and
    ``available_bytes`` (None: unknown) of the check; ``blender_bytes`` / ``prism_bytes`` its parts."""

    tiles: list
    needed_bytes: int
    blender_bytes: int
    prism_bytes: int
    available_bytes: int | None

    @property
    def tiled(self) -> bool:
        return len(self.tiles) > 1


def film_bytes_per_pixel(layout=None) -> int:
    """Memory one pixel of a film takes (bytes): Combined, the columns of ``layout``'s passes and its
    Cryptomatte counts (the dense part: a pixel's first object and material)."""
    if layout is None:
        return COMBINED_BYTES
    cryptomatte = CRYPTOMATTE_BYTES if getattr(layout, "cryptomatte_column", -1) >= 0 else 0
    return COMBINED_BYTES + 8 * layout.width + cryptomatte


def split_tiles(region, tile_size: int) -> list[tuple[int, int, int, int]]:
    """``region`` (x0, y0, x1, y1) cut into tiles of at most ``tile_size`` pixels a side, row by row from
    the top (0: one tile)."""
    x0, y0, x1, y1 = region
    if tile_size <= 0 or (x1 - x0 <= tile_size and y1 - y0 <= tile_size):
        return [(x0, y0, x1, y1)]
    return [(x, y, min(x + tile_size, x1), min(y + tile_size, y1))
            for y in range(y0, y1, tile_size) for x in range(x0, x1, tile_size)]


def available_memory_bytes() -> int | None:
    """Physical memory this process could still use (bytes), or None where the system does not say."""
    try:
        if sys.platform.startswith("linux"):
            with open("/proc/meminfo") as info:
                for line in info:
                    if line.startswith("MemAvailable:"):
                        return int(line.split()[1]) * 1024
        if sys.platform == "win32":
            import ctypes

            class Status(ctypes.Structure):
                _fields_ = [("length", ctypes.c_ulong), ("load", ctypes.c_ulong)] + [
                    (name, ctypes.c_ulonglong) for name in
                    ("total", "available", "total_page", "available_page", "total_virtual", "available_virtual",
                     "extended")]

            status = Status()
            status.length = ctypes.sizeof(Status)
            if ctypes.windll.kernel32.GlobalMemoryStatusEx(ctypes.byref(status)):
                return int(status.available)
        return int(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (OSError, ValueError, AttributeError):
        return None


def plan_frame(width: int, height: int, region, film_bytes_per_pixel: int, blender_channels: int,
               tile_size: int, available_bytes: int | None = None) -> FramePlan:
    """Tiles for ``region`` of a ``width`` x ``height`` frame and the memory check. ``film_bytes_per_pixel``:
    ``Film.bytes_per_pixel``; ``blender_channels``: float channels of all passes Blender keeps per pixel;
    ``tile_size``: Performance ▸ Tiles (0: no tiling). Raises ``PrismInputError`` when the frame would not
    fit in ``available_bytes`` (default: what the system reports)."""
    tiles = split_tiles(region, tile_size)
    x0, y0, x1, y1 = region
    pixels = (x1 - x0) * (y1 - y0)
    largest = max((b[2] - b[0]) * (b[3] - b[1]) for b in tiles)
    # Blender keeps Combined and every pass at full resolution, and an 8-bit copy to save a PNG.
    blender = (4 * (blender_channels + 4) + SAVE_BYTES) * pixels
    prism = (film_bytes_per_pixel + TILE_WORK_BYTES) * largest
    needed = BASE_BYTES + blender + prism
    available = available_memory_bytes() if available_bytes is None else available_bytes
    plan = FramePlan(tiles, needed, blender, prism, available)
    if available is not None and needed > USABLE_FRACTION * available:
        advice = ("lower Output ▸ Format ▸ Resolution %, turn off passes (View Layer ▸ Passes)"
                  + ("" if len(tiles) > 1 and largest < pixels else ", or turn on Render ▸ Performance ▸ Tiles"))
        passes = f"Combined and {blender_channels} more pass channels" if blender_channels else "Combined"
        raise PrismInputError(
            f"a {width} x {height} frame needs about {needed / GB:.1f} GB ({blender / GB:.1f} GB for the image "
            f"Blender keeps: {passes}; {prism / GB:.1f} GB for Prism's "
            f"{'tile' if len(tiles) > 1 else 'film'}) but only {available / GB:.1f} GB of memory is available: "
            f"{advice}."
        )
    return plan
