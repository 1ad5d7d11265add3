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
from .stages.camera import PINHOLE, THIN_LENS, CameraData, camera_data


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
    if not (camera.film_width_mm > 0 and camera.film_height_mm > 0):
        raise PrismInputError(f"Camera '{camera.name}': sensor size must be positive.")


def make_camera(camera, settings, origin=None) -> CameraSetup:
    """The camera for ``camera.model``: "pinhole", "thin_lens" or "real_lens", in a render space whose
    origin is ``origin`` (world, m; default: the camera's position)."""
    _check_common(camera)
    position = np.asarray(camera.camera_to_world, dtype=np.float64)[:3, 3].copy()
    origin = position.copy() if origin is None else np.asarray(origin, dtype=np.float64).copy()
    relative = position - origin
    if camera.model in ("pinhole", "thin_lens"):
        if not camera.focal_length_mm > 0:
            raise PrismInputError(f"Camera '{camera.name}': focal length must be positive.")
        if camera.model == "thin_lens":
            if not (camera.fstop > 0 and math.isfinite(camera.fstop)):
                raise PrismInputError(f"Camera '{camera.name}': f-stop must be positive.")
            if not camera.focus_distance_m > 0:
                raise PrismInputError(f"Camera '{camera.name}': focus distance must be positive.")
        kind = THIN_LENS if camera.model == "thin_lens" else PINHOLE
        return CameraSetup(camera_data(camera, settings, kind, relative), position=position, origin=origin)
    if camera.model == "real_lens":
        from .lens.camera import RealLensCamera

        lens = RealLensCamera(camera, settings)
        return CameraSetup(camera_data(camera, settings, PINHOLE, relative), lens=lens,
                           lens_tables=lens.kernel_tables(), disperses=True, strategy=lens.strategy,
                           position=position, origin=origin)
    raise PrismInputError(
        f"Camera '{camera.name}': unknown camera model '{camera.model}'; use pinhole, thin_lens or real_lens."
    )
