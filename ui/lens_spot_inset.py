"""The spot diagram inset: where each wavelength's rays meet the sensor, drawn in pixel space with its
RMS radii, both in the viewport (``lens_overlay_draw``'s ``POST_PIXEL`` handler) and in the exported
lens diagram PNG (``lens_overlay_export``). Call it inside a draw callback or an offscreen bind only.
"""

from __future__ import annotations

import math

from .lens_overlay_colours import SENSOR_RGBA, SPOT_BACKGROUND_RGBA, SPOT_POINT_SIZE, TEXT_RGBA, display_colours


def nice_extent_um(value_um):
    """The smallest 1, 2 or 5 x 10^k micrometres not below ``value_um``."""
    if not value_um > 0.0 or not math.isfinite(value_um):
        return 1.0
    power = 10.0 ** math.floor(math.log10(value_um))
    return next(m * power for m in (1.0, 2.0, 5.0, 10.0) if m * power >= value_um * (1 - 1e-9))


def _rectangle(shader, x0, y0, x1, y1, rgba, filled):
    from gpu_extras.batch import batch_for_shader

    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    shader.uniform_float("color", rgba)
    if filled:
        batch_for_shader(shader, "TRIS", {"pos": corners}, indices=((0, 1, 2), (0, 2, 3))).draw(shader)
    else:
        batch_for_shader(shader, "LINE_STRIP", {"pos": corners + corners[:1]}).draw(shader)


def _spot_legend(diagram, colours, half_um):
    lines = [(f"Spot diagram (box {2 * half_um:g} µm)", TEXT_RGBA)]
    for wavelength, rgb, spot in zip(diagram.wavelengths_nm, colours, diagram.spots):
        rms = "no rays reach the sensor" if not len(spot.hits_mm) else f"RMS {1000.0 * spot.rms_radius_mm:.1f} µm"
        lines.append((f"{wavelength:g} nm  {rms}", (*(0.7 * c + 0.3 for c in rgb), 1.0)))  # lifted to read on dark
    return lines


def draw_spot_inset(diagram, x0, y0, size, font_size, point_size=SPOT_POINT_SIZE):
    """Spot diagram in pixel space: a ``size`` px square at (``x0``, ``y0``) (bottom left), one
    colour per wavelength, around the centroid of all hits, with its legend (RMS radii) above
    it, all on a dark panel so it reads over any background. Returns the panel's height."""
    import blf
    import gpu
    import numpy as np
    from gpu_extras.batch import batch_for_shader

    spots = [s for s in diagram.spots if len(s.hits_mm)]
    colours = display_colours(diagram.wavelengths_nm)
    half_um, centre = 1.0, np.zeros(2)
    if spots:
        all_hits = np.concatenate([s.hits_mm for s in spots])
        centre = all_hits.mean(axis=0)
        half_um = nice_extent_um(1000.0 * 1.05 * float(np.abs(all_hits - centre).max()))
    font, line, pad = 0, 1.4 * font_size, 0.5 * font_size
    blf.size(font, font_size)
    legend = _spot_legend(diagram, colours, half_um)
    width = max(size, max(blf.dimensions(font, text)[0] for text, _ in legend))
    top = y0 + size + pad + len(legend) * line
    gpu.state.blend_set("ALPHA")
    flat = gpu.shader.from_builtin("UNIFORM_COLOR")
    flat.bind()
    _rectangle(flat, x0 - pad, y0 - pad, x0 + width + pad, top + pad, SPOT_BACKGROUND_RGBA, True)
    _rectangle(flat, x0, y0, x0 + size, y0 + size, SENSOR_RGBA, False)
    if spots:
        pos, col = [], []
        for spot in spots:
            rgb = colours[diagram.wavelengths_nm.index(spot.wavelength_nm)]
            xy = (spot.hits_mm - centre) * (1000.0 / half_um) * (0.5 * size) + (x0 + 0.5 * size, y0 + 0.5 * size)
            pos.append(xy)
            col.append(np.tile((*rgb, 0.85), (len(xy), 1)))
        shader = gpu.shader.from_builtin("POINT_FLAT_COLOR")
        gpu.state.point_size_set(point_size)
        gpu.state.blend_set("ADDITIVE")
        points = {"pos": np.concatenate(pos).astype(np.float32), "color": np.concatenate(col).astype(np.float32)}
        batch_for_shader(shader, "POINTS", points).draw(shader)
    for k, (text, rgba) in enumerate(reversed(legend)):
        blf.color(font, *rgba)
        blf.position(font, x0, y0 + size + pad + k * line + 0.3 * font_size, 0)
        blf.draw(font, text)
    gpu.state.blend_set("NONE")
    return top + pad - (y0 - pad)
