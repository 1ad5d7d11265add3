"""Converter and colour nodes: Math, Vector Math, Mix, Map Range, Clamp, Color Ramp, curves, Hue/Saturation/
Value, Invert, Bright/Contrast, Gamma, RGB to BW, Separate/Combine, Blackbody, Mapping, Vector Rotate.

Each handler returns {output identifier: (Value, kind)} (see ``compiler``); tables (ramps, curves,
blackbody colours) are sampled here once, at 256 entries as Cycles samples them, into constants.
"""

from __future__ import annotations

import math

import numpy as np

from ...tracer.materials import opcodes as op
from .terms import COLOR, FLOAT, VECTOR

TABLE_SIZE = 256


def _v(c, node, name, context, variant, kind):
    return c.value(node, name, context, kind, variant)


def math_node(c, node, context, variant, identifier):
    a = _v(c, node, 0, context, variant, FLOAT)
    b = _v(c, node, 1, context, variant, FLOAT)
    d = _v(c, node, 2, context, variant, FLOAT)
    out = c.emit(op.MATH, [a, b, d], mode=op.MATH_OPERATIONS.index(node.operation))
    if node.use_clamp:
        out = c.clamp01(out)
    return {"Value": (out, FLOAT)}


def vector_math_node(c, node, context, variant, identifier):
    operation = node.operation
    a = _v(c, node, 0, context, variant, VECTOR)
    b = _v(c, node, 1, context, variant, VECTOR)
    third = _v(c, node, 2, context, variant, VECTOR)
    scale = _v(c, node, 3, context, variant, FLOAT) if operation in ("SCALE", "REFRACT") else None
    out = c.vector_math(operation, a, b, third, scale)
    if operation in op.VECTOR_MATH_SCALAR:
        return {"Value": (out, FLOAT), "Vector": (c.const(0.0, 0.0, 0.0), VECTOR)}
    return {"Vector": (out, VECTOR), "Value": (c.const(0.0), FLOAT)}


def mix_node(c, node, context, variant, identifier):
    kind = node.data_type
    if kind == "FLOAT":
        fac = _v(c, node, "Factor_Float", context, variant, FLOAT)
        out = c.emit(op.MIX_FLOAT, [fac, _v(c, node, "A_Float", context, variant, FLOAT),
                                    _v(c, node, "B_Float", context, variant, FLOAT)], mode=int(node.clamp_factor))
        return {"Result_Float": (out, FLOAT)}
    if kind == "VECTOR":
        uniform = node.factor_mode == "UNIFORM"
        fac = _v(c, node, "Factor_Float" if uniform else "Factor_Vector", context, variant, FLOAT if uniform else VECTOR)
        out = c.emit(op.MIX_VECTOR, [fac, _v(c, node, "A_Vector", context, variant, VECTOR),
                                     _v(c, node, "B_Vector", context, variant, VECTOR), None, int(node.clamp_factor)],
                     mode=0 if uniform else 1, width=3)
        return {"Result_Vector": (out, VECTOR)}
    if kind == "RGBA":
        fac = _v(c, node, "Factor_Float", context, variant, FLOAT)
        out = c.emit(op.MIX_COLOR, [fac, _v(c, node, "A_Color", context, variant, COLOR),
                                    _v(c, node, "B_Color", context, variant, COLOR), int(node.clamp_factor),
                                    int(node.clamp_result)], mode=op.BLEND_MODES.index(node.blend_type), width=3)
        return {"Result_Color": (out, COLOR)}
    c.warn(node, "mixes rotations, which Prism does not support; it takes A.")
    return {}


def mix_rgb_node(c, node, context, variant, identifier):
    fac = _v(c, node, "Fac", context, variant, FLOAT)
    out = c.emit(op.MIX_COLOR, [fac, _v(c, node, "Color1", context, variant, COLOR),
                                _v(c, node, "Color2", context, variant, COLOR), 1, int(node.use_clamp)],
                 mode=op.BLEND_MODES.index(node.blend_type), width=3)
    return {"Color": (out, COLOR)}


