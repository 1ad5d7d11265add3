"""Outlines of a lens system's elements for a cross-section drawing.

Pure geometry in lens coordinates: millimetres, ``z`` along the optical axis
(light travels towards +z), ``y`` up in the meridional plane. Every outline is a
polyline ``[K, 2]`` of ``(z_mm, y_mm)`` points.

An element is the glass between two consecutive refracting surfaces. It is drawn
as its two spherical caps (each up to its own clear aperture) joined at the top
and at the bottom by the element's edge: a step at the smaller cap up to the
larger clear radius, then a line parallel to the axis. The aperture stop is drawn
as two short bars reaching outwards from its opening.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

CAP_SEGMENTS = 48
STOP_BAR_FRACTION = 0.35  # bar length as a fraction of the stop's clear radius


@dataclass(frozen=True)
class ElementOutlines:
    """Polylines of a system's cross-section (all ``[K, 2]`` arrays of ``(z_mm, y_mm)``).

    ``elements``: one closed outline per glass element. ``stop``: the stop's two
    bars (upper, lower). ``surface_caps``: the cap of every refracting surface,
    for drawing surfaces that bound no glass (a mirror-free air gap never needs it,
    but a single surface prescription does).
    """

    elements: tuple
    stop: tuple
    surface_caps: tuple


def sag_mm(radius_mm, y_mm):
    """Sag ``z - z_vertex`` of a spherical surface at height ``y_mm``.

    ``radius_mm`` > 0: centre of curvature behind the vertex (+z). Zero or
    infinite radius means flat. Heights beyond the sphere's reach are clamped to the equator.
    """
    y_mm = np.asarray(y_mm, dtype=np.float64)
    if radius_mm == 0.0 or not np.isfinite(radius_mm):
        return np.zeros_like(y_mm)
    reach = np.minimum(np.abs(y_mm), abs(radius_mm))
    return radius_mm - np.sign(radius_mm) * np.sqrt(radius_mm**2 - reach**2)


def cap_polyline(vertex_z_mm, radius_mm, clear_radius_mm, segments=CAP_SEGMENTS):
    """The cap of one surface from ``-clear_radius_mm`` to ``+clear_radius_mm``: ``[segments+1, 2]``."""
    y = np.linspace(-clear_radius_mm, clear_radius_mm, segments + 1)
    return np.column_stack([vertex_z_mm + sag_mm(radius_mm, y), y])


def element_outline(front, back):
    """Closed outline of one element from its two surfaces.

    ``front`` and ``back``: ``(vertex_z_mm, radius_mm, clear_radius_mm)``. The
    polyline runs up the front cap, across the top edge, down the back cap and
    back along the bottom edge.
    """
    zf, rf, af = front
    zb, rb, ab = back
    edge = max(af, ab)
    front_cap = cap_polyline(zf, rf, af)
    back_cap = cap_polyline(zb, rb, ab)[::-1]
    zf_edge = zf + float(sag_mm(rf, af))
    zb_edge = zb + float(sag_mm(rb, ab))
    top = [(zf_edge, edge), (zb_edge, edge)]
    bottom = [(zb_edge, -edge), (zf_edge, -edge)]
    points = np.vstack([front_cap, top, back_cap, bottom, front_cap[:1]])
    return _drop_repeats(points)


def _drop_repeats(points):
    keep = np.ones(len(points), dtype=bool)
    keep[1:] = np.any(np.abs(np.diff(points, axis=0)) > 1e-12, axis=1)
    return points[keep]


def stop_bars(vertex_z_mm, clear_radius_mm, bar_length_mm=None):
    """The aperture stop as two bars at ``vertex_z_mm``: upper and lower, each ``[2, 2]``."""
    length = STOP_BAR_FRACTION * clear_radius_mm if bar_length_mm is None else bar_length_mm
    upper = np.array([[vertex_z_mm, clear_radius_mm], [vertex_z_mm, clear_radius_mm + length]])
    lower = upper * np.array([1.0, -1.0])
    return upper, lower


def outlines(vertex_z_mm, radius_mm, clear_radius_mm, glass_after, stop_index, stop_clear_radius_mm=None):
    """Outlines of a whole system, surface by surface.

    ``vertex_z_mm``, ``radius_mm``, ``clear_radius_mm``: per surface (in order).
    ``glass_after[i]``: whether the medium after surface ``i`` is glass, i.e. an
    element lies between surfaces ``i`` and ``i + 1``. ``stop_index``: the stop
    surface (or ``None``); ``stop_clear_radius_mm`` overrides its opening (the
    f-stop the user set). The stop's bars reach out to the larger of the
    neighbouring surfaces' clear radii and 135 % of the opening, so a small f-stop
    reads as a diaphragm closing inside the barrel.
    """
    z = np.asarray(vertex_z_mm, dtype=np.float64)
    r = np.asarray(radius_mm, dtype=np.float64)
    a = np.asarray(clear_radius_mm, dtype=np.float64)
    n = len(z)
    elements = tuple(
        element_outline((z[i], r[i], a[i]), (z[i + 1], r[i + 1], a[i + 1]))
        for i in range(n - 1)
        if glass_after[i] and i != stop_index and i + 1 != stop_index
    )
    caps = tuple(cap_polyline(z[i], r[i], a[i]) for i in range(n) if i != stop_index)
    stop = ()
    if stop_index is not None:
        opening = a[stop_index] if stop_clear_radius_mm is None else float(stop_clear_radius_mm)
        neighbours = a[max(stop_index - 1, 0) : stop_index + 2]
        outer = max(float(neighbours.max()), opening * (1.0 + STOP_BAR_FRACTION))
        stop = stop_bars(z[stop_index], opening, outer - opening)
    return ElementOutlines(elements=elements, stop=stop, surface_caps=caps)


def system_outlines(system) -> ElementOutlines:
    """Outlines of a ``LensSystem`` (its stop drawn at the system's current stop diameter)."""
    surfaces = system.surfaces
    stop = next((i for i, s in enumerate(surfaces) if s.is_stop), None)
    return outlines(
        system.vertex_z_mm,
        [s.radius_mm for s in surfaces],
        [s.semi_aperture_mm for s in surfaces],
        [not getattr(s.medium, "is_air", False) for s in surfaces],
        stop,
    )
