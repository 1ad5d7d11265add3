"""The active camera → ``tracer.scene.Camera`` (perspective projection)."""

import numpy as np

from ..tracer.errors import PrismInputError
from ..tracer.scene import Camera


def render_resolution(scene) -> tuple[int, int]:
    """Output size in pixels, with the resolution percentage applied."""
    render = scene.render
    scale = render.resolution_percentage / 100.0
    return max(1, int(render.resolution_x * scale)), max(1, int(render.resolution_y * scale))


def film_size_mm(camera_data, width_px: int, height_px: int) -> tuple[float, float]:
    """The part of the sensor that maps onto the image, after Blender's sensor fit.

    Pixel aspect is taken as square.
    """
    fit = camera_data.sensor_fit
    if fit == "AUTO":
        horizontal = width_px >= height_px
        sensor = camera_data.sensor_width
    else:
        horizontal = fit == "HORIZONTAL"
        sensor = camera_data.sensor_width if horizontal else camera_data.sensor_height
    if horizontal:
        return sensor, sensor * height_px / width_px
    return sensor * width_px / height_px, sensor


def rigid_matrix(matrix_world) -> np.ndarray:
    """4x4 float64 world matrix with scale (and shear) removed."""
    matrix = np.array(matrix_world, dtype=np.float64)
    rotation = matrix[:3, :3]
    u, _, vt = np.linalg.svd(rotation)
    matrix[:3, :3] = u @ vt
    return matrix


def export_camera(scene) -> Camera:
    """The scene's active camera; a clear error when there is none or it is unsupported."""
    camera_object = scene.camera
    if camera_object is None:
        raise PrismInputError(
            f"Scene '{scene.name}' has no active camera: add a camera and make it active "
            "(select it, View ▸ Cameras ▸ Set Active Object as Camera)."
        )
    if camera_object.type != "CAMERA":
        raise PrismInputError(
            f"The active camera '{camera_object.name}' is not a camera object: set a camera as the scene camera."
        )
    data = camera_object.data
    if data.type != "PERSP":
        kind = {"ORTHO": "orthographic", "PANO": "panoramic"}.get(data.type, data.type.lower())
        raise PrismInputError(
            f"Camera '{camera_object.name}' is {kind}; Prism renders perspective cameras only: "
            "set Camera ▸ Lens ▸ Type to Perspective."
        )
    width, height = render_resolution(scene)
    film_w, film_h = film_size_mm(data, width, height)
    if not (np.isfinite(data.lens) and data.lens > 0):
        raise PrismInputError(f"Camera '{camera_object.name}' has focal length {data.lens} mm: use a positive value.")
    return Camera(
        name=camera_object.name,
        camera_to_world=rigid_matrix(camera_object.matrix_world),
        resolution=(width, height),
        focal_length_mm=float(data.lens),
        film_width_mm=float(film_w),
        film_height_mm=float(film_h),
        model="pinhole",
        fstop=float(data.dof.aperture_fstop),
        focus_distance_m=float(data.dof.focus_distance),
        shift_x=float(data.shift_x),
        shift_y=float(data.shift_y),
    )
