"""2D drawing of the lens overlay: the spot diagram inset (also drawn in the viewport's
pixel space) and the lens diagram as a PNG, the overlay's cross-section, rays and spot
inset drawn into a ``gpu.types.GPUOffScreen`` and saved through ``bpy.data.images``.

The cross-section is an orthographic view of lens coordinates (z to the right, y up, the
same scale on both axes) on a dark background, with a title line (lens, f-number, focus,
source) and the spot diagram inset on the right. Works in the UI and headless: in
background mode the GPU is first brought up by rendering one tiny Workbench frame.
"""

from __future__ import annotations

import math

import bpy

from ..engine.tracer.errors import PrismInputError
from . import lens_overlay_draw as draw
from .lens_overlay_colours import TEXT_RGBA
from .lens_spot_inset import draw_spot_inset

BACKGROUND_RGBA = (0.06, 0.06, 0.07, 1.0)


class LensDiagramExportError(PrismInputError):
    """The diagram cannot be drawn (no GPU) or written; the message says how to fix it."""


def _gpu_available() -> bool:
    import gpu

    try:
        gpu.types.GPUOffScreen(4, 4).free()
    except SystemError:
        return False
    return True


def ensure_gpu():
    """Make gpu drawing usable; in background mode render one 4x4 Workbench frame in a
    temporary scene first. Raises ``LensDiagramExportError`` if the GPU stays unavailable."""
    if _gpu_available():
        return
    scene = bpy.data.scenes.new("prism_gpu_init")
    camera_data = bpy.data.cameras.new("prism_gpu_init")
    camera = bpy.data.objects.new("prism_gpu_init", camera_data)
    try:
        scene.collection.objects.link(camera)
        scene.camera = camera
        scene.render.engine = "BLENDER_WORKBENCH"
        scene.render.resolution_x = scene.render.resolution_y = 4
        bpy.ops.render.render(scene=scene.name)
    except Exception as error:  # noqa: BLE001 - reported below with the fix
        failure = repr(error)
    else:
        failure = ""
    finally:
        bpy.data.objects.remove(camera)
        bpy.data.cameras.remove(camera_data)
        bpy.data.scenes.remove(scene)
    if not _gpu_available():
        raise LensDiagramExportError(
            "Lens diagram export needs Blender's GPU drawing, which could not be initialised"
            f"{' (' + failure + ')' if failure else ''}. On a headless Linux machine install Mesa EGL "
            "(apt-get install -y libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1), or export from the Blender UI."
        )


def diagram_layout(diagram, width, height):
    """Pixel layout: ``(matrix, inset)`` where ``matrix`` maps lens coordinates (mm) to pixels
    and ``inset`` is ``(x0, y0, size)`` of the spot diagram square (None without spots)."""
    from mathutils import Matrix

    margin = 0.04 * height
    title = 0.08 * height
    inset_size = min(0.45 * height, 0.28 * width) if diagram.spots else 0.0
    area_w = width - 2 * margin - (inset_size + margin if inset_size else 0.0)
    area_h = height - 2 * margin - title
    z_min, z_max, y_half = diagram.bounds_mm
    scale = min(area_w / (z_max - z_min), area_h / (2.0 * y_half))
    cx, cy = margin + 0.5 * area_w, margin + 0.5 * area_h
    zc = 0.5 * (z_min + z_max)
    matrix = Matrix(((0, 0, scale, cx - zc * scale), (0, scale, 0, cy), (0, 0, 0, 0), (0, 0, 0, 1)))
    inset = (width - margin - inset_size, margin + 0.12 * height, inset_size) if inset_size else None
    return matrix, inset


def pixel_projection(width, height):
    """Orthographic projection of pixel coordinates (origin bottom left) to clip space."""
    from mathutils import Matrix

    return Matrix(((2.0 / width, 0, 0, -1), (0, 2.0 / height, 0, -1), (0, 0, -1, 0), (0, 0, 0, 1)))


