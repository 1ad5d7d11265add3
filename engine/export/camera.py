"""The active camera → ``tracer.scene.Camera``: perspective projection plus ``Camera.prism``'s
lens model (Blender perspective = pinhole, thin lens, or a real lens prescription).

Focus distance, focus object and f-stop are Blender's own depth-of-field settings.
"""

from __future__ import annotations

import math

import numpy as np

from ..tracer.errors import PrismInputError
from ..tracer.scene import Camera

LENS_MODELS = {"PINHOLE": "pinhole", "THIN_LENS": "thin_lens", "REAL_LENS": "real_lens"}


def render_resolution(scene) -> tuple[int, int]:
    """Output size in pixels, with the resolution percentage applied (as Blender rounds it)."""
    render = scene.render
    percent = render.resolution_percentage
    return max(1, render.resolution_x * percent // 100), max(1, render.resolution_y * percent // 100)


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


def check_camera_scale(camera_object) -> None:
    """A camera scaled to zero along an axis has lost the direction it looks in: refuse it."""
    axes = np.array(camera_object.matrix_world, dtype=np.float64)[:3, :3]
    if not np.isfinite(axes).all():
        return  # reported with the scene's transforms (Scene.validate)
    lengths = np.linalg.norm(axes, axis=0)
    singular = np.linalg.svd(axes, compute_uv=False)
    if lengths.min() <= 0.0 or singular[-1] <= 1e-9 * singular[0]:
        scale = ", ".join(f"{v:g}" for v in camera_object.matrix_world.to_scale())
        raise PrismInputError(
            f"Camera '{camera_object.name}' is scaled to zero (world scale {scale}), so the direction it looks in "
            "is lost: set its Scale (and its parents') to non-zero values, e.g. 1 (Object ▸ Transform ▸ Scale)."
        )


def check_frame_memory(scene, width: int, height: int) -> None:
    """Refuse at once a frame whose image and passes cannot fit in memory (``engine.passes.frame_plan``)."""
    from ..passes import frame_plan

    frame_plan(scene, None, width, height)


def rigid_matrix(matrix_world) -> np.ndarray:
    """4x4 float64 world matrix with scale (and shear) removed."""
    matrix = np.array(matrix_world, dtype=np.float64)
    rotation = matrix[:3, :3]
    u, _, vt = np.linalg.svd(rotation)
    matrix[:3, :3] = u @ vt
    return matrix


def focus_distance_m(camera_object) -> float:
    """Blender's focus distance: along the view axis to the focus object when one is set."""
    dof = camera_object.data.dof
    target = dof.focus_object
    if target is None:
        return float(dof.focus_distance)
    matrix = np.array(camera_object.matrix_world, dtype=np.float64)
    view_axis = -matrix[:3, 2] / max(np.linalg.norm(matrix[:3, 2]), 1e-300)
    target_position = np.array(target.matrix_world, dtype=np.float64)[:3, 3]
    if dof.focus_subtarget and target.type == "ARMATURE":
        bone = target.pose.bones.get(dof.focus_subtarget)
        if bone is not None:
            target_position = (np.array(target.matrix_world) @ np.append(np.array(bone.head), 1.0))[:3]
    distance = float(np.dot(target_position - matrix[:3, 3], view_axis))
    if not distance > 0:
        raise PrismInputError(
            f"Camera '{camera_object.name}' focuses on '{target.name}', which is behind the camera: "
            "pick a focus object in front of it or clear Focus on Object."
        )
    return distance


def _lens_file(camera_object) -> str:
    from ..tracer.lens.lens_file import load_lens

    settings = camera_object.data.prism
    path = settings.lens_path()
    name = camera_object.name
    if not path:
        where = "Lens File" if settings.lens_source == "FILE" else "Lens"
        raise PrismInputError(
            f"Camera '{name}' uses a real lens but no prescription is chosen: set Camera ▸ Prism Lens ▸ {where}."
        )
    try:
        load_lens(path)  # parse now, so a bad file is reported before tracing starts
    except PrismInputError as error:
        raise PrismInputError(f"Camera '{name}': {error}") from None
    return path


def export_camera(scene, depsgraph=None) -> Camera:
    """The scene's active camera (as ``depsgraph`` evaluated it, when given: a material preview's
    scene is not evaluated itself); a clear error when there is none or it is unsupported."""
    camera_object = scene.camera
    if camera_object is not None and depsgraph is not None:
        camera_object = camera_object.evaluated_get(depsgraph)
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
    check_camera_scale(camera_object)
    width, height = render_resolution(scene)
    check_frame_memory(scene, width, height)
    film_w, film_h = film_size_mm(data, width, height)
    if not (np.isfinite(data.lens) and data.lens > 0):
        raise PrismInputError(f"Camera '{camera_object.name}' has focal length {data.lens} mm: use a positive value.")
    settings = getattr(data, "prism", None)
    model = LENS_MODELS[settings.lens_model] if settings is not None else "pinhole"
    camera = Camera(
        name=camera_object.name,
        camera_to_world=rigid_matrix(camera_object.matrix_world),
        resolution=(width, height),
        focal_length_mm=float(data.lens),
        film_width_mm=float(film_w),
        film_height_mm=float(film_h),
        model=model,
        fstop=float(data.dof.aperture_fstop),
        focus_distance_m=float(data.dof.focus_distance),
        shift_x=float(data.shift_x),
        shift_y=float(data.shift_y),
    )
    if model == "pinhole":
        return camera
    camera.focus_distance_m = focus_distance_m(camera_object)
    if not (math.isfinite(camera.focus_distance_m) and camera.focus_distance_m > 0):
        raise PrismInputError(
            f"Camera '{camera_object.name}' focuses at {camera.focus_distance_m:g} m: set a focus distance above 0 "
            "(Camera ▸ Prism Lens ▸ Focus)."
        )
    if not (math.isfinite(camera.fstop) and camera.fstop > 0):
        raise PrismInputError(f"Camera '{camera_object.name}' has f-stop {camera.fstop:g}: use a positive f-stop.")
    if model == "real_lens":
        camera.lens_file = _lens_file(camera_object)
    return camera
