"""Texture nodes: Image, Noise, Voronoi, Checker, Gradient, Wave, Brick, Magic, White Noise. Unlinked
vectors read the default UV map (images) or the generated coordinates (procedural textures), as in
Blender. Each handler returns {output identifier: (Value, kind)} (see ``compiler``)."""

from __future__ import annotations

from ...tracer.materials import opcodes as op
from .terms import COLOR, FLOAT, VECTOR
from ..texture_memory import TextureMemoryError
from .images import MISSING_COLOUR, read_image
from .inputs import generated, uv


def _vector(c, node, context, variant, default):
    return c.value(node, "Vector", context, VECTOR, variant, default=lambda: default(c, variant))


def _float(c, node, name, context, variant):
    return c.value(node, name, context, FLOAT, variant)


def _mapping_warning(c, node):
    mapping = getattr(node, "texture_mapping", None)
    if mapping is None:
        return
    moved = any(abs(x) > 1e-9 for x in mapping.translation) or any(abs(x) > 1e-9 for x in mapping.rotation) or any(
        abs(x - 1.0) > 1e-9 for x in mapping.scale)
    if moved:
        c.warn(node, "has a Texture Mapping (node sidebar) that Prism ignores; use a Mapping node instead.")


def image_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    if node.projection != "FLAT":
        c.warn(node, f"uses {node.projection.lower()} projection; Prism projects it flat.")
    try:
        image = read_image(node.image, node, c.warn, c.image_cache) if c.load_pixels else None
    except TextureMemoryError as error:
        raise TextureMemoryError(f"Material '{c.material.name}': {error}") from None
    if image is None and c.load_pixels:
        return {"Color": (c.const(*MISSING_COLOUR[:3]), COLOR), "Alpha": (c.const(1.0), FLOAT)}
    vector = c.value(node, "Vector", context, VECTOR, variant, default=lambda: uv(c, "", variant))
    index = c.image_index(image) if image is not None else 0
    out = c.emit(op.IMAGE, [vector, index], width=4)
    return {"Color": (out.__class__(out.register, 3), COLOR), "Alpha": (out.component(3), FLOAT)}


def noise_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    dims = int(node.noise_dimensions[0])
    kind = op.NOISE_TYPES.index(node.noise_type)
    vector = _vector(c, node, context, variant, generated)
    args = [vector] + [_float(c, node, name, context, variant)
                       for name in ("W", "Scale", "Detail", "Roughness", "Lacunarity", "Distortion")]
    colour = identifier == "Color"
    extra = [_float(c, node, "Offset", context, variant), _float(c, node, "Gain", context, variant),
             int(node.normalize), int(colour)]
    out = c.emit(op.NOISE, args, mode=kind * 8 + dims, width=4, extra=extra)
    result = {"Fac": (out.component(0), FLOAT)}
    if colour:
        result["Color"] = (out.__class__(out.register + 1, 3), COLOR)
    return result


def voronoi_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    dims = int(node.voronoi_dimensions[0])
    if dims not in (2, 3):
        c.warn(node, f"is {dims}-D; Prism renders Voronoi in 2-D and 3-D only and uses 3-D.")
        dims = 3
    feature = op.VORONOI_FEATURES.index(node.feature)
    metric = op.VORONOI_METRICS.index(node.distance)
    vector = _vector(c, node, context, variant, generated)
    args = [vector, _float(c, node, "W", context, variant)] + [
        _float(c, node, name, context, variant) for name in ("Scale", "Detail", "Roughness", "Lacunarity", "Smoothness")]
    extra = [_float(c, node, "Exponent", context, variant), _float(c, node, "Randomness", context, variant),
             int(node.normalize)]
    out = c.emit(op.VORONOI, args, mode=feature * 64 + metric * 8 + dims, width=9, extra=extra)
    r = out.register
    return {"Distance": (out.component(0), FLOAT), "Color": (out.__class__(r + 1, 3), COLOR),
            "Position": (out.__class__(r + 4, 3), VECTOR), "W": (out.component(7), FLOAT),
            "Radius": (out.component(8), FLOAT)}


def _colour_fac(out):
    return {"Color": (out.__class__(out.register, 3), COLOR), "Fac": (out.component(3), FLOAT)}


def checker_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    args = [_vector(c, node, context, variant, generated), c.value(node, "Color1", context, COLOR, variant),
            c.value(node, "Color2", context, COLOR, variant), _float(c, node, "Scale", context, variant)]
    return _colour_fac(c.emit(op.CHECKER, args, width=4))


def gradient_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    out = c.emit(op.GRADIENT, [_vector(c, node, context, variant, generated)],
                 mode=op.GRADIENT_TYPES.index(node.gradient_type), width=4)
    return _colour_fac(out)


def wave_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    kind = op.WAVE_TYPES.index(node.wave_type)
    direction = (op.WAVE_BANDS_DIRECTIONS.index(node.bands_direction) if kind == 0
                 else op.WAVE_RINGS_DIRECTIONS.index(node.rings_direction))
    profile = op.WAVE_PROFILES.index(node.wave_profile)
    args = [_vector(c, node, context, variant, generated)] + [
        _float(c, node, name, context, variant)
        for name in ("Scale", "Distortion", "Detail", "Detail Scale", "Detail Roughness", "Phase Offset")]
    return _colour_fac(c.emit(op.WAVE, args, mode=kind * 16 + direction * 4 + profile, width=4))


def brick_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    args = [_vector(c, node, context, variant, generated), c.value(node, "Color1", context, COLOR, variant),
            c.value(node, "Color2", context, COLOR, variant), c.value(node, "Mortar", context, COLOR, variant),
            _float(c, node, "Scale", context, variant), _float(c, node, "Mortar Size", context, variant),
            _float(c, node, "Mortar Smooth", context, variant)]
    extra = [_float(c, node, "Bias", context, variant), _float(c, node, "Brick Width", context, variant),
             _float(c, node, "Row Height", context, variant), c.const(float(node.offset)), int(node.offset_frequency),
             c.const(float(node.squash)), int(node.squash_frequency)]
    return _colour_fac(c.emit(op.BRICK, args, width=4, extra=extra))


def magic_texture(c, node, context, variant, identifier):
    _mapping_warning(c, node)
    args = [_vector(c, node, context, variant, generated), _float(c, node, "Scale", context, variant),
            _float(c, node, "Distortion", context, variant)]
    return _colour_fac(c.emit(op.MAGIC, args, mode=int(node.turbulence_depth), width=4))


def white_noise_texture(c, node, context, variant, identifier):
    dims = int(node.noise_dimensions[0])
    args = [_vector(c, node, context, variant, generated), _float(c, node, "W", context, variant)]
    out = c.emit(op.WHITE_NOISE, args, mode=dims, width=4)
    return {"Value": (out.component(0), FLOAT), "Color": (out.__class__(out.register + 1, 3), COLOR)}


HANDLERS = {
    "ShaderNodeTexImage": image_texture,
    "ShaderNodeTexNoise": noise_texture,
    "ShaderNodeTexVoronoi": voronoi_texture,
    "ShaderNodeTexChecker": checker_texture,
    "ShaderNodeTexGradient": gradient_texture,
    "ShaderNodeTexWave": wave_texture,
    "ShaderNodeTexBrick": brick_texture,
    "ShaderNodeTexMagic": magic_texture,
    "ShaderNodeTexWhiteNoise": white_noise_texture,
}
