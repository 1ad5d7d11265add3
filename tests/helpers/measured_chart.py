"""A bpy scene of measured colour-checker patches lit by a sun of a standard illuminant, and the colours
colour-science computes for them (not a test module).

Each patch is a plane facing +Z whose material sets Material ▸ Prism ▸ Base Colour Spectrum = Measured,
on a Principled BSDF (Specular IOR Level 0: a Lambertian surface) or a Diffuse BSDF node, both given a
wrong RGB colour that the measured reflectance must replace. The sun shines straight down with
irradiance E = π W/m² and angle 0 (a delta light), so a patch of reflectance ρ(λ) has radiance
ρ(λ) E S(λ) / π = ρ(λ) S(λ), where S is the illuminant normalised to luminance Y = 1 (Prism's emission
spectra convention). An orthographic camera looks straight down; the world is black. Its image in
scene-linear Rec.709 is then M · XYZ with XYZ = colour-science's ``sd_to_XYZ(ρ, illuminant=S) / 100``
and M the BT.709 matrix (D65 white, no chromatic adaptation), as Prism's film writes.
"""

from __future__ import annotations

import math
import os

import bpy
import numpy as np

from .node_scenes import black_world, material, node, plane

CHECKER = "ColorChecker N Ohta"
COLUMNS = 6
PATCH_PX = 12  # pixels across one patch
MARGIN_PX = 3  # pixels left out at each edge of a patch when averaging
WRONG_RGB = (0.9, 0.1, 0.5)  # the nodes' own colour, which the measured reflectance replaces

_MATERIAL_KINDS = ("principled", "diffuse")


def patch_names(checker: str = CHECKER) -> list[str]:
    """The panel's names of ``checker``'s patches (``"<checker>: <patch>"``), in chart order."""
    from engine.tracer.spectra.cie import import_colour

    return [f"{checker}: {patch}" for patch in import_colour().SDS_COLOURCHECKERS[checker]]


def measured_material(name: str, patch: str, kind: str):
    """A material of ``kind`` (``"principled"`` or ``"diffuse"``) whose base colour is ``patch``: a colour-checker
    patch's name, or the path of a reflectance file (Base Colour Spectrum = Reflectance File)."""
    mat, nodes, link = material(name)
    if kind == "principled":
        shader = node(nodes, "ShaderNodeBsdfPrincipled", Base_Color=WRONG_RGB, Roughness=1.0,
                      Specular_IOR_Level=0.0)
    elif kind == "diffuse":
        shader = node(nodes, "ShaderNodeBsdfDiffuse", Color=WRONG_RGB, Roughness=0.0)
    else:
        raise ValueError(f"unknown material kind {kind!r}; use one of {_MATERIAL_KINDS}")
    link(shader.outputs[0], nodes["Output"].inputs["Surface"])
    if os.path.isfile(patch):
        mat.prism.reflectance_source, mat.prism.reflectance_file = "FILE", patch
    else:
        mat.prism.reflectance_source, mat.prism.measured_reflectance = "MEASURED", patch
    return mat


def illuminant_sun(illuminant: str, irradiance_w_m2: float = math.pi):
    """A sun of angle 0 shining straight down (−Z) with the spectrum of standard ``illuminant``."""
    data = bpy.data.lights.new(f"Sun {illuminant}", "SUN")
    data.energy, data.angle = irradiance_w_m2, 0.0
    data.prism.color_source, data.prism.illuminant = "ILLUMINANT", illuminant
    sun = bpy.data.objects.new(data.name, data)
    bpy.context.scene.collection.objects.link(sun)
    return sun


def build_measured_chart(scene, illuminant: str, patches: list[str], kinds=_MATERIAL_KINDS):
    """One 1 m plane per (kind, patch), ``COLUMNS`` to a row, a block of rows per kind; returns
    [(kind, patch, (row slice, column slice) of its inner pixels, row 0 on top)]."""
    rows_per_kind = -(-len(patches) // COLUMNS)
    rows = rows_per_kind * len(kinds)
    black_world()
    illuminant_sun(illuminant)
    windows = []
    for k, kind in enumerate(kinds):
        for i, patch in enumerate(patches):
            row, column = k * rows_per_kind + i // COLUMNS, i % COLUMNS
            location = (column + 0.5 - COLUMNS / 2, rows / 2 - row - 0.5, 0.0)
            plane(f"{kind} {i}", 1.0, location, mat=measured_material(f"{kind}: {patch}", patch, kind))
            inner = slice(MARGIN_PX, PATCH_PX - MARGIN_PX)
            windows.append((kind, patch, (slice(row * PATCH_PX + inner.start, row * PATCH_PX + inner.stop),
                                          slice(column * PATCH_PX + inner.start, column * PATCH_PX + inner.stop))))
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.type, camera.data.ortho_scale = "ORTHO", float(max(COLUMNS, rows))
    camera.data.sensor_fit = "AUTO"
    camera.location = (0.0, 0.0, 2.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.resolution_x, scene.render.resolution_y = COLUMNS * PATCH_PX, rows * PATCH_PX
    scene.render.resolution_percentage = 100
    return windows


def window_means(image, windows) -> np.ndarray:
    """Mean scene-linear RGB [N, 3] of each window's pixels."""
    return np.array([image[r, c].reshape(-1, 3).mean(axis=0) for _, _, (r, c) in windows], dtype=np.float64)


def reference_xyz(patches: list[str], illuminant: str):
    """(XYZ [N, 3] of each patch under ``illuminant``, XYZ of the perfect white) as colour-science computes
    them, scaled so that the white has Y = 1 (Prism's luminance-normalised light at E = π W/m²)."""
    from engine.tracer.spectra.cie import import_colour

    colour = import_colour()
    light = colour.SDS_ILLUMINANTS[illuminant]
    checkers = colour.SDS_COLOURCHECKERS
    xyz = np.array([colour.sd_to_XYZ(checkers[name.split(": ")[0]][name.split(": ")[1]], illuminant=light)
                    for name in patches]) / 100.0
    return xyz, colour.sd_to_XYZ(light) / 100.0


def rec709_to_xyz(rgb) -> np.ndarray:
    """Scene-linear Rec.709 → XYZ with the BT.709 matrix (D65 white, no adaptation), Prism's film's inverse."""
    from engine.tracer.spectra.cie import import_colour

    matrix = np.array(import_colour().RGB_COLOURSPACES["ITU-R BT.709"].matrix_XYZ_to_RGB, dtype=np.float64)
    return np.asarray(rgb, dtype=np.float64) @ np.linalg.inv(matrix).T


def delta_e_2000(rendered_xyz, expected_xyz, white_xyz) -> np.ndarray:
    """CIEDE2000 between two XYZ sets, both in CIELAB relative to ``white_xyz`` (the illuminant's white)."""
    from engine.tracer.spectra.cie import import_colour

    colour = import_colour()
    white = colour.XYZ_to_xy(white_xyz)
    return colour.delta_E(colour.XYZ_to_Lab(rendered_xyz, white), colour.XYZ_to_Lab(expected_xyz, white),
                          method="CIE 2000")
