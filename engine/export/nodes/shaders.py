"""Shader nodes → closures, as Cycles defines them: Principled BSDF (layered: alpha, coat, emission,
metallic, transmission, specular, diffuse), Diffuse, Glossy, Metallic, Glass, Refraction, Translucent,
Transparent, Emission, Holdout, Mix Shader and Add Shader; Sheen in ``sheen``.

Each handler takes the weight its shader socket carries (``terms.Weight``) and adds closures
(``terms.PendingClosure``) and emission. The Principled layering follows Blender's: a layer's closure
takes the running weight, then the layers below keep weight × (1 - its albedo seen from the view
direction) (sheen, ``SHEEN_ALBEDO``; coat and specular, ``LAYER_ALBEDO``) or × (1 - its weight) (metallic, transmission).
"""

from __future__ import annotations

from ...tracer.bsdf.closure import (CONDUCTOR, DIELECTRIC, DIFFUSE, FRESNEL_CONDUCTOR, FRESNEL_DIELECTRIC,
                                    FRESNEL_F82, FRESNEL_NONE, GLASS, REFRACTION_ONLY, TRANSLUCENT, TRANSPARENT)
from ...tracer.materials import opcodes as op
from .terms import COLOR, FLOAT, VECTOR, PendingClosure, Weight
from .measured_base import keeps_own_colour, measured_base
from .overrides import check_film, conductor_override, glass_override, prism_coating
from .normals import bump_map_correction, shader_normal, towards
from .sheen import principled_sheen, sheen_bsdf
from .hair import hair_bsdf, principled_hair
from .subsurface import principled_subsurface, subsurface_scattering


def _val(c, node, name, context, kind=FLOAT):
    return c.value(node, name, context, kind)


def _alpha(c, roughness):
    roughness = c.clamp01(roughness)
    return c.math("MULTIPLY", roughness, roughness)


def _multiscatter(c, node) -> bool:
    """Whether the node's distribution is Multiscatter GGX (energy-compensated GGX, as Cycles renders it);
    other distributions than GGX get a warning (Prism renders them as single-scatter GGX)."""
    distribution = getattr(node, "distribution", "GGX")
    if distribution == "MULTI_GGX":
        return True
    if distribution not in ("GGX", "SHARP"):
        c.warn(node, f"uses the {distribution.replace('_', ' ').title()} distribution; Prism renders GGX.")
    return False


def _cos_view(c, normal):
    incoming = c.hit(op.INCOMING)
    return c.vector_math("DOT_PRODUCT", incoming, normal if normal is not None else c.normal())


def _f0(c, eta):
    r = c.math("DIVIDE", c.math("SUBTRACT", eta, c.const(1.0)), c.math("ADD", eta, c.const(1.0)))
    return c.math("MULTIPLY", r, r)


def _layer_albedo(c, roughness, cos, eta):
    return c.emit(op.LAYER_ALBEDO, [c.clamp01(roughness), cos, eta])


def _darkening(c, roughness, cos, eta, f0):
    """Factor on a Multiscatter GGX dielectric layer's albedo: what its energy compensation reflects."""
    return c.emit(op.LAYER_DARKENING, [c.clamp01(roughness), cos, eta, f0])


def _max_channel(c, colour):
    return c.math("MAXIMUM", c.math("MAXIMUM", colour.component(0), colour.component(1)), colour.component(2))


def _saturate(c, colour):
    return c.vector_math("MINIMUM", c.vector_math("MAXIMUM", colour, c.const(0.0, 0.0, 0.0)), c.const(1.0, 1.0, 1.0))


