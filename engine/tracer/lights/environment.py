"""The world's background as a light: a constant colour, an equirectangular image or a Nishita sky.

Escaping rays see it (``footprint`` once per ray, then ``value`` per wavelength) and light sampling
draws directions from it (``sample_li``,
density ``pdf_li``; MIS against BSDF sampling on escapes). Radiance is spectral:

- constant: the RGB emitter spectrum of the colour (``spectra.table``); not light-sampled: for a
  constant background the BSDF's own sampling is already proportional to the integrand (up to
  visibility, which no background sampling knows either), so a light sample would only cost a ray;
- image: each texel an illuminant spectrum (``spectra.illuminant_texels``: scale · S(λ) · D65(λ)),
  looked up as Blender does (bilinear between texel centres, columns wrapping, or the closest texel),
  sampled from the texel grid (``sphere_distribution``) with cell weights the luminance averaged over
  each cell — the bilinear image's exact cell mean, so every direction the image lights has density;
- sky: ``spectra.atmosphere``'s table, per wavelength, ×∫ȳ dλ (Prism's emission units: XYZ is
  ∫ L cmf dλ / ∫ ȳ dλ, Blender's sky ∫ L cmf dλ); sampled from a 256 x 128 grid of its luminance (the
  largest of 3 x 3 looks in each cell). Its Sun disc is a separate distant light (``sky_sun_row``).

Blender's Mapping node is a linear map M from world to texture directions (``World.to_texture``):
radiance is looked up at M d / |M d|, and densities carry the Jacobian |det M| / |M d|³.

``EnvironmentArrays``: ``kind`` (``ENV_*``), ``strength``, ``spectrum`` (constant's spectrum id),
``d65`` (spectrum id of D65), ``closest`` (1: nearest texel), ``to_texture`` / ``from_texture``
float64 [3, 3], ``det``, ``texels`` float32 [H, W, 4], ``sky`` float32 [E, A, L], ``sun_phi`` (the
sky's Sun azimuth, atan2 in the texture frame), ``distribution`` (``SphereDistribution``).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..errors import PrismInputError
from ..jit import inlined, kernel
from ..spectra.atmosphere import ground_fade
from ..spectra.illuminant_texels import texel_reflectance
from ..spectra.table import spectrum_value
from ..spectra.trapezoid import trapezoid
from ..spectra.wavelengths import VISIBLE_RANGE_NM
from .row import L_CAMERA, L_COS_MAX, L_KIND, L_LIMB, L_NX, L_NZ, L_ONE_MINUS_COS, L_SCALE, L_SPECTRUM, LIGHT_ROW, SUN_DISK
from .sphere_distribution import SphereDistribution, build_sphere_distribution, direction_pdf, sample_direction

ENV_NONE = 0
ENV_CONSTANT = 1
ENV_IMAGE = 2
ENV_SKY = 3

SKY_GRID = (128, 256)  # rows x columns of the sky's sampling grid
SKY_SUN_LIMB_DARKENING = 0.6  # Blender's: radiance × (1 - 0.6 (1 - μ))

#: What ``build_environment`` makes: ``arrays`` (``EnvironmentArrays``), ``integral`` (∫ luminance dω for
#: light selection; 0 when not light-sampled), ``sun_rows`` (the sky's Sun disc as light rows) and
#: ``guide_spectrum`` (a spectrum id of the background's mean spectrum for the wavelength guide; -1: none).
EnvironmentBuild = namedtuple("EnvironmentBuild", "arrays integral sun_rows guide_spectrum")

EnvironmentArrays = namedtuple(
    "EnvironmentArrays",
    "kind strength spectrum d65 closest to_texture from_texture det texels sky sun_phi distribution",
)

_LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


@kernel
def texture_direction(env, d):
    """(unit texture-frame direction M d / |M d|, |M d|) of the world direction ``d``."""
    m = env.to_texture
    x = m[0, 0] * d[0] + m[0, 1] * d[1] + m[0, 2] * d[2]
    y = m[1, 0] * d[0] + m[1, 1] * d[1] + m[1, 2] * d[2]
    z = m[2, 0] * d[0] + m[2, 1] * d[1] + m[2, 2] * d[2]
    n = math.sqrt(x * x + y * y + z * z)
    if not n > 0.0:
        return (0.0, 0.0, 1.0), 1.0
    return (x / n, y / n, z / n), n


@kernel
def _image_footprint(env, t):
    """Bilinear (or closest) footprint of texture direction ``t`` in the image: (r0, r1, c0, c1, fr, fc)."""
    rows = env.texels.shape[0]
    columns = env.texels.shape[1]
    u = (math.pi - math.atan2(t[1], t[0])) / (2.0 * math.pi)
    v = math.acos(min(max(t[2], -1.0), 1.0)) / math.pi
    x = u * columns - 0.5
    y = v * rows - 0.5
    if env.closest:
        x = math.floor(x + 0.5)
        y = math.floor(y + 0.5)
    c0 = int(math.floor(x))
    r0 = int(math.floor(y))
    fc = x - c0
    fr = y - r0
    c0 = c0 % columns
    c1 = (c0 + 1) % columns
    r1 = min(max(r0 + 1, 0), rows - 1)
    r0 = min(max(r0, 0), rows - 1)
    return r0, r1, c0, c1, fr, fc


@kernel
def _sky_footprint(env, t):
    """Footprint in the sky table (elevation rows, azimuth-from-the-Sun columns) and the ground fade."""
    rows = env.sky.shape[0]
    columns = env.sky.shape[1]
    z = min(max(t[2], -1.0), 1.0)
    elevation = math.asin(z) if z > 0.0 else 0.0
    azimuth = abs(math.atan2(t[1], t[0]) - env.sun_phi)
    if azimuth > math.pi:
        azimuth = 2.0 * math.pi - azimuth
    y = math.sqrt(min(elevation / (0.5 * math.pi), 1.0)) * (rows - 1)
    x = math.sqrt(min(azimuth / math.pi, 1.0)) * (columns - 1)
    r0 = min(int(y), rows - 2) if rows > 1 else 0
    c0 = min(int(x), columns - 2) if columns > 1 else 0
    return r0, min(r0 + 1, rows - 1), c0, min(c0 + 1, columns - 1), y - r0, x - c0, ground_fade(z)


@kernel
def _texel_value(env, r, c, wavelength_nm):
    texel = env.texels[r, c]
    return texel[3] * texel_reflectance(texel[0], texel[1], texel[2], wavelength_nm)


@kernel
def footprint(env, d):
    """Where world direction ``d`` looks up the background, computed once for all wavelengths:
    (r0, r1, c0, c1, fr, fc, fade) — rows, columns and weights in the image or the sky table."""
    t, _ = texture_direction(env, d)
    if env.kind == ENV_IMAGE:
        r0, r1, c0, c1, fr, fc = _image_footprint(env, t)
        return r0, r1, c0, c1, fr, fc, 1.0
    if env.kind == ENV_SKY:
        return _sky_footprint(env, t)
    return 0, 0, 0, 0, 0.0, 0.0, 1.0


@kernel
def value(env, spectra, fp, wavelength_nm):
    """The background's spectral radiance at ``wavelength_nm`` along the direction of footprint ``fp``."""
    if env.kind == ENV_CONSTANT:
        return env.strength * spectrum_value(spectra, env.spectrum, wavelength_nm)
    r0, r1, c0, c1, fr, fc, fade = fp
    if env.kind == ENV_IMAGE:
        s = ((1.0 - fr) * ((1.0 - fc) * _texel_value(env, r0, c0, wavelength_nm)
                           + fc * _texel_value(env, r0, c1, wavelength_nm))
             + fr * ((1.0 - fc) * _texel_value(env, r1, c0, wavelength_nm)
                     + fc * _texel_value(env, r1, c1, wavelength_nm)))
        return env.strength * s * spectrum_value(spectra, env.d65, wavelength_nm)
    if env.kind == ENV_SKY:
        count = env.sky.shape[2]
        x = min(max((wavelength_nm - 360.0) / 10.0, 0.0), count - 1.0)
        l0 = min(int(x), count - 2)
        fl = x - l0
        sky = env.sky
        total = 0.0
        for ll, wl in ((l0, 1.0 - fl), (l0 + 1, fl)):
            total += wl * ((1.0 - fr) * ((1.0 - fc) * sky[r0, c0, ll] + fc * sky[r0, c1, ll])
                           + fr * ((1.0 - fc) * sky[r1, c0, ll] + fc * sky[r1, c1, ll]))
        return env.strength * fade * total
    return 0.0


