"""``Scene.prism.lens_overlay``: what the viewport lens overlay draws (nested in ``scene.py``'s group)."""

import re

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ..tracer.errors import PrismInputError
from ..tracer.spectra.wavelengths import VISIBLE_RANGE_NM
from ._common import tag_3d_views_for_redraw


def parse_wavelengths_nm(text: str) -> tuple[float, ...]:
    """Parse a list such as ``"450, 550, 650"`` (nm, commas or spaces) into floats.

    Raises ``PrismInputError`` for an empty list, a word that is not a number or a
    wavelength outside 360-830 nm.
    """
    words = [w for w in re.split(r"[,;\s]+", text.strip()) if w]
    if not words:
        raise PrismInputError("Lens overlay: enter at least one wavelength in nm, e.g. \"450, 550, 650\".")
    values = []
    for word in words:
        try:
            value = float(word.removesuffix("nm"))
        except ValueError:
            raise PrismInputError(
                f"Lens overlay: '{word}' is not a wavelength; enter numbers in nm separated by commas."
            ) from None
        low, high = VISIBLE_RANGE_NM
        if not low <= value <= high:
            raise PrismInputError(
                f"Lens overlay: {value:g} nm is outside the visible range {low:g}-{high:g} nm."
            )
        values.append(value)
    return tuple(values)


def _redraw(self, context):
    tag_3d_views_for_redraw(context)


def _custom_wavelengths_error(self) -> str:
    try:
        parse_wavelengths_nm(self.custom_wavelengths_nm)
    except PrismInputError as error:
        return str(error)
    return ""


class PrismLensOverlaySettings(bpy.types.PropertyGroup):
    """Lens overlay: ray fans through the active camera's real lens, drawn in the viewport."""

    enabled: BoolProperty(
        name="Lens Overlay",
        description="Draw ray fans through the active camera's real lens in the 3D viewport",
        default=False,
        update=_redraw,
    )
    wavelength_source: EnumProperty(
        name="Wavelengths",
        description="Which wavelengths the ray fans are traced at",
        items=[
            ("CHANNELS", "Render Channels", "The means of the render's R, G and B wavelength Gaussians", 0),
            ("CUSTOM", "Custom", "A list of wavelengths typed in nm", 1),
        ],
        default="CHANNELS",
        update=_redraw,
    )
    custom_wavelengths_nm: StringProperty(
        name="Custom Wavelengths",
        description="Wavelengths in nm (360-830), separated by commas, e.g. \"450, 550, 650\"",
        default="450, 550, 650",
        update=_redraw,
    )
    custom_wavelengths_error: StringProperty(
        name="Wavelength Error",
        description="Why the custom wavelength list cannot be used (empty when it is valid)",
        get=_custom_wavelengths_error,
    )
    rays_per_fan: IntProperty(
        name="Rays per Fan",
        description="Number of rays traced across the aperture in each fan",
        default=9,
        min=1,
        max=99,
        update=_redraw,
    )
    field_angle_deg: FloatProperty(
        name="Field Angle",
        description="Angle in degrees between the incoming rays and the lens axis (0 = on axis)",
        default=0.0,
        min=-89.0,
        max=89.0,
        update=_redraw,
    )
    source_distance_m: FloatProperty(
        name="Source Distance",
        description="Distance in metres of the point the rays come from (0 = infinitely far: parallel rays)",
        default=0.0,
        min=0.0,
        soft_max=100.0,
        subtype="DISTANCE",
        unit="LENGTH",
        update=_redraw,
    )
    show_outlines: BoolProperty(
        name="Element Outlines",
        description="Draw the outlines of the lens elements and the aperture stop",
        default=True,
        update=_redraw,
    )
    show_sensor: BoolProperty(
        name="Sensor",
        description="Draw the sensor plane",
        default=True,
        update=_redraw,
    )
    show_spot_diagram: BoolProperty(
        name="Spot Diagram",
        description="Draw where each wavelength's rays land on the sensor",
        default=True,
        update=_redraw,
    )

    def wavelengths_nm(self, scene_settings) -> tuple[float, ...]:
        """The wavelengths (nm) to trace: the channel means of ``scene_settings`` (``Scene.prism``)
        or the custom list. Raises ``PrismInputError`` if the custom list is invalid."""
        if self.wavelength_source == "CHANNELS":
            return (scene_settings.mean_r_nm, scene_settings.mean_g_nm, scene_settings.mean_b_nm)
        return parse_wavelengths_nm(self.custom_wavelengths_nm)


def register():
    bpy.utils.register_class(PrismLensOverlaySettings)


def unregister():
    bpy.utils.unregister_class(PrismLensOverlaySettings)
