"""Plots in panels: the render panel's three channel Gaussians against the CIE colour-matching
functions, and the spectrum of a light or material (Light and Material panels).

Drawn with numpy into a ``bpy.utils.previews`` image and shown with
``layout.template_icon``; regenerated only when the values it shows change.
"""

from __future__ import annotations

import sys

import numpy as np

from ..engine.tracer.spectra.wavelengths import VISIBLE_RANGE_NM as PLOT_RANGE_NM

PLOT_WIDTH_PX = 240
PLOT_HEIGHT_PX = 120
_MARGIN_PX = 4
_BACKGROUND = (0.12, 0.12, 0.12)
_CMF_COLOURS = ((0.75, 0.55, 0.55), (0.55, 0.75, 0.55), (0.55, 0.6, 0.8))
_CHANNEL_COLOURS = ((1.0, 0.25, 0.2), (0.3, 1.0, 0.3), (0.3, 0.45, 1.0))

_previews = None
_plot_key = None


def cmf_curves(wavelength_nm) -> tuple[np.ndarray, str]:
    """CIE 1931 x̄, ȳ, z̄ at ``wavelength_nm`` ([N, 3]) and where they came from.

    Uses ``engine.tracer.spectra.cie``'s tables once colour-science is loaded (after a
    render); until then the analytic fit, so drawing a panel never stalls Blender
    for the second colour-science takes to import.
    """
    from ..engine.properties.spectral_colour import cmf_xyz

    if "colour" in sys.modules:
        try:
            from ..engine.tracer.spectra import cie

            return np.asarray(cie.cie_xyz_cmf(wavelength_nm), dtype=np.float64), "table"
        except Exception:  # noqa: BLE001 - the plot falls back to the fit rather than fail to draw
            pass
    return cmf_xyz(wavelength_nm), "fit"


def _rows_for(values: np.ndarray) -> np.ndarray:
    """Map curve values in [0, 1] to pixel rows counted from the bottom."""
    return _MARGIN_PX + np.clip(values, 0.0, 1.05) * (PLOT_HEIGHT_PX - 1 - 2 * _MARGIN_PX)


def _blend(image: np.ndarray, mask: np.ndarray, colour, alpha: float) -> None:
    image[mask, :3] = (1.0 - alpha) * image[mask, :3] + alpha * np.asarray(colour)


def _line_mask(curve_at_edges: np.ndarray, half_width_px: float) -> np.ndarray:
    """Pixels [H, W] covered by a polyline whose values at the W+1 column edges are given."""
    rows = _rows_for(curve_at_edges)
    low = np.minimum(rows[:-1], rows[1:]) - half_width_px
    high = np.maximum(rows[:-1], rows[1:]) + half_width_px
    centres = np.arange(PLOT_HEIGHT_PX, dtype=np.float64)[:, None] + 0.5
    return (centres >= low[None, :]) & (centres <= high[None, :] + 1.0)


def render_plot(means_nm, sigmas_nm, cmf_at_edges: np.ndarray, channels_active: bool) -> np.ndarray:
    """RGBA float32 image [H, W, 4] (row 0 at the bottom, as Blender stores images).

    ``cmf_at_edges``: the CMFs at the W+1 column edges ([W+1, 3]); the Gaussians are
    drawn with peak height 1, the CMFs scaled together so their highest peak is 1.
    """
    edges_nm = np.linspace(*PLOT_RANGE_NM, PLOT_WIDTH_PX + 1)
    centres_nm = 0.5 * (edges_nm[:-1] + edges_nm[1:])
    image = np.empty((PLOT_HEIGHT_PX, PLOT_WIDTH_PX, 4), dtype=np.float64)
    image[..., :3] = _BACKGROUND
    image[..., 3] = 1.0

    cmf = cmf_at_edges / max(float(cmf_at_edges.max()), 1e-12)
    for column, colour in zip(cmf.T, _CMF_COLOURS):
        _blend(image, _line_mask(column, 0.5), colour, 0.9)

    rows = np.arange(PLOT_HEIGHT_PX, dtype=np.float64)[:, None] + 0.5
    fill_alpha, line_alpha = (0.3, 1.0) if channels_active else (0.1, 0.4)
    for mean, sigma, colour in zip(means_nm, sigmas_nm, _CHANNEL_COLOURS):
        gaussian_edges = np.exp(-0.5 * ((edges_nm - mean) / sigma) ** 2)
        gaussian_centres = np.exp(-0.5 * ((centres_nm - mean) / sigma) ** 2)
        _blend(image, rows <= _rows_for(gaussian_centres)[None, :], colour, fill_alpha)
        _blend(image, _line_mask(gaussian_edges, 0.8), colour, line_alpha)
    return image.astype(np.float32)