@inlined
def radiance(env, spectra, d, wavelength_nm, out):
    """``out[k]`` = the background's spectral radiance along world direction ``d`` at
    ``wavelength_nm[k]``."""
    fp = footprint(env, d)
    for k in range(wavelength_nm.shape[0]):
        out[k] = value(env, spectra, fp, wavelength_nm[k])


@kernel
def sample_li(env, u1, u2):
    """(world direction, solid-angle density) of a direction drawn toward an image or sky background."""
    t, pdf = sample_direction(env.distribution, u1, u2)
    m = env.from_texture
    x = m[0, 0] * t[0] + m[0, 1] * t[1] + m[0, 2] * t[2]
    y = m[1, 0] * t[0] + m[1, 1] * t[1] + m[1, 2] * t[2]
    z = m[2, 0] * t[0] + m[2, 1] * t[1] + m[2, 2] * t[2]
    n = math.sqrt(x * x + y * y + z * z)
    d = (x / n, y / n, z / n)
    _, stretch = texture_direction(env, d)
    return d, pdf * env.det / (stretch * stretch * stretch)


@kernel
def pdf_li(env, d):
    """Solid-angle density of ``sample_li`` for world direction ``d``."""
    t, stretch = texture_direction(env, d)
    return direction_pdf(env.distribution, t) * env.det / (stretch * stretch * stretch)


