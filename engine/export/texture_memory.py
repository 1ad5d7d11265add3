"""What image textures cost in memory, checked image by image before Prism reads an image's pixels.

Measured per texel around ``nodes.images.read_image`` and ``tracer.textures.image.build_textures``
(bpy 4.5; the test counts numpy's buffers with ``tracemalloc``, exact to 0.01 byte a texel): Blender's own buffer of the image
(4 bytes a texel for 8-bit images, 16 for float ones), the peak while Prism reads it (the float32 RGBA
copy ``foreach_get`` fills, the levels or decoded values made from it), and what stays for the render
(the ``TextureImage`` and its copy in the texture tables). A 16384² 8-bit texture thus needs about
6.0 GB while it is read and keeps 3.0 GB; a frame's own memory (``tracer.frame_plan``) comes first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..tracer import frame_plan as frames
from ..tracer.errors import PrismInputError

GB = frames.GB


@dataclass(frozen=True)
class TexelCost:
    """Bytes per texel: ``blender`` (Blender's image buffer), ``reading`` (Prism's peak while reading and
    tabulating it), ``kept`` (what Prism keeps for the render)."""

    blender: int
    reading: int
    kept: int

    @property
    def peak(self) -> int:
        return self.blender + max(self.reading, self.kept)

    @property
    def held(self) -> int:
        return self.blender + self.kept


#: 8-bit images kept as levels (sRGB, and colour spaces that map each channel alone): measured 20.0 / 8.0.
LEVELS = TexelCost(blender=4, reading=20, kept=8)
#: Float images (EXR, HDR): measured 32.0 / 32.0.
FLOAT = TexelCost(blender=16, reading=32, kept=32)
#: 8-bit images in a colour space that mixes channels (AgX, ACES), decoded to float32: measured 76.3 / 32.3.
DECODED = TexelCost(blender=4, reading=76, kept=32)
#: Premultiplied alpha is undone on a float copy first: measured 21 bytes a texel more while reading.
PREMULTIPLIED_READING = 21


def _size(count: float) -> str:
    """``6.4 GB``, ``48 MB``, ``24 kB`` (binary units, as the frame's check writes them)."""
    if count >= 0.1 * GB:
        return f"{count / GB:.1f} GB"
    return f"{count / 1024**2:.0f} MB" if count >= 1024**2 else f"{count / 1024:.0f} kB"


class TextureMemoryError(PrismInputError):
    """An image texture that would not fit in the memory left for it."""


@dataclass
class TextureBudget:
    """Memory for one render's image textures: ``available_bytes`` (None: the system does not say),
    ``reserved_bytes`` (the frame, Blender, Prism's base: ``tracer.frame_plan``) and ``kept_bytes``
    (images read so far)."""

    available_bytes: int | None
    reserved_bytes: int = frames.BASE_BYTES
    kept_bytes: int = 0

    @classmethod
    def for_scene(cls, scene) -> TextureBudget:
        """The budget left once ``scene``'s frame (its resolution and passes) is planned."""
        from ..render.result_passes import frame_plan
        from .camera import render_resolution

        available = frames.available_memory_bytes()
        try:
            reserved = frame_plan(scene, None, *render_resolution(scene)).needed_bytes
        except PrismInputError:
            reserved = frames.BASE_BYTES  # the frame itself is refused, with its own message
        return cls(available, reserved)

    def admit(self, image_name: str, node_name: str, width: int, height: int, cost: TexelCost,
              premultiplied: bool = False) -> None:
        """Count a ``width`` x ``height`` image about to be read; ``TextureMemoryError`` naming the image, its
        size, the estimate and the fix when it would not fit."""
        texels = width * height
        reading = TexelCost(cost.blender, cost.reading + (PREMULTIPLIED_READING if premultiplied else 0), cost.kept)
        before = self.reserved_bytes + self.kept_bytes
        needed = before + reading.peak * texels
        usable = None if self.available_bytes is None else frames.USABLE_FRACTION * self.available_bytes
        if usable is not None and needed > usable:
            raise TextureMemoryError(self._refusal(image_name, node_name, width, height, reading, before, usable))
        self.kept_bytes += cost.held * texels

    def _refusal(self, image_name, node_name, width, height, cost, before, usable) -> str:
        room = max(usable - before, 0.0)
        scale = math.sqrt(room / (cost.peak * width * height))
        fits = (f"e.g. {max(1, int(width * scale))} x {max(1, int(height * scale))} would fit" if scale >= 1 / 64
                else "no size of it fits beside the frame: lower Output ▸ Format ▸ Resolution % too")
        kind = "float" if cost.blender == FLOAT.blender else "8-bit"
        return (
            f"the '{node_name}' node's image '{image_name}' ({width} x {height}, {kind}) needs about "
            f"{_size(cost.peak * width * height)} while Prism reads it ({cost.peak} bytes a texel; "
            f"{_size(cost.held * width * height)} stay for the render) on top of the {_size(before)} the "
            f"frame and the textures before it need, but only {_size(self.available_bytes)} of memory is "
            f"available: scale the image down (Image Editor ▸ Image ▸ Resize, or a smaller file; {fits}) or "
            "close other programs."
        )


class TextureCache(dict):
    """``nodes.images.read_image``'s cache of the images one render has read, with their ``budget``."""

    def __init__(self, budget: TextureBudget):
        super().__init__()
        self.budget = budget


def budget_of(cache) -> TextureBudget:
    """``cache``'s budget; a plain dict (a material compiled on its own) gets one without a frame."""
    budget = getattr(cache, "budget", None)
    return budget if budget is not None else TextureBudget(frames.available_memory_bytes())