def principled(c, node, context, weight: Weight):
    base = _val(c, node, "Base Color", context, COLOR)
    roughness = c.clamp01(_val(c, node, "Roughness", context))
    alpha = _alpha(c, roughness)
    ior = c.math("MAXIMUM", _val(c, node, "IOR", context), c.const(1e-5))
    normal = shader_normal(c, node, context)
    specular_tint = c.vector_math("MAXIMUM", _val(c, node, "Specular Tint", context, COLOR), c.const(0.0, 0.0, 0.0))
    multiscatter = _multiscatter(c, node)
    for name in ("Anisotropic",):
        if c.known(_val(c, node, name, context)) != 0.0:
            c.warn(node, "is anisotropic; Prism renders it isotropic.")
    cos = _cos_view(c, normal)

    opacity = c.clamp01(_val(c, node, "Alpha", context))
    if c.known(opacity) != 1.0:
        c.add_closure(PendingClosure(TRANSPARENT, c.weighted(weight, scale=c.one_minus(opacity)), node))
        weight = c.weighted(weight, scale=opacity)

    coat = c.math("MAXIMUM", _val(c, node, "Coat Weight", context), c.const(0.0))
    has_coat = c.known(coat) != 0.0
    coat_normal = shader_normal(c, node, context, "Coat Normal") if has_coat else None
    # Cycles' sheen leans towards the Coat Normal by the coat's weight (svm/closure.h, principled_bsdf_emission)
    sheen_normal = normal if coat_normal is None else towards(c, normal, coat_normal, c.clamp01(coat))
    sheen_cos = cos if sheen_normal is normal else _cos_view(c, sheen_normal)
    weight = principled_sheen(c, node, context, weight, sheen_cos, sheen_normal)

    if has_coat:
        coat_roughness = c.clamp01(_val(c, node, "Coat Roughness", context))
        coat_ior = c.math("MAXIMUM", _val(c, node, "Coat IOR", context), c.const(1.0))
        if coat_normal is None:
            coat_normal, coat_cos = normal, cos
        else:  # the coat shades, weighs the layers under it and tints along its own normal, as in Cycles,
            if bump_map_correction(c):  # raised as Cycles raises it before it sets the coat up
                coat_normal = c.emit(op.VALID_REFLECTION, [coat_normal], width=3)
            coat_cos = _cos_view(c, coat_normal)
        # Cycles compensates the coat's energy whatever the distribution (bsdf_microfacet_setup_fresnel_dielectric)
        c.add_closure(PendingClosure(CONDUCTOR, c.weighted(weight, scale=coat), node, alpha=_alpha(c, coat_roughness),
                                     eta=coat_ior, fresnel=FRESNEL_DIELECTRIC, normal=coat_normal, multiscatter=True))
        f0 = _f0(c, coat_ior)
        s = _layer_albedo(c, coat_roughness, coat_cos, coat_ior)
        albedo = c.math("ADD", f0, c.math("MULTIPLY", c.one_minus(f0), s))
        albedo = c.math("MULTIPLY", albedo, _darkening(c, coat_roughness, coat_cos, coat_ior, f0))
        weight = c.weighted(weight, scale=c.clamp01(c.one_minus(c.math("MULTIPLY", coat, albedo))))
        tint = c.vector_math("MAXIMUM", _val(c, node, "Coat Tint", context, COLOR), c.const(0.0, 0.0, 0.0))
        if c.known(tint) != (1.0, 1.0, 1.0):
            inv = c.math("DIVIDE", c.const(1.0), coat_ior)
            sin2 = c.math("MULTIPLY", c.math("MULTIPLY", inv, inv), c.one_minus(c.math("MULTIPLY", coat_cos, coat_cos)))
            depth = c.math("DIVIDE", c.const(1.0), c.math("SQRT", c.one_minus(sin2)))
            absorbed = c.vector_math("POWER", tint, c.broadcast(depth))
            mixed = c.emit(op.MIX_VECTOR, [coat, c.const(1.0, 1.0, 1.0), absorbed, None, 0], width=3)
            weight = c.weighted(weight, colour=mixed)

    emission_colour = _val(c, node, "Emission Color", context, COLOR)
    strength = _val(c, node, "Emission Strength", context)
    _non_negative(c, node, "Emission Strength", strength)
    spectrum = c.overrides.get("emission") or _blackbody_spectrum(c, node, "Emission Color", context)
    c.add_emission(weight, None if "emission" in c.overrides else emission_colour, strength, spectrum=spectrum,
                   node=node, setting="Emission Strength × Emission Color")

    film = _val(c, node, "Thin Film Thickness", context)
    film_nm = c.known(film)
    if film_nm is None:
        c.warn(node, "has a textured Thin Film Thickness; Prism uses no film there.")
        film_nm = 0.0
    film_ior = c.known(_val(c, node, "Thin Film IOR", context))
    if film_ior is None:
        c.warn(node, "has a textured Thin Film IOR; Prism uses 1.33 there.")
        film_ior = 1.33
    if film_nm > 0.1:
        check_film(c.material.name, f"{node.name} ▸ Thin Film Thickness", film_nm, f"{node.name} ▸ Thin Film IOR",
                   film_ior)

    metallic = c.clamp01(_val(c, node, "Metallic", context))
    if c.known(metallic) != 0.0:
        metal = PendingClosure(CONDUCTOR, c.weighted(weight, scale=metallic), node, alpha=alpha, fresnel=FRESNEL_F82,
                               s0=_saturate(c, base), s1=c.vector_math("MINIMUM", specular_tint, c.const(1.0, 1.0, 1.0)),
                               normal=normal, measured=measured_base(c), multiscatter=multiscatter)
        conductor_override(c, metal)
        prism_coating(c, metal)
        c.add_closure(metal)
        weight = c.weighted(weight, scale=c.one_minus(metallic))

    transmission = c.clamp01(_val(c, node, "Transmission Weight", context))
    if c.known(transmission) != 0.0:
        keeps_own_colour(c, node, "its transmission is tinted by the Base Color as a transmittance")
        through = c.vector_math("POWER", _saturate(c, base), c.const(0.5, 0.5, 0.5))
        # Cycles' Fss of a glass is its transmission tint
        glass = PendingClosure(DIELECTRIC, c.weighted(weight, scale=transmission), node, alpha=alpha, eta=ior,
                               fresnel=GLASS, s0=specular_tint, s1=through, normal=normal, multiscatter=multiscatter,
                               multiscatter_colour=through if multiscatter else None)
        if film_nm > 0.1:
            glass.coat_nm, glass.coat_ior = film_nm, film_ior
        glass_override(c, glass)
        prism_coating(c, glass)
        c.add_closure(glass)
        weight = c.weighted(weight, scale=c.one_minus(transmission))

    level = c.math("MAXIMUM", _val(c, node, "Specular IOR Level", context), c.const(0.0))
    eta = ior
    if c.known(level) != 0.5:
        f0 = c.math("MULTIPLY", _f0(c, ior), c.math("MULTIPLY", level, c.const(2.0)))
        root = c.math("SQRT", c.emit(op.CLAMP, [f0, c.const(0.0), c.const(0.99)]))
        eta = c.math("DIVIDE", c.math("ADD", c.const(1.0), root), c.math("SUBTRACT", c.const(1.0), root))
        below = c.math("LESS_THAN", ior, c.const(1.0))
        eta = c.emit(op.MIX_FLOAT, [below, eta, c.math("DIVIDE", c.const(1.0), eta)])
    if c.known(eta) != 1.0 or film_nm > 0.1:
        specular = PendingClosure(CONDUCTOR, weight, node, alpha=alpha, eta=eta, fresnel=FRESNEL_DIELECTRIC,
                                  s0=specular_tint, normal=normal, multiscatter=multiscatter)
        if film_nm > 0.1:
            specular.coat_nm, specular.coat_ior = film_nm, film_ior
        c.add_closure(specular)
        f0 = c.vector_math("SCALE", specular_tint, s=_f0(c, eta))
        f0 = _saturate(c, f0)
        constant = (normal is None and weight.layer is None
                    and None not in (c.known(f0), c.known(roughness), c.known(eta)))
        if constant:  # applied per hit from the closure rows, without running a program
            weight = Weight(weight.scale, weight.colour, (c.known(eta), c.known(roughness), max(c.known(f0)),
                                                          1.0 if multiscatter else 0.0))
        else:
            s = _layer_albedo(c, roughness, cos, eta)
            one = c.const(1.0, 1.0, 1.0)
            albedo = c.vector_math("ADD", f0, c.vector_math("SCALE", c.vector_math("SUBTRACT", one, f0), s=s))
            largest = _max_channel(c, albedo)
            if multiscatter:
                largest = c.math("MULTIPLY", largest, _darkening(c, roughness, cos, eta, _max_channel(c, f0)))
            weight = c.weighted(weight, scale=c.clamp01(c.one_minus(largest)))

    weight = principled_subsurface(c, node, context, weight, base, alpha, eta)
    if c.known(_val(c, node, "Diffuse Roughness", context)) != 0.0:
        c.warn(node, "has Diffuse Roughness; Prism renders Lambertian (smooth) diffuse reflection.")
    measured = measured_base(c)
    colour = c.vector_math("MAXIMUM", base, c.const(0.0, 0.0, 0.0)) if measured is None else None
    c.add_closure(PendingClosure(DIFFUSE, c.weighted(weight, colour=colour), node, normal=normal, measured=measured))


