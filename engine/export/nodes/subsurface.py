"""Subsurface scattering from Blender's nodes, as Cycles sets it up (``svm_node_closure_bsdf``): the Principled
BSDF's Subsurface (Weight, Radius, Scale, IOR, Anisotropy, the node's Subsurface Method) and the Subsurface
Scattering node, each a ``SUBSURFACE`` closure the tracer renders as a random walk (``tracer.subsurface``).

Principled: weight × Subsurface Weight × Base Color (clamped to 0-1) under its specular layer, the walk's albedo
the clamped Base Color, the entry's roughness its Roughness² and index its IOR (after Specular IOR Level), or
Subsurface IOR for Random Walk (Skin); the diffuse lobe keeps 1 − Subsurface Weight. Subsurface Scattering node:
weight × Color, albedo Color, entry roughness Roughness (not squared, as Cycles) and index IOR.

The radius is Radius × Scale per channel (metres, a mean free path); Prism upsamples Radius over its largest
channel to a spectrum (a smooth reflectance spectrum, as colours), so each wavelength has its own. Radius and
Scale must be constant here: a linked one takes its socket's value, and a warning says so.
"""

from __future__ import annotations

from ...tracer.bsdf.closure import DIFFUSE, SSS_RANDOM_WALK, SSS_SKIN, SUBSURFACE
from .inputs import needs_objects
from .measured_base import measured_base
from .normals import shader_normal
from .terms import COLOR, FLOAT, VECTOR, PendingClosure

#: Cycles' bounds on the walk's anisotropy (``bssrdf_setup``): Random Walk, Random Walk (Skin).
G_BOUNDS = {SSS_RANDOM_WALK: (-0.99, 0.99), SSS_SKIN: (-0.99, 0.9)}
#: Radii below this (m) are no walk: Cycles renders such a channel diffuse (BSSRDF_MIN_RADIUS).
MIN_RADIUS_M = 1e-8


def _method(c, node, name):
    """``SSS_RANDOM_WALK`` or ``SSS_SKIN`` for Blender's method enum (Christensen-Burley is walked, and warned)."""
    method = getattr(node, name, "RANDOM_WALK")
    if method == "RANDOM_WALK_SKIN":
        return SSS_SKIN
    if method == "BURLEY":
        c.warn(node, "uses Christensen-Burley subsurface scattering; Prism renders it as Random Walk with the same "
                     "radius (light spreads further under the surface than in Cycles' Burley disk).")
    return SSS_RANDOM_WALK


def _constant(c, node, name, context, kind):
    """The socket's constant value; a linked one is warned and its unlinked value used."""
    value = c.known(c.value(node, name, context, kind))
    if value is None:
        socket = node.inputs[name]
        value = tuple(socket.default_value) if kind == VECTOR else float(socket.default_value)
        c.warn(node, f"has a varying {name}; Prism's random walk takes a constant one, so it uses the socket's "
                     f"value {value}.")
    return value


def _radius(c, node, context, radius_name, scale_name):
    """(largest radius in m, the radius over it as RGB) or None when every channel is below the minimum."""
    radius = [max(float(x), 0.0) for x in _constant(c, node, radius_name, context, VECTOR)]
    scale = max(float(_constant(c, node, scale_name, context, FLOAT)), 0.0)
    largest = max(radius) * scale
    if not largest >= MIN_RADIUS_M:
        return None
    if min(radius) * scale < MIN_RADIUS_M:
        c.warn(node, "has a subsurface radius channel near 0; Cycles renders that channel as diffuse reflection, "
                     "Prism walks with the smallest radius it can (1e-8 m), which looks the same.")
    return largest, tuple(max(x * scale / largest, MIN_RADIUS_M / largest) for x in radius)


def _subsurface_closure(c, node, context, weight, albedo, alpha, eta, method, g, measured=None, prefix=""):
    """Add the closure (``prefix``: "Subsurface " for the Principled BSDF's sockets); False where every radius
    channel is below the minimum."""
    radius = _radius(c, node, context, prefix + "Radius", prefix + "Scale")
    if radius is None:
        return False
    low, high = G_BOUNDS[method]
    g = min(max(float(g), low), high)
    needs_objects(c)  # the walk stays in the object it entered (``tracer.subsurface.walk``)
    normal = shader_normal(c, node, context)
    if normal is not None:
        c.warn(node, "bends the normal of its subsurface scattering; Prism enters along it, but where the walk leaves "
                     "the surface it shades with the smooth normal (Cycles: the bent one).")
    c.add_closure(PendingClosure(SUBSURFACE, weight, node, s0=albedo, s1=c.const(*radius[1]), alpha=alpha, eta=eta,
                                 normal=normal, subsurface=(radius[0], g, method), measured=measured))
    return True


def principled_subsurface(c, node, context, weight, base, alpha, eta):
    """Add the Principled BSDF's subsurface closure under ``weight``; returns the weight left for its diffuse
    lobe (× (1 − Subsurface Weight))."""
    amount = c.clamp01(c.value(node, "Subsurface Weight", context, FLOAT))
    if c.known(amount) == 0.0:
        return weight
    measured = measured_base(c)  # replaces the Base Color as the walk's albedo and in the tint
    clamped = None
    if measured is None:
        clamped = c.vector_math("MINIMUM", c.vector_math("MAXIMUM", base, c.const(0.0, 0.0, 0.0)),
                                c.const(1.0, 1.0, 1.0))
    method = _method(c, node, "subsurface_method")
    index = eta
    if method == SSS_SKIN:
        index = c.value(node, "Subsurface IOR", context, FLOAT)
    g = _constant(c, node, "Subsurface Anisotropy", context, FLOAT)
    added = _subsurface_closure(c, node, context, c.weighted(c.weighted(weight, scale=amount), colour=clamped), clamped,
                                alpha, index, method, g, measured, "Subsurface ")
    if not added:  # no radius: Cycles renders the closure as diffuse reflection of the same weight
        return weight
    return c.weighted(weight, scale=c.one_minus(amount))


def subsurface_scattering(c, node, context, weight):
    """Blender's Subsurface Scattering node."""
    measured = measured_base(c)
    colour = None
    if measured is None:
        colour = c.vector_math("MAXIMUM", c.value(node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0))
    method = _method(c, node, "falloff")
    alpha = c.clamp01(c.value(node, "Roughness", context, FLOAT))
    g = _constant(c, node, "Anisotropy", context, FLOAT)
    tinted = c.weighted(weight, colour=colour)
    if not _subsurface_closure(c, node, context, tinted, colour, alpha, c.value(node, "IOR", context, FLOAT), method,
                               g, measured):
        c.add_closure(PendingClosure(DIFFUSE, tinted, node, normal=shader_normal(c, node, context), measured=measured))
