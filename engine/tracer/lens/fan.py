"""Ray fans and spot diagrams through a lens system, for the lens overlay ("lenstester").

Pure geometry on top of ``LensSystem.trace(..., toward="film", record_path=True)``: this
module generates the rays and sorts out what the tracer recorded; it never refracts.

Lens coordinates (mm): z along the optical axis from the scene toward the film, the front
vertex at z = 0, y up in the meridional plane. A point source sits on the scene side, in
the plane ``z = z_mm`` (``-inf`` = infinitely far: parallel rays) and ``field_angle_deg``
above the axis as seen from the front vertex, so its rays travel downwards for a positive
angle.

The meridional fan aims N rays at evenly spaced heights across the front clear aperture
(so rays the stop or another aperture clips show up as blocked). The spot diagram aims a
square grid over the part of the front plane whose meridional rays actually pass (found by
tracing a dense 1D scan), so it keeps enough rays at small f-stops.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .ray_fate import FATE_ALIVE, FATE_BLOCKED, FATE_MISSED, FATE_TIR
from .system import TOWARD_FILM

LEAD_IN_FRACTION = 0.3  # incoming rays start this fraction of the lens length before the front
PUPIL_SCAN_RAYS = 801
SPOT_GRID = 31  # spot diagram: SPOT_GRID x SPOT_GRID aim points, those inside the pupil disk kept


@dataclass(frozen=True)
class PointSource:
    """Where the fan comes from: the plane ``z_mm`` (lens coordinates, < 0; ``-inf`` = at
    infinity) and ``field_angle_deg`` above the axis."""

    z_mm: float = -np.inf
    field_angle_deg: float = 0.0

    @property
    def at_infinity(self) -> bool:
        return not np.isfinite(self.z_mm)

    @classmethod
    def from_film_distance(cls, system, sensor_distance_mm, distance_mm, field_angle_deg=0.0):
        """A source ``distance_mm`` in front of the film (as Blender measures focus; ``inf`` or
        0 = at infinity), the film being ``sensor_distance_mm`` behind the rear vertex."""
        if not np.isfinite(distance_mm) or distance_mm <= 0.0:
            return cls(-np.inf, field_angle_deg)
        return cls(system.rear_z_mm + sensor_distance_mm - float(distance_mm), field_angle_deg)


@dataclass(frozen=True)
class RayFan:
    """N rays of one wavelength as polylines, each with its fate.

    ``points_mm`` [N, V, 3]: vertices from the start point through every surface hit to the
    sensor (reached rays only); rows are padded by repeating their last valid vertex, and
    ``vertex_count`` [N] says how many are valid. ``fate`` [N] int8 uses the tracer's codes
    (``FATE_ALIVE`` = reached the sensor plane); ``fate_surface`` [N] is the index of the
    surface where the ray was blocked or totally reflected (-1 for reached rays).
    """

    wavelength_nm: float
    points_mm: np.ndarray
    vertex_count: np.ndarray
    fate: np.ndarray
    fate_surface: np.ndarray

    @property
    def reached(self) -> np.ndarray:
        return self.fate == FATE_ALIVE

    def segments(self):
        """``(starts [M, 3], ends [M, 3], ray [M])``: every drawn segment and its ray index."""
        n, v = self.points_mm.shape[:2]
        valid = np.arange(1, v)[None, :] < self.vertex_count[:, None]
        ray, k = np.nonzero(valid)
        return self.points_mm[ray, k], self.points_mm[ray, k + 1], ray

    def fate_names(self) -> list[str]:
        """``"sensor"``, ``"blocked at surface i"`` or ``"TIR at surface i"`` per ray."""
        kind = {FATE_ALIVE: "sensor", FATE_BLOCKED: "blocked", FATE_MISSED: "blocked", FATE_TIR: "TIR"}
        return [
            "sensor" if f == FATE_ALIVE else f"{kind[f]} at surface {s}"
            for f, s in zip(self.fate.tolist(), self.fate_surface.tolist())
        ]


@dataclass(frozen=True)
class SpotDiagram:
    """Where rays of one wavelength from a pupil grid land on the sensor.

    ``hits_mm`` [M, 2]: (x, y) on the sensor plane of the rays that reached it.
    ``centroid_mm`` (2,), ``rms_radius_mm``: root-mean-square distance of the hits from
    their own centroid (NaN without hits). ``traced``: rays aimed.
    """

    wavelength_nm: float
    hits_mm: np.ndarray
    centroid_mm: np.ndarray
    rms_radius_mm: float
    traced: int


def front_extent_mm(system) -> tuple[float, float]:
    """Lowest z reached by any surface cap (a concave front rim lies before z = 0), and the
    largest clear radius. Used to place the incoming rays and to size drawings."""
    z = system.vertex_z_mm
    rims = [zi + float(s.sag_mm(s.semi_aperture_mm)) for zi, s in zip(z, system.surfaces)]
    rims = np.nan_to_num(np.array(rims), nan=0.0)
    return min(0.0, float(rims.min())), max(s.semi_aperture_mm for s in system.surfaces)


def _source_rays(system, source, aim_xy_mm, sensor_z_mm):
    """Origins and unit directions of rays from ``source`` aimed at points of the plane z = 0."""
    aim = np.column_stack([aim_xy_mm, np.zeros(len(aim_xy_mm))])
    theta = np.radians(source.field_angle_deg)
    z_front, _ = front_extent_mm(system)
    lead_in = LEAD_IN_FRACTION * max(sensor_z_mm, system.rear_z_mm, 1e-6)
    z_start = z_front - lead_in
    if source.at_infinity:
        d = np.broadcast_to(np.array([0.0, -np.sin(theta), np.cos(theta)]), aim.shape).copy()
    else:
        point = np.array([0.0, -source.z_mm * np.tan(theta), source.z_mm])
        d = aim - point
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        if source.z_mm >= z_start:
            return np.broadcast_to(point, aim.shape).copy(), d
    t = (aim[:, 2] - z_start) / d[:, 2]
    return aim - t[:, None] * d, d


def _trace_to_sensor(system, origins, directions, wavelength_nm, sensor_z_mm):
    result = system.trace(origins, directions, wavelength_nm, toward=TOWARD_FILM, record_path=True)
    path = np.transpose(result.path, (1, 0, 2))  # [N, S+1, 3]
    alive = result.alive
    t = (sensor_z_mm - result.origins[:, 2]) / result.directions[:, 2]
    sensor = result.origins + t[:, None] * result.directions
    sensor[~alive] = np.nan
    return result, path, sensor


def ray_fan(system, wavelength_nm, source, n_rays, sensor_z_mm, heights_mm=None) -> RayFan:
    """A meridional fan of ``n_rays`` rays of one wavelength from ``source`` to the sensor plane.

    ``heights_mm``: aim heights on the front vertex plane (default: evenly across the front
    clear aperture; a single ray goes through its centre). ``sensor_z_mm``: axial position of the sensor plane.
    """
    if heights_mm is None:
        radius = system.surfaces[0].semi_aperture_mm
        heights_mm = np.linspace(-radius, radius, int(n_rays)) if n_rays > 1 else np.zeros(1)
    heights_mm = np.asarray(heights_mm, dtype=np.float64)
    aim = np.column_stack([np.zeros_like(heights_mm), heights_mm])
    origins, directions = _source_rays(system, source, aim, sensor_z_mm)
    result, path, sensor = _trace_to_sensor(system, origins, directions, wavelength_nm, sensor_z_mm)
    points = np.concatenate([path, sensor[:, None, :]], axis=1)
    valid = np.isfinite(points).all(axis=2)
    # Vertices are valid up to the first NaN; pad the rest with the last valid vertex.
    count = np.where(valid.all(axis=1), valid.shape[1], np.argmin(valid, axis=1))
    last = points[np.arange(len(points)), np.maximum(count - 1, 0)]
    pad = np.arange(points.shape[1])[None, :] >= count[:, None]
    points = np.where(pad[:, :, None], last[:, None, :], points)
    return RayFan(float(wavelength_nm), points, count, result.fate.copy(), result.surface.copy())


def pupil_range_mm(system, source, wavelength_nm, sensor_z_mm, axis=1, centre_mm=0.0, scan_rays=PUPIL_SCAN_RAYS):
    """``(low, high)`` aim coordinates on the front plane between which rays reach the sensor,
    scanning along ``axis`` (1 = y, meridional; 0 = x, sagittal, at ``y = centre_mm``) across
    the front clear aperture; ``None`` if no ray passes."""
    radius = system.surfaces[0].semi_aperture_mm
    scan = np.linspace(-radius, radius, scan_rays)
    aim = np.zeros((scan_rays, 2))
    aim[:, axis] = scan
    aim[:, 1 - axis] = centre_mm
    origins, directions = _source_rays(system, source, aim, sensor_z_mm)
    result = system.trace(origins, directions, wavelength_nm, toward=TOWARD_FILM)
    passing = scan[result.alive]
    if not len(passing):
        return None
    step = scan[1] - scan[0]
    return float(passing.min() - 0.5 * step), float(passing.max() + 0.5 * step)


def spot_diagram(system, wavelength_nm, source, sensor_z_mm, aim_xy_mm) -> SpotDiagram:
    """Sensor hits of rays aimed at ``aim_xy_mm`` [M, 2] (points on the front plane)."""
    origins, directions = _source_rays(system, source, np.asarray(aim_xy_mm, dtype=np.float64), sensor_z_mm)
    result = system.trace(origins, directions, wavelength_nm, toward=TOWARD_FILM)
    t = (sensor_z_mm - result.origins[:, 2]) / result.directions[:, 2]
    hits = (result.origins + t[:, None] * result.directions)[result.alive, :2]
    if len(hits):
        centroid = hits.mean(axis=0)
        rms = float(np.sqrt(np.mean(np.sum((hits - centroid) ** 2, axis=1))))
    else:
        centroid, rms = np.full(2, np.nan), float("nan")
    return SpotDiagram(float(wavelength_nm), hits, centroid, rms, len(origins))


def pupil_grid_mm(y_range_mm, x_range_mm, grid=SPOT_GRID) -> np.ndarray:
    """Aim points [M, 2] of a square grid inside the ellipse spanning ``y_range_mm`` and
    ``x_range_mm`` (each ``(low, high)``) on the front plane."""
    cy, ry = 0.5 * (y_range_mm[0] + y_range_mm[1]), 0.5 * (y_range_mm[1] - y_range_mm[0])
    cx, rx = 0.5 * (x_range_mm[0] + x_range_mm[1]), 0.5 * (x_range_mm[1] - x_range_mm[0])
    u = np.linspace(-1.0, 1.0, grid)
    gx, gy = np.meshgrid(u, u)
    inside = gx**2 + gy**2 <= 1.0 + 1e-12
    return np.column_stack([cx + gx[inside] * rx, cy + gy[inside] * ry])


def spot_diagrams(system, wavelengths_nm, source, sensor_z_mm, grid=SPOT_GRID) -> tuple[SpotDiagram, ...]:
    """One spot diagram per wavelength, all over the same pupil grid (found at the middle
    wavelength so the grids match and lateral colour shows as offset spots)."""
    wavelengths_nm = [float(w) for w in wavelengths_nm]
    reference = float(np.median(wavelengths_nm))
    y_span = pupil_range_mm(system, source, reference, sensor_z_mm, axis=1)
    x_span = None
    if y_span is not None:
        x_span = pupil_range_mm(system, source, reference, sensor_z_mm, axis=0, centre_mm=0.5 * sum(y_span))
    if x_span is None:
        empty = np.zeros((0, 2))
        return tuple(SpotDiagram(w, empty, np.full(2, np.nan), float("nan"), 0) for w in wavelengths_nm)
    aim = pupil_grid_mm(y_span, x_span, grid=grid)
    return tuple(spot_diagram(system, w, source, sensor_z_mm, aim) for w in wavelengths_nm)


@dataclass(frozen=True)
class LensDiagram:
    """Everything the lens overlay draws, in lens coordinates (mm).

    ``fans``/``spots``: one per wavelength (same order as ``wavelengths_nm``).
    ``sensor_z_mm``: the focused film plane. ``bounds_mm``: ``(z_min, z_max, y_half)`` of
    the drawing (incoming rays' start plane to the sensor; half height).
    """

    name: str
    wavelengths_nm: tuple
    fans: tuple
    spots: tuple
    outlines: object
    source: PointSource
    sensor_z_mm: float
    sensor_half_height_mm: float
    f_number: float
    bounds_mm: tuple


def lens_diagram(
    system,
    wavelengths_nm,
    n_rays=15,
    field_angle_deg=0.0,
    source_distance_mm=np.inf,
    sensor_distance_mm=None,
    focus_distance_mm=np.inf,
    sensor_half_height_mm=12.0,
    spot_grid=SPOT_GRID,
) -> LensDiagram:
    """Fans, spot diagrams and outlines of ``system`` (already stopped to its f-stop).

    Distances from the film like Blender's focus distance: ``source_distance_mm`` (``inf``
    or 0 = at infinity) and ``focus_distance_mm`` (used to place the film when
    ``sensor_distance_mm``, from the rear vertex, is not given). Raises
    ``PrismInputError`` when the source would sit inside the lens.
    """
    from ..errors import PrismInputError
    from .outline import system_outlines

    if sensor_distance_mm is None:
        from .focus import focus

        sensor_distance_mm = focus(system, focus_distance_mm).sensor_distance_mm
    sensor_z = system.rear_z_mm + float(sensor_distance_mm)
    source = PointSource.from_film_distance(system, sensor_distance_mm, source_distance_mm, field_angle_deg)
    z_front, max_radius = front_extent_mm(system)
    if source.z_mm >= z_front:
        raise PrismInputError(
            f"Lens overlay: the source distance {source_distance_mm / 1000.0:g} m puts the source inside "
            f"'{system.name}' (the lens is {sensor_z - z_front:.1f} mm long from film to front): "
            "use a larger source distance, or 0 for infinity."
        )
    wavelengths = tuple(float(w) for w in wavelengths_nm)
    fans = tuple(ray_fan(system, w, source, n_rays, sensor_z) for w in wavelengths)
    spots = spot_diagrams(system, wavelengths, source, sensor_z, grid=spot_grid)
    z_min = z_front - LEAD_IN_FRACTION * max(sensor_z, system.rear_z_mm, 1e-6)
    y_half = 1.1 * max(max_radius, float(sensor_half_height_mm))
    from .paraxial import paraxial_data

    return LensDiagram(
        name=system.name,
        wavelengths_nm=wavelengths,
        fans=fans,
        spots=spots,
        outlines=system_outlines(system),
        source=source,
        sensor_z_mm=sensor_z,
        sensor_half_height_mm=float(sensor_half_height_mm),
        f_number=float(paraxial_data(system).f_number),
        bounds_mm=(z_min, sensor_z, y_half),
    )