def wavelength_colours(wavelength_nm) -> np.ndarray:
    """Display colour [N, 3] of light at each wavelength (brightest channel 1), from the analytic CMF fit."""
    from ..engine.properties.spectral_colour import XYZ_TO_REC709, cmf_xyz

    rgb = np.clip(cmf_xyz(wavelength_nm) @ XYZ_TO_REC709.T, 0.0, None)
    return rgb / np.maximum(rgb.max(axis=1, keepdims=True), 1e-12)


def render_spectrum_plot(values: np.ndarray) -> np.ndarray:
    """RGBA float32 image [H, W, 4] (row 0 at the bottom) of a spectrum sampled every nm over 360-830 nm
    (values 0-1, 1 = the plot's top): the area under the curve in each wavelength's colour."""
    edges_nm = np.linspace(*PLOT_RANGE_NM, PLOT_WIDTH_PX + 1)
    centres_nm = 0.5 * (edges_nm[:-1] + edges_nm[1:])
    grid = np.linspace(*PLOT_RANGE_NM, len(values))
    # The highest value in each column's span, so a line narrower than a pixel column still shows.
    column = np.minimum(((grid - PLOT_RANGE_NM[0]) / (PLOT_RANGE_NM[1] - PLOT_RANGE_NM[0]) * PLOT_WIDTH_PX)
                        .astype(int), PLOT_WIDTH_PX - 1)
    heights = np.zeros(PLOT_WIDTH_PX)
    np.maximum.at(heights, column, np.asarray(values, np.float64))
    image = np.empty((PLOT_HEIGHT_PX, PLOT_WIDTH_PX, 4), dtype=np.float64)
    image[..., :3] = _BACKGROUND
    image[..., 3] = 1.0
    rows = np.arange(PLOT_HEIGHT_PX, dtype=np.float64)[:, None] + 0.5
    for level in (0.25, 0.5, 0.75, 1.0):
        _blend(image, np.abs(rows - _rows_for(np.full(PLOT_WIDTH_PX, level))[None, :]) < 0.5, (0.3, 0.3, 0.3), 1.0)
    under = rows <= _rows_for(heights)[None, :]
    colours = np.broadcast_to(wavelength_colours(centres_nm)[None], image[..., :3].shape)
    image[..., :3] = np.where(under[..., None], 0.3 * image[..., :3] + 0.7 * colours, image[..., :3])
    at_edges = np.concatenate([heights[:1], np.maximum(heights[1:], heights[:-1]), heights[-1:]])
    _blend(image, _line_mask(at_edges, 0.6), (0.95, 0.95, 0.95), 1.0)
    return image.astype(np.float32)


_spectrum_keys: dict[str, tuple] = {}


def spectrum_icon_id(name: str, values) -> int:
    """Icon id of the plot named ``name`` (one per panel) showing ``values`` (regenerated on change)."""
    if _previews is None:
        return 0
    preview = _previews.get(name) or _previews.new(name)
    key = tuple(values)
    if _spectrum_keys.get(name) != key:
        preview.image_size = (PLOT_WIDTH_PX, PLOT_HEIGHT_PX)
        preview.image_pixels_float = render_spectrum_plot(np.asarray(values, np.float64)).ravel()
        _spectrum_keys[name] = key
    return preview.icon_id


def plot_icon_id(scene_settings) -> int:
    """Icon id of the plot for ``Scene.prism`` (regenerated only when its values changed)."""
    global _plot_key
    if _previews is None:
        return 0
    preview = _previews.get("wavelength_plot") or _previews.new("wavelength_plot")
    means = scene_settings.channel_means_nm()
    sigmas = scene_settings.channel_sigmas_nm()
    active = scene_settings.wavelength_mode == "GAUSSIAN_RGB"
    edges_nm = np.linspace(*PLOT_RANGE_NM, PLOT_WIDTH_PX + 1)
    cmf_source = "table" if "colour" in sys.modules else "fit"
    key = (tuple(round(v, 3) for v in means + sigmas), active, cmf_source)
    if key != _plot_key:
        cmf, _ = cmf_curves(edges_nm)
        image = render_plot(means, sigmas, cmf, active)
        preview.image_size = (PLOT_WIDTH_PX, PLOT_HEIGHT_PX)
        preview.image_pixels_float = image.ravel()
        _plot_key = key
    return preview.icon_id


def register():
    global _previews, _plot_key
    import bpy.utils.previews

    _previews = bpy.utils.previews.new()
    _plot_key = None
    _spectrum_keys.clear()


def unregister():
    global _previews, _plot_key
    import bpy.utils.previews

    if _previews is not None:
        bpy.utils.previews.remove(_previews)
    _previews = None
    _plot_key = None
    _spectrum_keys.clear()
