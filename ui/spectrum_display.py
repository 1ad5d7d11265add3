"""Drawing a light's or material's spectrum in a panel: the plot, the colour metrics of an emitter,
or the message of a spectrum the render would refuse. Previews come from ``engine.output.spectrum_preview``
(computed off the main thread); while one is computed a timer redraws the Properties editor when it
is ready."""

from __future__ import annotations

import bpy

from ..engine.output.spectrum_preview import pending
from . import spectral_plot
from ._panel_base import error_label

PLOT_SCALE = 10.0
_POLL_SECONDS = 0.25


def _redraw_when_ready():
    if pending():
        return _POLL_SECONDS
    window_manager = bpy.context.window_manager
    for window in getattr(window_manager, "windows", ()):
        for area in window.screen.areas:
            if area.type == "PROPERTIES":
                area.tag_redraw()
    return None


def _watch() -> None:
    if not bpy.app.timers.is_registered(_redraw_when_ready):
        bpy.app.timers.register(_redraw_when_ready, first_interval=_POLL_SECONDS)


def metric_lines(preview) -> list[str]:
    """The colour metrics of an emitter's preview, one label each."""
    if preview.cct_k is None:
        return ["CCT, CRI: not defined (far from white light)"]
    lines = [f"CCT {preview.cct_k:.0f} K, Duv {preview.duv:+.4f}"]
    if preview.cri_ra is not None:
        lines.append(f"CRI Ra {preview.cri_ra:.0f}")
    if preview.tm30_rf is not None:
        lines.append(f"TM-30 Rf {preview.tm30_rf:.0f}, Rg {preview.tm30_rg:.0f}")
    return lines


def draw_spectrum(layout, plot_name: str, preview, caption: str, metrics: bool) -> None:
    """The plot of ``preview`` (a ``SpectrumPreview``, None while computed) with ``caption`` under it,
    and the emitter metrics when ``metrics``."""
    if preview is None:
        layout.label(text="Computing the spectrum…", icon="TIME")
        _watch()
        return
    if preview.error:
        error_label(layout, preview.error)
        return
    box = layout.box()
    box.template_icon(icon_value=spectral_plot.spectrum_icon_id(plot_name, preview.values), scale=PLOT_SCALE)
    box.label(text=caption)
    if metrics:
        column = box.column(align=True)
        for line in metric_lines(preview):
            column.label(text=line)
