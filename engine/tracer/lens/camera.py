"""``RealLensCamera``: camera rays traced from the film out through every lens element.

Set-up only: this class loads and stops down the lens, focuses it, finds the exit-pupil
bounds, measures the centre irradiance and the wasted samples, and hands the render
kernels ``kernel_tables()``; the ray itself is ``camera_kernel.camera_ray`` (placement,
180-degree film rotation and weights are documented there). ``generate_rays`` is the
batch form for numpy callers. Only the hero wavelength (column 0) is traced: its weight
is multiplied by K and the other columns are 0.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..errors import PrismInputError
from ..spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM
from .exit_pupil import RADIAL_BINS, ExitPupilBounds
from .lens_file import load_lens
from .media import D_LINE_NM
from .system import KERNEL_ARRAY

WASTE_SAMPLES = 20000
# The centre irradiance is integrated over a Fibonacci lattice (F_24 points; F_23 is its
# generator): the passing region of the pupil is close to a square in the concentric map's
# (u, v), so an axis-aligned grid would count its edge rows all in or all out (up to 2 %
# off); the lattice's rows are slanted and it stays within ~0.1 %.
NORMALISATION_POINTS, NORMALISATION_GENERATOR = 46368, 28657


@lru_cache(maxsize=8)
def glass_range_warnings(system) -> list[str]:
    """One message per glass of ``system`` whose data does not cover the wavelengths a render samples
    (360-830 nm): outside its range the kernels use its index at the range's edge."""
    messages = []
    for surface in system.surfaces:
        glass = getattr(surface.medium, "glass", None)
        lo, hi = getattr(glass, "valid_range_nm", (VISIBLE_MIN_NM, VISIBLE_MAX_NM))
        if lo > VISIBLE_MIN_NM or hi < VISIBLE_MAX_NM:
            text = (f"Lens '{system.name}': glass '{surface.medium.label}' is specified for {lo:g}-{hi:g} nm only: "
                    f"wavelengths outside that range use its index at the nearer edge")
            if text not in messages:
                messages.append(text)
    return messages


def _pupil_bounds(system, film_z_mm, film_radius_mm, full):
    return ExitPupilBounds(system, film_z_mm, film_radius_mm, RADIAL_BINS, full=full)