def map_range_node(c, node, context, variant, identifier):
    mode = op.MAP_RANGE_MODES.index(node.interpolation_type)
    clamp = int(node.clamp)
    if node.data_type == "FLOAT":
        args = [_v(c, node, name, context, variant, FLOAT)
                for name in ("Value", "From Min", "From Max", "To Min", "To Max", "Steps")]
        return {"Result": (c.emit(op.MAP_RANGE, args + [clamp], mode=mode), FLOAT)}
    vectors = [_v(c, node, name, context, variant, VECTOR)
               for name in ("Vector", "From_Min_FLOAT3", "From_Max_FLOAT3", "To_Min_FLOAT3", "To_Max_FLOAT3",
                            "Steps_FLOAT3")]
    if mode >= 2:
        clamp = 0
    parts = [c.emit(op.MAP_RANGE, [v.component(k) for v in vectors] + [clamp], mode=mode) for k in range(3)]
    return {"Vector": (c.emit(op.COMBINE_XYZ, parts, width=3), VECTOR)}


def clamp_node(c, node, context, variant, identifier):
    args = [_v(c, node, name, context, variant, FLOAT) for name in ("Value", "Min", "Max")]
    return {"Result": (c.emit(op.CLAMP, args, mode=0 if node.clamp_type == "MINMAX" else 1), FLOAT)}


def _table(c, rows):
    """Constant registers holding ``rows`` (a float array [size, stride]), row after row."""
    flat = np.asarray(rows, dtype=np.float64).reshape(-1)
    return c.const(*flat.tolist())


def color_ramp_node(c, node, context, variant, identifier):
    ramp = node.color_ramp
    samples = [tuple(ramp.evaluate(i / (TABLE_SIZE - 1))) for i in range(TABLE_SIZE)]
    table = _table(c, samples)
    fac = _v(c, node, "Fac", context, variant, FLOAT)
    mode = 1 if ramp.interpolation == "CONSTANT" else 0
    out = c.emit(op.COLOR_RAMP, [fac, table, TABLE_SIZE], mode=mode, width=4, reads=[table])
    return {"Color": (out.__class__(out.register, 3), COLOR), "Alpha": (out.component(3), FLOAT)}


def _curve_table(mapping, channels, combined):
    mapping.initialize()
    curves = list(mapping.curves)
    used = [curves[i] for i in channels] + ([curves[3]] if combined else [])
    lo = min(curve.points[0].location[0] for curve in used)
    hi = max(curve.points[-1].location[0] for curve in used)
    rows = []
    for i in range(TABLE_SIZE):
        t = lo + i / (TABLE_SIZE - 1) * (hi - lo)
        if combined:
            rows.append([mapping.evaluate(curves[k], mapping.evaluate(curves[3], t)) for k in channels])
        else:
            rows.append([mapping.evaluate(curves[k], t) for k in channels] + [0.0] * (3 - len(channels)))
    return rows, lo, hi, mapping.extend == "EXTRAPOLATED"


def rgb_curves_node(c, node, context, variant, identifier):
    rows, lo, hi, extrapolate = _curve_table(node.mapping, (0, 1, 2), True)
    table = _table(c, rows)
    out = c.emit(op.CURVES, [_v(c, node, "Fac", context, variant, FLOAT), _v(c, node, "Color", context, variant, COLOR),
                             table, TABLE_SIZE, int(extrapolate), c.const(lo, hi)], mode=0, width=3, reads=[table])
    return {"Color": (out, COLOR)}


def vector_curves_node(c, node, context, variant, identifier):
    rows, lo, hi, extrapolate = _curve_table(node.mapping, (0, 1, 2), False)
    table = _table(c, rows)
    out = c.emit(op.CURVES, [_v(c, node, "Fac", context, variant, FLOAT),
                             _v(c, node, "Vector", context, variant, VECTOR), table, TABLE_SIZE, int(extrapolate),
                             c.const(lo, hi)], mode=1, width=3, reads=[table])
    return {"Vector": (out, VECTOR)}


