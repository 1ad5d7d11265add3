"""Node materials against Cycles: the same .blend rendered by both, compared by statistics.

Cycles is the oracle (set up by ``helpers/cycles.py``): single-scatter GGX everywhere (Multiscatter GGX, Blender's default,
has its own comparison in absolute luminance: ``test_multiscatter_cycles.py``), box filter, no adaptive
sampling or denoising, equal bounce limits. Images are compared in absolute light, per object (pixels an
ID render shows wholly inside one object) and by relative MSE. Saturated colours met twice along a path are
avoided: the product of two smooth spectra
is less saturated than the product of two RGB triples, a real difference between a spectral and an RGB
renderer, not an error of either.
"""

from __future__ import annotations

import numpy as np
import pytest

from helpers.cycles_compare import LUMINANCE, object_ids, region_ratios, relative_mse, render_cycles, \
    render_prism
from helpers.shader_scene import build_shader_scene
from helpers.texture_board import build_texture_board


def test_shader_nodes_render_as_in_cycles(prism_addon, fresh_scene):
    """Principled (plastic, textured, metal, coat, specular tint), Glossy, Glass, Refraction, Diffuse,
    Translucent, Transparent, Emission, Mix by Layer Weight and by Fresnel, Add, Bump, a tangent-space Normal
    Map, a node group behind a reroute: each sphere's absolute brightness within 2 % of Cycles'."""
    names, spheres = build_shader_scene()
    ids = object_ids(fresh_scene, spheres)
    cycles = render_cycles(fresh_scene, 256, max_bounces=12)
    prism = render_prism(fresh_scene, 256, max_bounces=12)
    p, c = prism, cycles  # absolute: an energy error in any shader shows
    ratios = region_ratios(p, c, ids, len(spheres))
    assert len(ratios) == len(spheres)
    report = {names[i]: round(r, 4) for i, r in ratios.items()}
    assert all(abs(r - 1.0) < 0.02 for r in ratios.values()), report
    assert relative_mse(p, c) < 0.03, relative_mse(p, c)


def test_textures_and_colour_nodes_match_blender_pixel_by_pixel(prism_addon, fresh_scene):
    """Emissive tiles of Checker, Noise (fBM, ridged), Voronoi, Wave, Brick, Magic, Gradient, White Noise,
    Color Ramp, Map Range, Math, Mix (overlay), Hue/Saturation, Invert, Bright/Contrast, an sRGB image,
    Separate/Combine Color (HSV), RGB Curves, Object Info (colour, random), a colour Attribute, UV Map,
    Mapping and Separate/Combine XYZ: each tile's colour within 2 % of Cycles' and its pattern in place
    (per-pixel error at noise level)."""
    names, tiles = build_texture_board()
    ids = object_ids(fresh_scene, tiles)
    cycles = render_cycles(fresh_scene, 16, max_bounces=1)
    prism = render_prism(fresh_scene, 16, max_bounces=1)
    for index, name in enumerate(names):
        inside = ids == index
        assert inside.sum() > 150, name
        lp, lc = prism[inside] @ LUMINANCE, cycles[inside] @ LUMINANCE
        assert lp.mean() == pytest.approx(lc.mean(), rel=0.02), name
        # The pattern is in place: pixel by pixel the colours agree (a shifted or rescaled pattern would
        # differ by the pattern's own contrast, tenths).
        rms = float(np.sqrt(np.mean((prism[inside] - cycles[inside]) ** 2)))
        assert rms < 0.05, (name, rms)
