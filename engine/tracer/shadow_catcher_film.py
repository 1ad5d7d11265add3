"""The shadow catcher's accumulations and the images Cycles makes of them (Combined, Shadow Catcher pass).

A camera path that meets a shadow catcher splits there (``stages.shadow_catcher``): the path goes on
into Combined with every object, a copy shades the catcher seeing only catchers. Besides Combined (its
colour C and transparency) each sample writes, in the film's ``shadow_catcher`` columns:

- ``CATCHER_RGB``: what the copy brought (the catcher lit without the other objects), S;
- ``SPLITS``: 1 when the sample split (Cycles' PASS_SHADOW_CATCHER_SAMPLE_COUNT);
- ``MATTE_RGB`` / ``MATTE_TRANSPARENCY``: what the sample brought before the split (all of it when it did
  not split), M, and its transparency, where a split counts as see-through by the throughput's mean
  (Cycles' PASS_SHADOW_CATCHER_MATTE: the other objects over a transparent catcher);
- ``BACKGROUND_RGB``: the world seen along the camera ray (directly, or behind the catcher at the split),
  for the approximate Combined on an opaque film (Cycles' Background pass, added with a catcher).

Per pixel (means; Cycles divides sums, which is the same ratio), as Cycles' ``film_calculate_shadow_catcher``
and ``film_calculate_shadow_catcher_matte_with_shadow`` (kernel/film/read.h):

- Shadow Catcher pass: 1 where no sample split; else ratio = (C - M) / S per channel (1 where S is 0),
  alpha-overed on white with Combined's alpha: (1 - a) + a · ratio.
- Combined with the pass on (View Layer ▸ Passes ▸ Light ▸ Shadow Catcher): the matte, M and alpha
  1 - its transparency — the catcher transparent, its shadows only in the pass.
- Combined with the pass off (Cycles' "approximate shadow catcher", the default): alpha_matte =
  (1 - a_m) · (1 - mean(pass)) + a_m; with Film ▸ Transparent, M with alpha alpha_matte (the shadow in
  alpha); without, M + background · (1 - alpha_matte) with alpha 1 (the world behind the catcher,
  darkened by the shadow's grey).
"""

from __future__ import annotations

import numpy as np

CATCHER_RGB, SPLITS, MATTE_RGB, MATTE_TRANSPARENCY, BACKGROUND_RGB = 0, 3, 4, 7, 8
WIDTH = 11


def shadow_catcher_pass(combined: np.ndarray, combined_alpha: np.ndarray, columns: np.ndarray) -> np.ndarray:
    """Cycles' Shadow Catcher pass, float64 [..., 3], from Combined's mean colour [..., 3] (unexposed), its
    alpha [...] and the pixel means of the catcher columns [..., WIDTH]."""
    catcher = columns[..., CATCHER_RGB:CATCHER_RGB + 3]
    matte = columns[..., MATTE_RGB:MATTE_RGB + 3]
    # the matte is taken out: only the catcher's own samples are divided (else its edges would show)
    ratio = np.divide(combined - matte, catcher, out=np.ones_like(catcher), where=catcher != 0.0)
    alpha = np.clip(combined_alpha, 0.0, 1.0)[..., None]
    pixel = (1.0 - alpha) + alpha * ratio
    return np.where(columns[..., SPLITS:SPLITS + 1] > 0.0, pixel, 1.0)


def combined_with_catcher(columns: np.ndarray, catcher_pass: np.ndarray, approximate: bool,
                          film_transparent: bool) -> tuple[np.ndarray, np.ndarray]:
    """Combined as Cycles writes it in a scene with a shadow catcher: (rgb [..., 3], alpha [...]), unexposed.
    ``approximate``: the Shadow Catcher pass is off (the shadow goes into Combined)."""
    matte = columns[..., MATTE_RGB:MATTE_RGB + 3]
    alpha = np.clip(1.0 - columns[..., MATTE_TRANSPARENCY], 0.0, 1.0)
    if not approximate:
        return matte, alpha
    shadow = 1.0 - np.clip(catcher_pass.mean(axis=-1), 0.0, 1.0)
    alpha_matte = (1.0 - alpha) * shadow + alpha
    if film_transparent:
        return matte, alpha_matte
    background = columns[..., BACKGROUND_RGB:BACKGROUND_RGB + 3]
    return matte + background * (1.0 - alpha_matte)[..., None], np.ones_like(alpha_matte)


def catcher_names(scene) -> list[str]:
    """The names of ``scene``'s objects marked Shadow Catcher (for messages)."""
    from .visibility import SHADOW_CATCHER

    flags = scene.object_flags
    if flags is None:
        return []
    names = scene.object_names
    return [names[o] if o < len(names) else f"object {o}" for o in np.flatnonzero(np.asarray(flags) & SHADOW_CATCHER)]


def catcher_warnings(settings, names: list[str]) -> list[str]:
    """What a render with the shadow catchers ``names`` does not do as Cycles does, for its warnings."""
    if not names:
        return []
    who = "Shadow catcher " + ", ".join(f"'{n}'" for n in names[:3]) + (" …" if len(names) > 3 else "")
    out = []
    if settings.passes.light_groups:
        out.append(f"{who}: the light group passes include the light it receives (Cycles leaves it out of them); "
                   "Combined and the Shadow Catcher pass are as Cycles writes them.")
    if settings.spectral_band_nm:
        out.append(f"{who}: the spectral EXR holds it as an ordinary object (its matte and shadow are in the RGB "
                   "Combined only).")
    return out