def float_curve_node(c, node, context, variant, identifier):
    rows, lo, hi, extrapolate = _curve_table(node.mapping, (0,), False)
    table = _table(c, rows)
    value = _v(c, node, "Value", context, variant, FLOAT)
    curved = c.emit(op.CURVES, [None, value, table, TABLE_SIZE, int(extrapolate), c.const(lo, hi)], mode=2,
                    reads=[table])
    fac = _v(c, node, "Factor", context, variant, FLOAT)
    return {"Value": (c.emit(op.MIX_FLOAT, [fac, value, curved]), FLOAT)}


def hue_saturation_node(c, node, context, variant, identifier):
    args = [_v(c, node, "Hue", context, variant, FLOAT), _v(c, node, "Saturation", context, variant, FLOAT),
            _v(c, node, "Value", context, variant, FLOAT), _v(c, node, "Fac", context, variant, FLOAT),
            _v(c, node, "Color", context, variant, COLOR)]
    return {"Color": (c.emit(op.HUE_SATURATION, args, width=3), COLOR)}


def invert_node(c, node, context, variant, identifier):
    args = [_v(c, node, "Fac", context, variant, FLOAT), _v(c, node, "Color", context, variant, COLOR)]
    return {"Color": (c.emit(op.INVERT, args, width=3), COLOR)}


def bright_contrast_node(c, node, context, variant, identifier):
    args = [_v(c, node, "Color", context, variant, COLOR), _v(c, node, "Bright", context, variant, FLOAT),
            _v(c, node, "Contrast", context, variant, FLOAT)]
    return {"Color": (c.emit(op.BRIGHT_CONTRAST, args, width=3), COLOR)}


def gamma_node(c, node, context, variant, identifier):
    args = [_v(c, node, "Color", context, variant, COLOR), _v(c, node, "Gamma", context, variant, FLOAT)]
    return {"Color": (c.emit(op.GAMMA, args, width=3), COLOR)}


def rgb_to_bw_node(c, node, context, variant, identifier):
    return {"Val": (c.emit(op.RGB_TO_BW, [_v(c, node, "Color", context, variant, COLOR)]), FLOAT)}


_COLOR_MODES = {"RGB": 0, "HSV": 1, "HSL": 2}


def separate_color_node(c, node, context, variant, identifier, mode=None, names=("Red", "Green", "Blue"),
                        socket="Color"):
    mode = _COLOR_MODES[node.mode] if mode is None else mode
    out = c.emit(op.SEPARATE_COLOR, [_v(c, node, socket, context, variant, COLOR)], mode=mode, width=3)
    return {name: (out.component(i), FLOAT) for i, name in enumerate(names)}


def combine_color_node(c, node, context, variant, identifier, mode=None, names=("Red", "Green", "Blue"),
                       output="Color"):
    mode = _COLOR_MODES[node.mode] if mode is None else mode
    args = [_v(c, node, name, context, variant, FLOAT) for name in names]
    return {output: (c.emit(op.COMBINE_COLOR, args, mode=mode, width=3), COLOR)}


def separate_rgb_node(c, node, context, variant, identifier):
    return separate_color_node(c, node, context, variant, identifier, 0, ("R", "G", "B"), "Image")


def combine_rgb_node(c, node, context, variant, identifier):
    return combine_color_node(c, node, context, variant, identifier, 0, ("R", "G", "B"), "Image")


def separate_hsv_node(c, node, context, variant, identifier):
    return separate_color_node(c, node, context, variant, identifier, 1, ("H", "S", "V"), "Color")


def combine_hsv_node(c, node, context, variant, identifier):
    return combine_color_node(c, node, context, variant, identifier, 1, ("H", "S", "V"), "Color")


def separate_xyz_node(c, node, context, variant, identifier):
    v = _v(c, node, "Vector", context, variant, VECTOR)
    return {name: (v.component(i), FLOAT) for i, name in enumerate("XYZ")}


def combine_xyz_node(c, node, context, variant, identifier):
    args = [_v(c, node, name, context, variant, FLOAT) for name in "XYZ"]
    return {"Vector": (c.emit(op.COMBINE_XYZ, args, width=3), VECTOR)}


BLACKBODY_RANGE_K = (800.0, 12000.0)