def _non_negative(c, node, name, value):
    """A negative constant strength is bad input (Prism has no negative light)."""
    from ...tracer.errors import PrismInputError

    known = c.known(value)
    if known is not None and known < 0:
        raise PrismInputError(f"Material '{c.material.name}': {name} {known:g} is negative.")


def _blackbody_spectrum(c, node, name, context):
    """A Planck spectrum when a Blackbody node of constant temperature feeds ``name`` directly."""
    from ...tracer.scene import SpectrumSpec

    source = c.linked(node, name, context)
    if source is None or source.node.bl_idname != "ShaderNodeBlackbody":
        return None
    temperature = c.known(c.value(source.node, "Temperature", source.context, FLOAT))
    if temperature is None:
        return None
    if not 1000.0 <= temperature <= 40000.0:
        c.warn(source.node, f"has {temperature:g} K; Prism's blackbody spectra cover 1000-40000 K, so it uses "
                            f"{min(max(temperature, 1000.0), 40000.0):g} K.")
        temperature = min(max(temperature, 1000.0), 40000.0)
    return SpectrumSpec(kind="blackbody", temperature_k=float(temperature))


def _albedo(c, node, context):
    """(RGB colour or None, measured reflectance or None) of a diffuse node's Color: the material's measured
    reflectance replaces it."""
    measured = measured_base(c)
    if measured is not None:
        return None, measured
    return c.vector_math("MAXIMUM", _val(c, node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0)), None