def _title(diagram, focus_mm, fstop):
    source = diagram.source
    where = "infinity" if source.at_infinity else f"{(diagram.sensor_z_mm - source.z_mm) / 1000.0:.4g} m"
    focus = "infinity" if not math.isfinite(focus_mm) or focus_mm <= 0 else f"{focus_mm / 1000.0:.4g} m"
    return (
        f"{diagram.name}   at f/{fstop if fstop else diagram.f_number:.3g}   focus {focus}   "
        f"source {where}, {source.field_angle_deg:g}°"
    )


def render_diagram_pixels(diagram, width, height, focus_mm=math.inf, fstop=None):
    """Draw ``diagram`` offscreen; returns float32 RGBA pixels [height, width, 4], row 0 at the
    bottom. ``focus_mm`` and ``fstop`` (the camera's; default the paraxial f-number) go in the title."""
    import blf
    import gpu
    import numpy as np
    from mathutils import Matrix

    ensure_gpu()
    matrix, inset = diagram_layout(diagram, width, height)
    offscreen = gpu.types.GPUOffScreen(width, height)
    try:
        with offscreen.bind():
            framebuffer = gpu.state.active_framebuffer_get()
            framebuffer.clear(color=BACKGROUND_RGBA)
            with gpu.matrix.push_pop(), gpu.matrix.push_pop_projection():
                gpu.matrix.load_projection_matrix(pixel_projection(width, height))
                gpu.matrix.load_matrix(matrix)
                line_width = max(1.5, height / 400.0)
                draw.draw_batches(draw.build_batches(diagram), (width, height), line_width)
                gpu.matrix.load_matrix(Matrix.Identity(4))
                font_size = max(10, round(height / 40))
                if inset is not None:
                    draw_spot_inset(diagram, *inset, font_size, point_size=max(2.0, height / 250.0))
                blf.size(0, font_size)
                blf.color(0, *TEXT_RGBA)
                blf.position(0, 0.04 * height, height - 0.06 * height, 0)
                blf.draw(0, _title(diagram, focus_mm, fstop))
            buffer = framebuffer.read_color(0, 0, width, height, 4, 0, "FLOAT")
    finally:
        offscreen.free()
    buffer.dimensions = width * height * 4
    pixels = np.array(buffer, dtype=np.float32).reshape(height, width, 4)
    pixels[..., 3] = 1.0
    return pixels


def save_png(pixels, filepath):
    """Write display-encoded float RGBA pixels [H, W, 4] (row 0 at the bottom) as a PNG."""
    height, width = pixels.shape[:2]
    image = bpy.data.images.new("prism_lens_diagram", width, height, alpha=True)
    try:
        image.pixels.foreach_set(pixels.reshape(-1))
        image.filepath_raw = str(filepath)
        image.file_format = "PNG"
        image.save()
    except RuntimeError as error:
        raise LensDiagramExportError(f"Lens diagram: cannot write '{filepath}' ({error}); check the folder exists.")
    finally:
        bpy.data.images.remove(image)


def write_lens_diagram_png(scene, filepath, width=1200, height=600):
    """Draw the lens overlay of ``scene``'s active camera (cross-section, rays, spot diagram)
    to a PNG at ``filepath``. Raises ``PrismInputError`` (naming the fix) when the scene has no
    real-lens camera, the settings are invalid or the GPU is unavailable."""
    if width < 64 or height < 64:
        raise LensDiagramExportError(f"Lens diagram: {width}x{height} px is too small; use at least 64x64.")
    inputs, message = draw.overlay_inputs(scene)
    if inputs is None:
        raise PrismInputError(message)
    diagram = draw.compute_diagram(inputs)
    pixels = render_diagram_pixels(diagram, int(width), int(height), focus_mm=inputs[3], fstop=inputs[2])
    save_png(pixels, bpy.path.abspath(str(filepath)))
    return diagram