class RealLensCamera:
    """A camera whose rays are traced through a lens prescription (``camera.lens_file``).

    ``camera`` is an ``engine.tracer.scene.Camera`` with ``model == "real_lens"``;
    ``settings.use_pupil_bounds`` chooses exit-pupil sampling (default) or the whole rear
    element. Attributes: ``system`` (the stopped-down ``LensSystem``),
    ``sensor_distance_mm`` (rear vertex to film), ``strategy`` (one line for the render
    stats), ``wasted_fraction`` (share of samples inside the pupil bounds that the lens
    blocks), ``outside_image_circle_fraction`` (share of the frame no light reaches).
    """

    disperses = True

    def __init__(self, camera, settings=None):
        name = camera.name
        width, height = (int(r) for r in camera.resolution)
        if width < 1 or height < 1:
            raise PrismInputError(f"Camera '{name}': resolution must be at least 1 x 1 pixels.")
        if not (camera.film_width_mm > 0 and camera.film_height_mm > 0):
            raise PrismInputError(f"Camera '{name}': sensor size must be positive.")
        if not camera.lens_file:
            raise PrismInputError(
                f"Camera '{name}' uses a real lens but no lens file is chosen: pick a bundled lens or a .lens file."
            )
        if not (camera.fstop > 0 and math.isfinite(camera.fstop)):
            raise PrismInputError(f"Camera '{name}': f-stop must be a positive number (got {camera.fstop}).")
        self.width, self.height = width, height
        self.film_width_mm, self.film_height_mm = float(camera.film_width_mm), float(camera.film_height_mm)
        larger = max(self.film_width_mm, self.film_height_mm)
        self._shift_mm = np.array([camera.shift_x * larger, camera.shift_y * larger])

        self.system = load_lens(camera.lens_file).with_fstop(float(camera.fstop))
        if camera.sensor_distance_mm is None:
            if not camera.focus_distance_m > 0:
                raise PrismInputError(f"Camera '{name}': focus distance must be positive.")
            from .focus import focus

            self.sensor_distance_mm = focus(self.system, camera.focus_distance_m * 1000.0).sensor_distance_mm
        else:
            self.sensor_distance_mm = float(camera.sensor_distance_mm)
            if not self.sensor_distance_mm > 0:
                raise PrismInputError(
                    f"Camera '{name}': sensor distance {self.sensor_distance_mm:g} mm would put the film inside "
                    "the lens; use a positive distance behind the rear element."
                )
        self.film_z_mm = self.system.rear_z_mm + self.sensor_distance_mm
        film_radius = math.hypot(0.5 * self.film_width_mm + abs(self._shift_mm[0]),
                                 0.5 * self.film_height_mm + abs(self._shift_mm[1]))
        self.use_pupil_bounds = bool(getattr(settings, "use_pupil_bounds", True))
        self.pupil = _pupil_bounds(self.system, self.film_z_mm, film_radius, not self.use_pupil_bounds)
        self._tables = self._build_tables(centre_irradiance=1.0)
        centre_irradiance = self._centre_irradiance()
        if not centre_irradiance > 0:
            raise PrismInputError(
                f"Camera '{name}': no light reaches the film centre through lens '{self.system.name}'; "
                "check the lens file and the focus settings."
            )
        self._tables = self._tables._replace(centre_irradiance=centre_irradiance)
        m = np.asarray(camera.camera_to_world, dtype=np.float64)
        self._rotation, self._origin = m[:3, :3], m[:3, 3].copy()
        self.wasted_fraction, self.outside_image_circle_fraction = self._measure_waste(settings)
        how = "exit-pupil bounds" if self.use_pupil_bounds else "whole rear element"
        self.strategy = (
            f"real lens '{self.system.name}' f/{camera.fstop:g}, film {self.sensor_distance_mm:.2f} mm behind the "
            f"rear element, {how}, {100 * self.wasted_fraction:.1f}% samples wasted"
        )
        if self.outside_image_circle_fraction > 0.001:
            self.strategy += f", {100 * self.outside_image_circle_fraction:.0f}% of the frame outside the image circle"
        self.warnings = glass_range_warnings(self.system)

    # ---- rays ---------------------------------------------------------------------------
    def kernel_tables(self):
        """The ``camera_kernel.RealLensTables`` that ``camera_ray`` and ``film_point_mm`` read
        (built once at set-up)."""
        return self._tables

    def _build_tables(self, centre_irradiance):
        from .camera_kernel import RealLensTables

        return RealLensTables(
            lens=self.system.tables, pupil=self.pupil.tables, film_z_mm=float(self.film_z_mm),
            centre_irradiance=float(centre_irradiance), width_px=float(self.width), height_px=float(self.height),
            film_width_mm=self.film_width_mm, film_height_mm=self.film_height_mm,
            shift_x_mm=float(self._shift_mm[0]), shift_y_mm=float(self._shift_mm[1]),
        )

    def film_points_mm(self, pixel_xy):
        """Film positions [N, 2] (lens x, y in mm) of raster positions [N, 2], rotated 180 degrees."""
        from .camera_kernel import film_points_mm

        pixel_xy = np.require(np.reshape(pixel_xy, (-1, 2)), np.float64, KERNEL_ARRAY)
        film_xy = np.empty_like(pixel_xy)
        film_points_mm(self._tables, pixel_xy, film_xy)
        return film_xy

    def camera_space_rays(self, film_xy_mm, lens_uv, wavelength_nm):
        """``camera_ray`` for each film point [N, 2] (lens x, y, mm), lens sample [N, 2] and
        wavelength [N]: (weight [N], origins [N, 3] in metres, unit directions [N, 3]) in camera space."""
        from .camera_kernel import camera_rays

        film_xy_mm = np.require(np.reshape(film_xy_mm, (-1, 2)), np.float64, KERNEL_ARRAY)
        n = len(film_xy_mm)
        lens_uv = np.require(np.reshape(lens_uv, (n, 2)), np.float64, KERNEL_ARRAY)
        wavelength_nm = np.require(np.broadcast_to(wavelength_nm, (n,)), np.float64, KERNEL_ARRAY)
        weight, origins, directions = np.empty(n), np.empty((n, 3)), np.empty((n, 3))
        camera_rays(self._tables, film_xy_mm, lens_uv, wavelength_nm, weight, origins, directions)
        return weight, origins, directions

    def generate_rays(self, pixel_xy, lens_uv, wavelength_nm):
        """World-space rays for raster positions.

        ``pixel_xy`` [N, 2], ``lens_uv`` [N, 2] in [0, 1), ``wavelength_nm`` [N, K]: column 0
        (the hero wavelength) is traced; weight [N, K] has K x the lens weight in column 0.
        """
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        if wavelength_nm.ndim == 1:
            wavelength_nm = wavelength_nm[:, None]
        n, k = wavelength_nm.shape
        lens_weight, origins_cam, directions_cam = self.camera_space_rays(
            self.film_points_mm(pixel_xy), lens_uv, wavelength_nm[:, 0])
        origins = origins_cam @ self._rotation.T + self._origin
        directions = directions_cam @ self._rotation.T
        directions /= np.linalg.norm(directions, axis=1, keepdims=True)
        weight = np.zeros((n, k))
        weight[:, 0] = k * lens_weight
        return origins, directions, weight

    # ---- set-up measurements ------------------------------------------------------------
    def _centre_irradiance(self):
        """Integral of cos^4 / z^2 over the passing part of the pupil seen from the film centre
        (the mean ``camera_ray`` weight at the d line, before normalisation, over a lattice)."""
        n = NORMALISATION_POINTS
        i = np.arange(n)
        uv = np.column_stack([(i + 0.5) / n, ((i * NORMALISATION_GENERATOR) % n + 0.5) / n])
        weight, _, _ = self.camera_space_rays(np.zeros((n, 2)), uv, D_LINE_NM)
        return float(weight.mean())

    def _measure_waste(self, settings):
        """(blocked share of samples drawn inside non-empty pupil boxes, share of the frame with empty boxes)."""
        rng = np.random.default_rng(getattr(settings, "seed", 0) if settings is not None else 0)
        pixel = rng.random((WASTE_SAMPLES, 2)) * (self.width, self.height)
        film = self.film_points_mm(pixel)
        wavelength = rng.uniform(400.0, 700.0, WASTE_SAMPLES)
        has_box = self.pupil.sample(film, np.zeros((WASTE_SAMPLES, 2)))[1] > 0
        if not has_box.any():
            return 1.0, 1.0
        weight, _, _ = self.camera_space_rays(film[has_box], rng.random((int(has_box.sum()), 2)), wavelength[has_box])
        return float(1.0 - (weight > 0).mean()), float(1.0 - has_box.mean())