def diffuse(c, node, context, weight):
    if c.known(_val(c, node, "Roughness", context)) != 0.0:
        c.warn(node, "has Roughness (Oren-Nayar); Prism renders Lambertian diffuse reflection.")
    colour, measured = _albedo(c, node, context)
    c.add_closure(PendingClosure(DIFFUSE, c.weighted(weight, colour=colour), node, normal=shader_normal(c, node, context),
                                 measured=measured))


def glossy(c, node, context, weight):
    multiscatter = _multiscatter(c, node)
    keeps_own_colour(c, node, "its Color is a specular tint")
    if c.known(_val(c, node, "Anisotropy", context)) != 0.0:
        c.warn(node, "is anisotropic; Prism renders it isotropic.")
    colour = c.vector_math("MAXIMUM", _val(c, node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0))
    # Cycles' Fss of a Glossy BSDF is its colour
    c.add_closure(PendingClosure(CONDUCTOR, c.weighted(weight, colour=colour), node,
                                 alpha=_alpha(c, _val(c, node, "Roughness", context)), fresnel=FRESNEL_NONE,
                                 normal=shader_normal(c, node, context), multiscatter=multiscatter,
                                 multiscatter_colour=colour if multiscatter else None))


def metallic(c, node, context, weight):
    multiscatter = _multiscatter(c, node)
    if c.known(_val(c, node, "Anisotropy", context)) != 0.0:
        c.warn(node, "is anisotropic; Prism renders it isotropic.")
    alpha = _alpha(c, _val(c, node, "Roughness", context))
    if node.fresnel_type == "F82":
        s0 = _saturate(c, _val(c, node, "Base Color", context, COLOR))
        s1 = _saturate(c, _val(c, node, "Edge Tint", context, COLOR))
    else:
        n = c.vector_math("MAXIMUM", _val(c, node, "IOR", context, VECTOR), c.const(0.0, 0.0, 0.0))
        k = c.vector_math("MAXIMUM", _val(c, node, "Extinction", context, VECTOR), c.const(0.0, 0.0, 0.0))
        one = c.const(1.0, 1.0, 1.0)
        k2 = c.vector_math("MULTIPLY", k, k)
        minus = c.vector_math("SUBTRACT", n, one)
        plus = c.vector_math("ADD", n, one)
        s0 = c.vector_math("DIVIDE", c.vector_math("ADD", c.vector_math("MULTIPLY", minus, minus), k2),
                           c.vector_math("ADD", c.vector_math("MULTIPLY", plus, plus), k2))
        s1 = one
        c.warn(node, "is a physical conductor given by RGB n and k; Prism renders its normal-incidence "
                     "reflectance with the F82 model (or a measured metal: Material ▸ Prism ▸ Metal).")
        keeps_own_colour(c, node, "its IOR and Extinction give its reflectance")
    measured = measured_base(c) if node.fresnel_type == "F82" else None
    metal = PendingClosure(CONDUCTOR, weight, node, alpha=alpha, fresnel=FRESNEL_F82, s0=s0, s1=s1,
                           normal=shader_normal(c, node, context), measured=measured, multiscatter=multiscatter)
    conductor_override(c, metal)
    prism_coating(c, metal)
    c.add_closure(metal)