# ---------------------------------------------------------------------------------------------- build


def _blurred_mean(luminance, closest: bool) -> np.ndarray:
    """Mean of the bilinearly interpolated image over each texel's cell: a [1, 6, 1] / 8 filter in
    both directions (columns wrap, rows clamp); the texels themselves for closest lookup."""
    if closest:
        return luminance
    horizontal = (np.roll(luminance, 1, axis=1) + 6.0 * luminance + np.roll(luminance, -1, axis=1)) / 8.0
    up = np.concatenate([horizontal[:1], horizontal[:-1]])
    down = np.concatenate([horizontal[1:], horizontal[-1:]])
    return (up + 6.0 * horizontal + down) / 8.0


def _mapping(world):
    m = np.asarray(world.to_texture, np.float64).reshape(3, 3)
    det = float(np.linalg.det(m)) if np.isfinite(m).all() else 0.0
    if not abs(det) > 1e-12 * max(float(np.abs(m).max()), 1e-300) ** 3:
        raise PrismInputError(
            f"World '{world.name}': the texture mapping is singular (a Mapping node scale of 0?): "
            "give every axis a non-zero scale."
        )
    return np.ascontiguousarray(m), np.ascontiguousarray(np.linalg.inv(m)), abs(det)


def _empty_distribution() -> SphereDistribution:
    return build_sphere_distribution(np.ones((1, 1)))


def _arrays(kind, strength, spectrum, d65, closest, mapping, texels, sky, sun_phi, distribution):
    to_texture, from_texture, det = mapping
    return EnvironmentArrays(int(kind), float(strength), int(spectrum), int(d65), int(closest), to_texture,
                             from_texture, float(det), texels, sky, float(sun_phi), distribution)


def no_environment() -> EnvironmentArrays:
    """The tables of a black world (nothing to see or sample)."""
    return _arrays(ENV_NONE, 0.0, 0, 0, 0, (np.eye(3), np.eye(3), 1.0), np.zeros((1, 1, 4), np.float32),
                   np.zeros((1, 1, 2), np.float32), 0.0, _empty_distribution())