def blackbody_rgb(temperature_k):
    """Rec.709 colour of a blackbody (luminance 1, negative components clamped to 0), from Planck's law and
    the CIE 1931 observer; Blender's range 800-12000 K (beyond it the colour stays that of the end)."""
    from ...tracer.spectra import blackbody, cie

    t = np.clip(np.asarray(temperature_k, np.float64), *BLACKBODY_RANGE_K)
    xyz = cie.spectrum_to_xyz(lambda nm: blackbody.planck_spectral_radiance(nm, t[..., None]))
    rgb = cie.xyz_to_linear_rec709(xyz / xyz[..., 1:2])
    return np.maximum(rgb, 0.0)


def blackbody_node(c, node, context, variant, identifier):
    temperature = _v(c, node, "Temperature", context, variant, FLOAT)
    known = c.known(temperature)
    if c.evaluate is None:  # a preview (the material panel): no colour science at draw time
        return {"Color": (c.const(1.0, 1.0, 1.0), COLOR)}
    if known is not None:
        return {"Color": (c.const(*blackbody_rgb(known).tolist()), COLOR)}
    lo, hi = (math.log(x) for x in BLACKBODY_RANGE_K)
    samples = blackbody_rgb(np.exp(np.linspace(lo, hi, TABLE_SIZE)))
    table = _table(c, np.concatenate([samples, np.ones((TABLE_SIZE, 1))], axis=1))
    position = c.math("DIVIDE", c.math("SUBTRACT", c.math("LOGARITHM", temperature, c.const(math.e)), c.const(lo)),
                      c.const(hi - lo))
    out = c.emit(op.COLOR_RAMP, [position, table, TABLE_SIZE], mode=0, width=4, reads=[table])
    return {"Color": (out.__class__(out.register, 3), COLOR)}


def mapping_node(c, node, context, variant, identifier):
    mode = op.MAPPING_TYPES.index(node.vector_type)
    args = [_v(c, node, name, context, variant, VECTOR) for name in ("Vector", "Location", "Rotation", "Scale")]
    return {"Vector": (c.emit(op.MAPPING, args, mode=mode, width=3), VECTOR)}


def vector_rotate_node(c, node, context, variant, identifier):
    mode = op.ROTATE_TYPES.index(node.rotation_type)
    args = [_v(c, node, "Vector", context, variant, VECTOR), _v(c, node, "Center", context, variant, VECTOR),
            _v(c, node, "Axis", context, variant, VECTOR), _v(c, node, "Angle", context, variant, FLOAT),
            _v(c, node, "Rotation", context, variant, VECTOR), int(node.invert)]
    return {"Vector": (c.emit(op.VECTOR_ROTATE, args, mode=mode, width=3), VECTOR)}


HANDLERS = {
    "ShaderNodeMath": math_node,
    "ShaderNodeVectorMath": vector_math_node,
    "ShaderNodeMix": mix_node,
    "ShaderNodeMixRGB": mix_rgb_node,
    "ShaderNodeMapRange": map_range_node,
    "ShaderNodeClamp": clamp_node,
    "ShaderNodeValToRGB": color_ramp_node,
    "ShaderNodeRGBCurve": rgb_curves_node,
    "ShaderNodeVectorCurve": vector_curves_node,
    "ShaderNodeFloatCurve": float_curve_node,
    "ShaderNodeHueSaturation": hue_saturation_node,
    "ShaderNodeInvert": invert_node,
    "ShaderNodeBrightContrast": bright_contrast_node,
    "ShaderNodeGamma": gamma_node,
    "ShaderNodeRGBToBW": rgb_to_bw_node,
    "ShaderNodeSeparateColor": separate_color_node,
    "ShaderNodeCombineColor": combine_color_node,
    "ShaderNodeSeparateRGB": separate_rgb_node,
    "ShaderNodeCombineRGB": combine_rgb_node,
    "ShaderNodeSeparateHSV": separate_hsv_node,
    "ShaderNodeCombineHSV": combine_hsv_node,
    "ShaderNodeSeparateXYZ": separate_xyz_node,
    "ShaderNodeCombineXYZ": combine_xyz_node,
    "ShaderNodeBlackbody": blackbody_node,
    "ShaderNodeMapping": mapping_node,
    "ShaderNodeVectorRotate": vector_rotate_node,
}