def _dielectric(c, node, context, weight, mode):
    multiscatter = _multiscatter(c, node)  # Glass offers Multiscatter GGX; Refraction only GGX and Beckmann
    keeps_own_colour(c, node, "its Color is a transmittance")
    colour = c.vector_math("MAXIMUM", _val(c, node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0))
    eta = c.math("MAXIMUM", _val(c, node, "IOR", context), c.const(1e-5))
    # Cycles' Fss of a glass is its transmission tint, here the colour
    closure = PendingClosure(DIELECTRIC, c.weighted(weight, colour=colour), node,
                             alpha=_alpha(c, _val(c, node, "Roughness", context)), eta=eta, fresnel=mode,
                             normal=shader_normal(c, node, context), multiscatter=multiscatter,
                             multiscatter_colour=colour if multiscatter else None)
    glass_override(c, closure)
    prism_coating(c, closure)
    c.add_closure(closure)


def glass(c, node, context, weight):
    _dielectric(c, node, context, weight, GLASS)


def refraction(c, node, context, weight):
    _dielectric(c, node, context, weight, REFRACTION_ONLY)


def translucent(c, node, context, weight):
    keeps_own_colour(c, node, "its Color is a transmittance")
    colour = c.vector_math("MAXIMUM", _val(c, node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0))
    c.add_closure(PendingClosure(TRANSLUCENT, c.weighted(weight, colour=colour), node,
                                 normal=shader_normal(c, node, context)))


def transparent(c, node, context, weight):
    keeps_own_colour(c, node, "its Color is a transmittance")
    colour = c.vector_math("MAXIMUM", _val(c, node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0))
    c.add_closure(PendingClosure(TRANSPARENT, c.weighted(weight, colour=colour), node))


def emission(c, node, context, weight):
    spectrum = _blackbody_spectrum(c, node, "Color", context)
    colour = None if spectrum is not None else _val(c, node, "Color", context, COLOR)
    strength = _val(c, node, "Strength", context)
    _non_negative(c, node, "Strength", strength)
    c.add_emission(weight, colour, strength, spectrum=spectrum, node=node, setting="Strength × Color")


def holdout(c, node, context, weight):
    c.warn(node, "is mixed with other shaders; Prism holds out only a material whose Surface is a Holdout "
                 "node, so here it renders black.")


def mix_shader(c, node, context, weight):
    fac = c.clamp01(c.value(node, "Fac", context, FLOAT))
    first, second = node.inputs[1], node.inputs[2]
    if c.known(fac) != 1.0:
        c.shader(first, context, c.weighted(weight, scale=c.one_minus(fac)))
    if c.known(fac) != 0.0:
        c.shader(second, context, c.weighted(weight, scale=fac))


def add_shader(c, node, context, weight):
    c.shader(node.inputs[0], context, weight)
    c.shader(node.inputs[1], context, weight)


def left_out(c, node, context, weight):
    c.warn(node, "is not modelled by Prism; it is left out (black).")


SHADER_HANDLERS = {
    "ShaderNodeBsdfPrincipled": principled,
    "ShaderNodeBsdfDiffuse": diffuse,
    "ShaderNodeBsdfAnisotropic": glossy,
    "ShaderNodeBsdfMetallic": metallic,
    "ShaderNodeBsdfGlass": glass,
    "ShaderNodeBsdfRefraction": refraction,
    "ShaderNodeBsdfTranslucent": translucent,
    "ShaderNodeBsdfTransparent": transparent,
    "ShaderNodeEmission": emission,
    "ShaderNodeHoldout": holdout,
    "ShaderNodeSubsurfaceScattering": subsurface_scattering,
    "ShaderNodeMixShader": mix_shader,
    "ShaderNodeAddShader": add_shader,
    "ShaderNodeBsdfSheen": sheen_bsdf,
    "ShaderNodeBsdfToon": left_out,
    "ShaderNodeBsdfHair": hair_bsdf,
    "ShaderNodeBsdfHairPrincipled": principled_hair,
    "ShaderNodeBsdfRayPortal": left_out,
    "ShaderNodeEeveeSpecular": left_out,
    "ShaderNodeVolumeAbsorption": left_out,
    "ShaderNodeVolumeScatter": left_out,
    "ShaderNodeVolumePrincipled": left_out,
    "ShaderNodeBackground": left_out,
}
