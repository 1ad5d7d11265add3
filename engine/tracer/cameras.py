"""Camera models with Blender's conventions, and the factory the renderer uses.

A camera looks down its local -Z with +Y up; ``film_width_mm`` x
``film_height_mm`` at ``focal_length_mm`` defines the frustum; Blender's lens
shift moves the film window by ``shift_x``/``shift_y`` times the larger film
dimension. All models implement ``generate_rays(pixel_xy, lens_uv,
wavelength_nm) -> (origins [N,3] m, directions [N,3] unit, weight [N,K])`` in
world space; ``pixel_xy`` are continuous raster coordinates (x right, y down from
the top-left corner, pixels).
"""

from __future__ import annotations

import numpy as np

from .errors import PrismInputError
from .sampling import concentric_disk, norm, transform_rows


class PinholeCamera:
    """Ideal pinhole: every ray leaves the camera's origin; weight 1 (no vignetting)."""

    disperses = False

    def __init__(self, camera):
        width, height = (int(r) for r in camera.resolution)
        if width < 1 or height < 1:
            raise PrismInputError(f"Camera '{camera.name}': resolution must be at least 1 x 1 pixels.")
        if not camera.focal_length_mm > 0:
            raise PrismInputError(f"Camera '{camera.name}': focal length must be positive.")
        if not (camera.film_width_mm > 0 and camera.film_height_mm > 0):
            raise PrismInputError(f"Camera '{camera.name}': sensor size must be positive.")
        self.width, self.height = width, height
        m = np.asarray(camera.camera_to_world, dtype=np.float64)
        self._rotation = m[:3, :3]
        self._origin = m[:3, 3].copy()
        f = float(camera.focal_length_mm)
        self._tan_w = camera.film_width_mm / f
        self._tan_h = camera.film_height_mm / f
        larger = max(camera.film_width_mm, camera.film_height_mm) / f
        self._shift = np.array([camera.shift_x * larger, camera.shift_y * larger])

    def camera_directions(self, pixel_xy: np.ndarray) -> np.ndarray:
        """Camera-space directions [N,3] (not unit) with z = -1 through the film."""
        x = (pixel_xy[:, 0] / self.width - 0.5) * self._tan_w + self._shift[0]
        y = (0.5 - pixel_xy[:, 1] / self.height) * self._tan_h + self._shift[1]
        return np.column_stack([x, y, -np.ones_like(x)])

    def _to_world(self, origins_cam, directions_cam):
        d = transform_rows(directions_cam, self._rotation)
        d /= norm(d)[:, None]
        o = transform_rows(origins_cam, self._rotation) + self._origin
        return o, d

    def generate_rays(self, pixel_xy, lens_uv, wavelength_nm):
        d = self.camera_directions(np.asarray(pixel_xy, dtype=np.float64))
        o, d = self._to_world(np.zeros_like(d), d)
        return o, d, np.ones(np.shape(wavelength_nm))


class ThinLensCamera(PinholeCamera):
    """Thin lens: aperture radius focal_length / (2 fstop), sharp at ``focus_distance_m``
    (measured along the view axis); weight 1."""

    def __init__(self, camera):
        super().__init__(camera)
        if not camera.fstop > 0:
            raise PrismInputError(f"Camera '{camera.name}': f-stop must be positive.")
        if not camera.focus_distance_m > 0:
            raise PrismInputError(f"Camera '{camera.name}': focus distance must be positive.")
        self.aperture_radius_m = camera.focal_length_mm / (2.0 * camera.fstop) / 1000.0
        self.focus_distance_m = float(camera.focus_distance_m)

    def generate_rays(self, pixel_xy, lens_uv, wavelength_nm):
        d = self.camera_directions(np.asarray(pixel_xy, dtype=np.float64))
        focus = d * self.focus_distance_m  # z = -focus distance
        lens = concentric_disk(np.asarray(lens_uv, dtype=np.float64)) * self.aperture_radius_m
        origins = np.column_stack([lens, np.zeros(len(lens))])
        o, d = self._to_world(origins, focus - origins)
        return o, d, np.ones(np.shape(wavelength_nm))


def make_camera(camera, settings):
    """The camera model for ``camera.model``: "pinhole", "thin_lens" or "real_lens"."""
    if camera.model == "pinhole":
        return PinholeCamera(camera)
    if camera.model == "thin_lens":
        return ThinLensCamera(camera)
    if camera.model == "real_lens":
        from .lens.camera import RealLensCamera

        cam = RealLensCamera(camera, settings)
        if not hasattr(cam, "disperses"):
            cam.disperses = True
        return cam
    raise PrismInputError(
        f"Camera '{camera.name}': unknown camera model '{camera.model}'; use pinhole, thin_lens or real_lens."
    )