def build_environment(world, spectra) -> EnvironmentBuild:
    """The background of a ``scene.World``; ``spectra`` is the render's ``SpectrumTable``."""
    from ..scene import SpectrumSpec

    if world is None or world.is_black():
        return EnvironmentBuild(no_environment(), 0.0, [], -1)
    strength = float(world.strength)
    if world.kind == "constant":
        color = tuple(float(c) for c in world.color)
        spectrum = spectra.emission(SpectrumSpec(kind="rgb", rgb=color))
        env = _arrays(ENV_CONSTANT, strength, spectrum, 0, 0, (np.eye(3), np.eye(3), 1.0),
                      np.zeros((1, 1, 4), np.float32), np.zeros((1, 1, 2), np.float32), 0.0, _empty_distribution())
        return EnvironmentBuild(env, 0.0, [], spectrum)
    mapping = _mapping(world)
    if world.kind == "image":
        return _image_environment(world, spectra, strength, mapping)
    if world.kind == "sky":
        return _sky_environment(world, spectra, strength, mapping)
    raise PrismInputError(f"World '{world.name}': unknown background kind '{world.kind}'.")


def _image_environment(world, spectra, strength, mapping):
    from ..scene import SpectrumSpec
    from ..spectra.illuminant_texels import illuminant_texels
    from .sphere_distribution import cell_solid_angles

    rgb = np.asarray(world.image_rgb, np.float32)
    if rgb.ndim != 3 or rgb.shape[2] != 3 or rgb.shape[0] < 1 or rgb.shape[1] < 1:
        raise PrismInputError(f"World '{world.name}': the environment image must be an [H, W, 3] array.")
    rgb = np.maximum(np.nan_to_num(rgb, nan=0.0, posinf=0.0, neginf=0.0), 0.0)
    closest = world.interpolation == "closest"
    texels = np.ascontiguousarray(illuminant_texels(rgb))
    mean = _blurred_mean(rgb.astype(np.float64) @ _LUMINANCE, closest) * strength
    distribution = build_sphere_distribution(mean)
    integral = float((mean * cell_solid_angles(*mean.shape)[:, None]).sum())
    env = _arrays(ENV_IMAGE, strength, 0, spectra.d65(), closest, mapping, texels, np.zeros((1, 1, 2), np.float32),
                  0.0, distribution)
    # The wavelength guide follows the image's mean colour (weighted by solid angle), as an RGB emitter.
    weights = cell_solid_angles(*rgb.shape[:2])[:, None, None]
    mean_rgb = tuple(float(c) for c in (rgb * weights).sum(axis=(0, 1)) / weights.sum() / rgb.shape[1])
    guide = spectra.emission(SpectrumSpec(kind="rgb", rgb=mean_rgb)) if max(mean_rgb) > 0 else -1
    return EnvironmentBuild(env, integral, [], guide)


