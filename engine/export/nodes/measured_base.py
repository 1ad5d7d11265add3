"""Material ▸ Prism ▸ Base Colour Spectrum (Measured or File): which node colours the measured reflectance
replaces, and what Prism says where a node keeps its own colour.

The reflectance (a ``scene.ReflectanceSpec``, 0-1 per wavelength) replaces, once, the colour that is the
surface's own reflectance: the Principled BSDF's Base Color (its diffuse and metallic lobes), the Diffuse
BSDF's and Subsurface Scattering's Color, and the Metallic BSDF's Base Color (F82). Colours that are not a
reflectance of the surface body (a Glossy BSDF's specular tint, a glass's transmittance, a translucent or
transparent filter, a metal given by n and k) keep their RGB value, with one warning per node; a material
none of whose nodes takes it gets one warning naming what renders instead.
"""

from __future__ import annotations

#: What the panel and the warnings name as the colours the measured reflectance replaces.
REPLACED_COLOURS = ("Principled BSDF Base Color", "Diffuse BSDF Color", "Subsurface Scattering Color",
                    "Metallic BSDF Base Color (F82)")
PANEL = "Material ▸ Prism ▸ Base Colour Spectrum"


def measured_base(c):
    """The material's measured reflectance (``scene.ReflectanceSpec``) for a node whose colour it replaces,
    or None when the material uses the nodes' RGB colours."""
    return c.overrides.get("reflectance")


def keeps_own_colour(c, node, why: str) -> None:
    """Warn, when the material has a measured reflectance, that ``node`` keeps its RGB colour (``why``)."""
    if measured_base(c) is not None:
        c.warn(node, f"keeps its RGB colour: {why}, which the measured reflectance of {PANEL} does not replace.")


def check_measured_used(c, replaced_by: list[str]) -> None:
    """One warning when the material has a measured reflectance that none of its nodes took."""
    if measured_base(c) is None or replaced_by:
        return
    c.warn(None, f"has a measured reflectance ({PANEL}) but no node whose colour it replaces (it replaces the "
                 f"{', '.join(REPLACED_COLOURS)}); Prism renders the nodes' own colours.")
