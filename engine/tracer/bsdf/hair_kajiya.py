"""Blender's (legacy) Hair BSDF, Reflection and Transmission components, as Cycles 4.5 computes it
(``kernel/closure/bsdf_hair.h``): a Kajiya-Kay-like lobe in the tangent's frame whose value is its own pdf (a
sample's weight is 1, its Color is the closure's tint).

θ is measured from the plane across the tangent T (sin θ = dot(ω, T)); RoughnessU (r1) spreads θ as a Cauchy
(arctan-normalised) distribution about the half angle θh = (θi + θr)/2 shifted by the Offset; RoughnessV (r2)
spreads the azimuth: about the view's azimuth for Reflection (density cos(φ/(2 r2)) / (4 r2), |φ| ≤ π r2),
about the opposite azimuth for Transmission (a Cauchy of scale r2 trimmed to ±π/2). Evaluation returns nothing
on the wrong side of the shading normal (Reflection needs the light above it, Transmission below) or for light
within 0.001 rad of the tangent, and Reflection nothing beyond a right angle of azimuth: Cycles' sampler
produces such directions with weight 1 all the same (its eval and sample are not exactly consistent for
RoughnessV > 0.5), and Prism keeps that.

Directions here are Prism's: ``wo`` the view, ``wi`` the light, both in the material's frame (z = normal).
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..vec3 import cross, dot

REFLECTION = 1  # ``C_HAIR_MODEL`` values of the Hair BSDF's components (0 is Principled Hair, Chiang)
TRANSMISSION = 2
NEAR_TANGENT = 0.001  # light within this (rad) of the tangent carries nothing (Cycles)


@kernel
def _unit_across(w, t, along):
    x, y, z = w[0] - t[0] * along, w[1] - t[1] * along, w[2] - t[2] * along
    size = math.sqrt(x * x + y * y + z * z)
    if not size > 0.0:
        return (0.0, 0.0, 0.0)
    return (x / size, y / size, z / size)


@kernel
def _theta_terms(theta_r, offset, r1):
    a = math.atan(((0.5 * math.pi + theta_r) * 0.5 - offset) / r1)
    b = math.atan(((-0.5 * math.pi + theta_r) * 0.5 - offset) / r1)
    return a, b


@kernel
def _theta_pdf(t, r1, a, b, cos_theta_i):
    return r1 / (2.0 * (t * t + r1 * r1) * (a - b) * cos_theta_i)


@kernel
def kajiya_pdf(component, tangent, r1, r2, offset, wo, wi):
    """The lobe's value F (= its pdf, solid angle) for view ``wo`` and light ``wi`` (unit, material frame)."""
    if (component == REFLECTION) != (wi[2] >= 0.0):
        return 0.0
    iz = min(max(dot(tangent, wo), -1.0), 1.0)
    locy = _unit_across(wo, tangent, iz)
    theta_r = math.asin(iz)
    lz = min(max(dot(tangent, wi), -1.0), 1.0)
    ly = _unit_across(wi, tangent, lz)
    theta_i = math.asin(lz)
    cos_phi = min(max(dot(ly, locy), -1.0), 1.0)
    if 0.5 * math.pi - abs(theta_i) < NEAR_TANGENT:
        return 0.0
    a, b = _theta_terms(theta_r, offset, r1)
    t = 0.5 * (theta_i + theta_r) - offset
    theta_pdf = _theta_pdf(t, r1, a, b, math.cos(theta_i))
    if component == REFLECTION:
        if cos_phi < 0.0:
            return 0.0
        phi = math.acos(cos_phi) / r2
        phi = phi if abs(phi) < math.pi else math.pi
        return math.cos(0.5 * phi) * 0.25 / r2 * theta_pdf
    c = 2.0 * math.atan(0.5 * math.pi / r2)
    p = math.pi - math.acos(cos_phi)
    return r2 / (c * (p * p + r2 * r2)) * theta_pdf


@kernel
def kajiya_sample(component, tangent, r1, r2, offset, wo, u1, u2):
    """(wi, pdf): Cycles' ``bsdf_hair_reflection_sample`` / ``bsdf_hair_transmission_sample`` (weight 1)."""
    iz = min(max(dot(tangent, wo), -1.0), 1.0)
    locy = _unit_across(wo, tangent, iz)
    locx = cross(locy, tangent)
    theta_r = math.asin(iz)
    a, b = _theta_terms(theta_r, offset, r1)
    t = r1 * math.tan(u1 * (a - b) + b)
    theta_i = 2.0 * (t + offset) - theta_r
    cos_i, sin_i = math.cos(theta_i), math.sin(theta_i)
    theta_pdf = _theta_pdf(t, r1, a, b, cos_i)
    if component == REFLECTION:
        phi = 2.0 * math.asin(min(max(1.0 - 2.0 * u2, -1.0), 1.0)) * r2
        phi_pdf = math.cos(0.5 * phi) * 0.25 / r2
    else:
        c = 2.0 * math.atan(0.5 * math.pi / r2)
        p = r2 * math.tan(c * (u2 - 0.5))
        phi = p + math.pi
        phi_pdf = r2 / (c * (p * p + r2 * r2))
    cp, sp = math.cos(phi), math.sin(phi)
    wi = (cp * cos_i * locy[0] - sp * cos_i * locx[0] + sin_i * tangent[0],
          cp * cos_i * locy[1] - sp * cos_i * locx[1] + sin_i * tangent[1],
          cp * cos_i * locy[2] - sp * cos_i * locx[2] + sin_i * tangent[2])
    pdf = abs(phi_pdf * theta_pdf)
    if 0.5 * math.pi - abs(theta_i) < NEAR_TANGENT:
        pdf = 0.0
    return wi, pdf
