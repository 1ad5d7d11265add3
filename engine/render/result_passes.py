"""Blender's side of the render passes: what a view layer asks for, the passes Prism registers, and the
pixels written into the Render Result.

The switches are Blender's own (View Layer ▸ Passes: ``ViewLayer.use_pass_z``, ``use_pass_normal``, …,
its AOVs and Light Groups, ``Object.lightgroup``, ``World.lightgroup``), so a scene set up for Cycles
gives the same passes with Prism. Prism adds Denoising Data, Noise and Sample Count (``Scene.prism``).
Imports no numpy until pixels are written (``update_render_passes`` runs in the UI).
"""

from __future__ import annotations

from ..tracer.cryptomatte import DEFAULT_LEVELS
from ..tracer.errors import PrismInputError
from ..tracer.frame_plan import DEFAULT_TILE_SIZE, film_bytes_per_pixel, plan_frame
from ..tracer.pass_table import (CYCLES_VIEW_LAYER_SWITCH, DENOISING_PASSES, PASSES, VIEW_LAYER_SWITCH, FilmLayout,
                                 PassRequest, blender_passes)

#: View Layer ▸ Passes ▸ Cryptomatte: the switch of each kind (``tracer.cryptomatte.KINDS``).
CRYPTOMATTE_SWITCH = {"Object": "use_pass_cryptomatte_object", "Material": "use_pass_cryptomatte_material",
                      "Asset": "use_pass_cryptomatte_asset"}

COMBINED = ("Combined", "RGBA", "COLOR")
NOISY_IMAGE = ("Noisy Image", "RGBA", "COLOR")
NOISE = ("Noise", "RGB", "COLOR")
SAMPLE_COUNT = ("Sample Count", "X", "VALUE")
#: The guides the final-frame denoiser reads.
DENOISER_GUIDES = ("Denoising Albedo", "Denoising Normal")


def _view_layer(scene, view_layer):
    if view_layer is not None:
        return view_layer
    layers = getattr(scene, "view_layers", None)
    return layers[0] if layers else None


def denoising(scene) -> bool:
    prism = getattr(scene, "prism", None)
    return bool(prism is not None and prism.use_denoising)


def pass_request(scene, view_layer=None, for_render: bool = False) -> PassRequest:
    """The passes ``view_layer`` of ``scene`` asks for. ``for_render``: add what the final-frame denoiser
    needs even when not written out."""
    layer = _view_layer(scene, view_layer)
    prism = getattr(scene, "prism", None)
    names = []
    if layer is not None:
        names = [name for name, switch in VIEW_LAYER_SWITCH.items() if getattr(layer, switch, False)]
        cycles = getattr(layer, "cycles", None)  # Cycles' own switches (Shadow Catcher), read where Cycles keeps them
        names += [name for name, switch in CYCLES_VIEW_LAYER_SWITCH.items() if getattr(cycles, switch, False)]
    if prism is not None and prism.use_pass_denoising_data:
        names += DENOISING_PASSES
    if for_render and denoising(scene):
        names += [name for name in DENOISER_GUIDES if name not in names]
    groups, aovs, crypto, levels = (), {}, (), DEFAULT_LEVELS
    if layer is not None:
        groups = tuple(dict.fromkeys(g.name for g in layer.lightgroups if g.name))
        aovs = {aov.name: aov.type for aov in layer.aovs if aov.name and getattr(aov, "is_valid", True)}
        crypto = tuple(kind for kind, switch in CRYPTOMATTE_SWITCH.items() if getattr(layer, switch, False))
        levels = int(getattr(layer, "pass_cryptomatte_depth", levels))
    return PassRequest(passes=tuple(n for n in PASSES if n in names), light_groups=groups, aovs=aovs,
                       cryptomatte=crypto, cryptomatte_levels=levels)


def enabled_passes(scene, view_layer=None) -> list[tuple[str, int, str, str]]:
    """Every pass besides Combined Prism writes for ``view_layer``: (name, channels, channel ids, type)."""
    prism = getattr(scene, "prism", None)
    out = []
    if denoising(scene):
        out.append(NOISY_IMAGE)
    out += blender_passes(pass_request(scene, view_layer))
    if prism is not None and prism.use_pass_variance:
        out.append(NOISE)
    if prism is not None and prism.use_pass_sample_count:
        out.append(SAMPLE_COUNT)
    return [(name, len(ids), ids, kind) for name, ids, kind in out]


def frame_plan(scene, view_layer, width: int, height: int, region=None, whole_film: bool = False):
    """Tiles of ``region`` (default: the frame) and the memory check for the passes ``view_layer`` asks
    for (``tracer.frame_plan``); ``whole_film``: no tiles (a sample chunk keeps its whole film)."""
    prism = getattr(scene, "prism", None)
    layout = FilmLayout(pass_request(scene, view_layer, for_render=True))
    channels = sum(channels for _, channels, _, _ in enabled_passes(scene, view_layer))
    tile_size = DEFAULT_TILE_SIZE if prism is None else int(prism.tile_size) if prism.use_auto_tile else 0
    try:
        return plan_frame(width, height, region or (0, 0, width, height), film_bytes_per_pixel(layout), channels,
                          0 if whole_film else tile_size)
    except PrismInputError as error:
        raise PrismInputError(f"Scene '{scene.name}': {error}") from None


def bottom_up(image, alpha: bool = False):
    """[H, W, C] with row 0 at the top → Blender's flat [H*W, C(+1)], first row at the bottom."""
    import numpy as np

    height, width, channels = image.shape
    if alpha:
        rgba = np.ones((height, width, channels + 1), np.float32)
        rgba[..., :channels] = image
        image = rgba
    return np.ascontiguousarray(image[::-1], dtype=np.float32).reshape(height * width, -1)


def write_passes(result_passes, images: dict, wanted: set[str]) -> None:
    """Copy each ``images[name]`` ([h, w, C], row 0 on top) into the Render Result pass of that name
    (padded with alpha 1 where Blender's pass has one more channel)."""
    for name, image in images.items():
        if name not in wanted:
            continue
        target = result_passes.get(name)
        if target is None:
            continue
        alpha = target.channels == image.shape[-1] + 1
        target.rect = bottom_up(image, alpha=alpha)
