"""The active camera → ``tracer.scene.Camera``: Blender's projection (perspective, orthographic,
Cycles' equirectangular and fisheye panoramas), sensor fit and shift, plus ``Camera.prism``'s lens
model: Blender's camera (a pinhole, or a thin lens when its Depth of Field box is checked), always a
thin lens, or a real lens prescription (perspective only).

Focus distance, focus object, f-stop, blades, rotation and ratio are Blender's own depth-of-field
settings.
"""

from __future__ import annotations

import math

import numpy as np

from ..tracer.errors import PrismInputError
from ..tracer.scene import Camera

LENS_MODELS = {"PINHOLE": "pinhole", "THIN_LENS": "thin_lens", "REAL_LENS": "real_lens"}
PANORAMAS = {"EQUIRECTANGULAR": "equirectangular", "FISHEYE_EQUIDISTANT": "fisheye_equidistant",
             "FISHEYE_EQUISOLID": "fisheye_equisolid"}


def render_resolution(scene) -> tuple[int, int]:
    """Output size in pixels, with the resolution percentage applied (as Blender rounds it)."""
    render = scene.render
    percent = render.resolution_percentage
    return max(1, render.resolution_x * percent // 100), max(1, render.resolution_y * percent // 100)


def _fits_horizontally(camera_data, width_px: float, height_px: float) -> bool:
    fit = camera_data.sensor_fit
    return width_px >= height_px if fit == "AUTO" else fit == "HORIZONTAL"


def film_size_mm(camera_data, width_px: float, height_px: float) -> tuple[float, float]:
    """The part of the sensor that maps onto the image, after Blender's sensor fit, for an image
    ``width_px`` x ``height_px`` as displayed (pixel counts times the pixel aspect)."""
    horizontal = _fits_horizontally(camera_data, width_px, height_px)
    if camera_data.sensor_fit == "AUTO":
        sensor = camera_data.sensor_width
    else:
        sensor = camera_data.sensor_width if horizontal else camera_data.sensor_height
    if horizontal:
        return sensor, sensor * height_px / width_px
    return sensor * width_px / height_px, sensor


def ortho_size_m(camera_data, width_px: float, height_px: float) -> tuple[float, float]:
    """The orthographic view's width and height (m): Orthographic Scale along the fitted side."""
    scale = float(camera_data.ortho_scale)
    if _fits_horizontally(camera_data, width_px, height_px):
        return scale, scale * height_px / width_px
    return scale * width_px / height_px, scale


def larger_side_factor(camera_data, width_px: float, height_px: float) -> float:
    """Blender's shift is in units of the fitted side, the tracer's in units of the larger one: this ratio."""
    fitted = width_px if _fits_horizontally(camera_data, width_px, height_px) else height_px
    return fitted / max(width_px, height_px)


def shift_in_larger_side(camera_data, width_px: float, height_px: float) -> tuple[float, float]:
    """The camera's Shift X / Y in the tracer's units (``larger_side_factor``)."""
    factor = larger_side_factor(camera_data, width_px, height_px)
    return float(camera_data.shift_x) * factor, float(camera_data.shift_y) * factor


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
    """Refuse at once a frame whose image and passes cannot fit in memory (``engine.render.result_passes.frame_plan``)."""
    from ..render.result_passes import frame_plan

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


def _projection(camera_object, warnings) -> str:
    data = camera_object.data
    if data.type == "PERSP":
        return "perspective"
    if data.type == "ORTHO":
        return "orthographic"
    if data.type == "PANO":
        kind = data.panorama_type
        if kind not in PANORAMAS:
            label = kind.replace("_", " ").title()
            raise PrismInputError(
                f"Camera '{camera_object.name}': the {label} panorama is not supported; set Camera ▸ Lens ▸ "
                "Panorama Type to Equirectangular, Fisheye Equidistant or Fisheye Equisolid."
            )
        if (data.shift_x or data.shift_y) and warnings is not None:
            warnings.append(f"Camera '{camera_object.name}': Shift is ignored by panoramic cameras (as in Cycles).")
        return PANORAMAS[kind]
    if data.type == "CUSTOM":
        # A Custom camera is an OSL shader that writes the ray itself (Cycles' CPU OSL backend only);
        # Prism runs no OSL, so it says so rather than guess a projection.
        raise PrismInputError(
            f"Camera '{camera_object.name}' is a Custom (OSL script) camera, which Prism cannot run: Prism "
            "renders perspective, orthographic and panoramic (Equirectangular, Fisheye Equidistant, Fisheye "
            "Equisolid) cameras; set Camera ▸ Lens ▸ Type to one of them."
        )
    raise PrismInputError(
        f"Camera '{camera_object.name}' has the camera type '{data.type}', which Prism does not know: set Camera ▸ "
        "Lens ▸ Type to Perspective, Orthographic or Panoramic."
    )


def _lens_model(camera_object, projection) -> str:
    """Blender's camera is a thin lens when its Depth of Field box is checked."""
    settings = getattr(camera_object.data, "prism", None)
    model = LENS_MODELS[settings.lens_model] if settings is not None else "pinhole"
    if model == "pinhole" and camera_object.data.dof.use_dof:
        return "thin_lens"
    if model == "real_lens" and projection != "perspective":
        raise PrismInputError(
            f"Camera '{camera_object.name}' uses a real lens, which forms a perspective image: set Camera ▸ Lens "
            "▸ Type to Perspective, or Prism Lens ▸ Lens Model to Blender's camera."
        )
    return model


def export_camera(scene, depsgraph=None, warnings: list[str] | None = None) -> Camera:
    """The scene's active camera (as ``depsgraph`` evaluated it, when given: a material preview's
    scene is not evaluated itself); a clear error when there is none or it is unsupported. Settings
    Prism ignores are appended to ``warnings``."""
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
    projection = _projection(camera_object, warnings)
    check_camera_scale(camera_object)
    width, height = render_resolution(scene)
    check_frame_memory(scene, width, height)
    # Blender fits the sensor to the image as displayed: non-square pixels (Format ▸ Aspect X/Y) stretch it.
    shape = (width * float(scene.render.pixel_aspect_x), height * float(scene.render.pixel_aspect_y))
    film_w, film_h = film_size_mm(data, *shape)
    if projection == "perspective" and not (np.isfinite(data.lens) and data.lens > 0):
        raise PrismInputError(f"Camera '{camera_object.name}' has focal length {data.lens} mm: use a positive value.")
    model = _lens_model(camera_object, projection)
    shift_x, shift_y = shift_in_larger_side(data, *shape)
    ortho_w, ortho_h = ortho_size_m(data, *shape)
    dof = data.dof
    camera = Camera(
        name=camera_object.name,
        camera_to_world=rigid_matrix(camera_object.matrix_world),
        resolution=(width, height),
        focal_length_mm=float(data.lens),
        film_width_mm=float(film_w),
        film_height_mm=float(film_h),
        model=model,
        fstop=float(dof.aperture_fstop),
        focus_distance_m=float(dof.focus_distance),
        shift_x=shift_x if projection in ("perspective", "orthographic") else 0.0,
        shift_y=shift_y if projection in ("perspective", "orthographic") else 0.0,
        aperture_blades=int(dof.aperture_blades),
        aperture_rotation_rad=float(dof.aperture_rotation),
        aperture_ratio=float(dof.aperture_ratio),
        projection=projection,
        ortho_width_m=ortho_w,
        ortho_height_m=ortho_h,
        fisheye_fov_rad=float(data.fisheye_fov),
        fisheye_lens_mm=float(data.fisheye_lens),
        latitude_min_rad=float(data.latitude_min),
        latitude_max_rad=float(data.latitude_max),
        longitude_min_rad=float(data.longitude_min),
        longitude_max_rad=float(data.longitude_max),
        clip_start_m=float(data.clip_start),
        clip_end_m=float(data.clip_end),
    )
    if camera.clip_start_m > camera.clip_end_m and warnings is not None:
        warnings.append(f"Camera '{camera_object.name}': Clip Start ({camera.clip_start_m:g} m) lies beyond Clip End "
                        f"({camera.clip_end_m:g} m), so the camera sees no geometry, only the world (as in Cycles): "
                        "set Clip Start below Clip End (Camera ▸ Lens).")
    if model == "pinhole":
        return camera
    camera.focus_distance_m = focus_distance_m(camera_object)
    if not (math.isfinite(camera.focus_distance_m) and camera.focus_distance_m > 0):
        raise PrismInputError(
            f"Camera '{camera_object.name}' focuses at {camera.focus_distance_m:g} m: set a focus distance above 0 "
            "(Camera ▸ Depth of Field ▸ Focus Distance)."
        )
    if not (math.isfinite(camera.fstop) and camera.fstop > 0):
        raise PrismInputError(f"Camera '{camera_object.name}' has f-stop {camera.fstop:g}: use a positive f-stop.")
    if model == "real_lens":
        camera.lens_file = _lens_file(camera_object)
    return camera