def _sky_environment(world, spectra, strength, mapping):
    from ..spectra import cie
    from ..spectra.atmosphere import SKY_WAVELENGTHS_NM, sky_tables
    from .sphere_distribution import cell_solid_angles

    sky = world.sky
    tables = sky_tables(sky)
    y_integral = float(cie.CMF_Y_INTEGRAL)
    table = np.ascontiguousarray(tables.radiance * np.float32(y_integral))
    sun_phi = 0.5 * math.pi - float(sky.sun_rotation_rad)
    env = _arrays(ENV_SKY, strength, 0, 0, 0, mapping, np.zeros((1, 1, 4), np.float32), table,
                  math.atan2(math.sin(sun_phi), math.cos(sun_phi)), _empty_distribution())
    ybar = cie.cie_xyz_cmf(SKY_WAVELENGTHS_NM)[:, 1]
    luminance = (table.astype(np.float64) * ybar).sum(axis=2) * 10.0 / y_integral  # Y per table entry
    rows, columns = SKY_GRID
    grid = np.zeros((rows, columns))
    _sky_luminance_grid(env, np.ascontiguousarray(luminance), grid)
    grid *= strength
    env = env._replace(distribution=build_sphere_distribution(grid))
    integral = float((grid * cell_solid_angles(rows, columns)[:, None]).sum())
    # The wavelength guide follows the sky's spectrum averaged over the upper hemisphere (luminance 1).
    mean = table.astype(np.float64).mean(axis=(0, 1))
    mean_luminance = float((mean * ybar).sum() * 10.0 / y_integral)
    guide = spectra.tabulated(("sky mean", tuple(np.round(mean / mean_luminance, 12))), float(SKY_WAVELENGTHS_NM[0]),
                              10.0, mean / mean_luminance, support_nm=VISIBLE_RANGE_NM) if mean_luminance > 0 else -1
    return EnvironmentBuild(env, integral, _sky_sun_rows(world, spectra, strength, tables, mapping), guide)


@kernel
def _sky_luminance_grid(env, luminance, grid):
    """grid[r, c] = the largest sky luminance of 3 x 3 looks spread over cell (r, c) (texture frame)."""
    rows, columns = grid.shape
    for r in range(rows):
        for c in range(columns):
            best = 0.0
            for a in range(3):
                theta = math.pi * (r + 0.05 + 0.45 * a) / rows
                for b in range(3):
                    u = (c + 0.05 + 0.45 * b) / columns
                    phi = math.pi - 2.0 * math.pi * u
                    t = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
                    r0, r1, c0, c1, fr, fc, fade = _sky_footprint(env, t)
                    y = fade * ((1.0 - fr) * ((1.0 - fc) * luminance[r0, c0] + fc * luminance[r0, c1])
                                + fr * ((1.0 - fc) * luminance[r1, c0] + fc * luminance[r1, c1]))
                    best = max(best, y)
            grid[r, c] = best


def _sky_sun_rows(world, spectra, strength, tables, mapping):
    """The sky's Sun disc as a distant light (limb-darkened, seen by camera rays) in world space."""
    from ..spectra import cie
    from ..spectra.atmosphere import SKY_WAVELENGTHS_NM

    sky = world.sky
    if not (sky.sun_disc and sky.sun_intensity > 0 and sky.sun_size_rad > 0 and tables.sun_radiance.max() > 0):
        return []
    spectrum = tables.sun_radiance * float(cie.CMF_Y_INTEGRAL)
    luminance = float(trapezoid(spectrum * cie.cie_xyz_cmf(SKY_WAVELENGTHS_NM)[:, 1], SKY_WAVELENGTHS_NM)
                      / float(cie.CMF_Y_INTEGRAL))
    sid = spectra.tabulated(("sky sun", tuple(np.round(spectrum / luminance, 12))), float(SKY_WAVELENGTHS_NM[0]),
                            10.0, spectrum / luminance, support_nm=VISIBLE_RANGE_NM)
    e, rot = float(sky.sun_elevation_rad), float(sky.sun_rotation_rad)
    toward_sun = np.array([math.cos(e) * math.sin(rot), math.cos(e) * math.cos(rot), math.sin(e)])
    world_dir = mapping[1] @ toward_sun
    world_dir /= np.linalg.norm(world_dir)
    half = 0.5 * float(sky.sun_size_rad)
    row = np.zeros(LIGHT_ROW)
    row[L_KIND] = SUN_DISK
    row[L_SPECTRUM] = sid
    row[L_NX:L_NZ + 1] = world_dir
    row[L_ONE_MINUS_COS] = 2.0 * math.sin(half / 2.0) ** 2
    row[L_COS_MAX] = 1.0 - row[L_ONE_MINUS_COS]
    row[L_SCALE] = strength * float(sky.sun_intensity) * luminance
    row[L_LIMB] = SKY_SUN_LIMB_DARKENING
    row[L_CAMERA] = 1.0
    return [row]
