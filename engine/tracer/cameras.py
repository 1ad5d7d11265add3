"""The camera of a render, validated and turned into what the camera stage needs.

``make_camera(camera, settings)`` returns a ``CameraSetup``: ``data`` (``stages.camera.CameraData``: the
pinhole or thin lens, and for every camera the pixel filter and orientation), ``lens`` and
``lens_tables`` (the ``lens.camera.RealLensCamera`` of a real lens and its kernel tables, else None),
``disperses`` (a real lens refracts per wavelength: paths keep only their hero), ``strategy`` (for the
render stats), ``position`` (the camera's world position, m) and ``origin`` (world metres: the origin of
the render's space, which every position the kernels see is relative to; the camera position unless the
caller keeps another one, as the viewport does while the view moves).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import PrismInputError
from .stages.camera import PINHOLE, PROJECTIONS, THIN_LENS, CameraData, camera_data


@dataclass
class CameraSetup:
    data: CameraData
    lens: object = None
    lens_tables: object = None
    disperses: bool = False
    strategy: str = ""
    position: np.ndarray = None
    origin: np.ndarray = None


def _check_common(camera):
    width, height = (int(r) for r in camera.resolution)
    if width < 1 or height < 1:
        raise PrismInputError(f"Camera '{camera.name}': resolution must be at least 1 x 1 pixels.")
    if camera.projection != "orthographic" and not (camera.film_width_mm > 0 and camera.film_height_mm > 0):
        raise PrismInputError(f"Camera '{camera.name}': sensor size must be positive.")


def _check_projection(camera):
    name = camera.name
    if camera.projection not in PROJECTIONS:
        raise PrismInputError(
            f"Camera '{name}': unknown projection '{camera.projection}'; use one of {', '.join(PROJECTIONS)}."
        )
    if camera.projection == "orthographic":
        if not (camera.ortho_width_m > 0 and camera.ortho_height_m > 0 and math.isfinite(camera.ortho_width_m)
                and math.isfinite(camera.ortho_height_m)):
            raise PrismInputError(f"Camera '{name}': the orthographic scale must be positive (Camera ▸ Lens ▸ Scale).")
        return
    if camera.projection == "perspective" or camera.projection == "fisheye_equisolid":
        lens = camera.focal_length_mm if camera.projection == "perspective" else camera.fisheye_lens_mm
        if not (lens > 0 and math.isfinite(lens)):
            raise PrismInputError(f"Camera '{name}': focal length must be positive.")
    if camera.projection.startswith("fisheye") and not (camera.fisheye_fov_rad > 0
                                                        and math.isfinite(camera.fisheye_fov_rad)):
        raise PrismInputError(f"Camera '{name}': the fisheye field of view must be positive (Camera ▸ Lens ▸ Field of View).")
    if camera.projection == "equirectangular":
        ranges = (camera.longitude_min_rad, camera.longitude_max_rad, camera.latitude_min_rad, camera.latitude_max_rad)
        if not all(math.isfinite(v) for v in ranges):
            raise PrismInputError(f"Camera '{name}': the panorama's latitude and longitude limits must be finite.")


def make_camera(camera, settings, origin=None) -> CameraSetup:
    """The camera for ``camera.model``: "pinhole", "thin_lens" or "real_lens", in a render space whose
    origin is ``origin`` (world, m; default: the camera's position)."""
    _check_common(camera)
    _check_projection(camera)
    position = np.asarray(camera.camera_to_world, dtype=np.float64)[:3, 3].copy()
    origin = position.copy() if origin is None else np.asarray(origin, dtype=np.float64).copy()
    relative = position - origin
    if camera.model in ("pinhole", "thin_lens"):
        if camera.model == "thin_lens":
            if not (camera.fstop > 0 and math.isfinite(camera.fstop)):
                raise PrismInputError(f"Camera '{camera.name}': f-stop must be positive.")
            if not camera.focus_distance_m > 0:
                raise PrismInputError(f"Camera '{camera.name}': focus distance must be positive.")
            if not (camera.aperture_ratio > 0 and math.isfinite(camera.aperture_ratio)):
                raise PrismInputError(f"Camera '{camera.name}': the aperture ratio must be positive (Depth of Field ▸ Ratio).")
        kind = THIN_LENS if camera.model == "thin_lens" else PINHOLE
        strategy = "" if camera.projection == "perspective" else camera.projection.replace("_", " ") + " camera"
        return CameraSetup(camera_data(camera, settings, kind, relative), position=position, origin=origin,
                           strategy=strategy)
    if camera.model == "real_lens":
        from .lens.camera import RealLensCamera

        if camera.projection != "perspective":
            raise PrismInputError(
                f"Camera '{camera.name}': a real lens forms a perspective image; set Camera ▸ Lens ▸ Type to "
                "Perspective, or choose Blender's camera (Prism Lens ▸ Lens Model)."
            )
        lens = RealLensCamera(camera, settings)
        return CameraSetup(camera_data(camera, settings, PINHOLE, relative), lens=lens,
                           lens_tables=lens.kernel_tables(), disperses=True, strategy=lens.strategy,
                           position=position, origin=origin)
    raise PrismInputError(
        f"Camera '{camera.name}': unknown camera model '{camera.model}'; use pinhole, thin_lens or real_lens."
    )
