"""The clear sky of a spherical atmosphere, per wavelength: Nishita et al.'s single-scattering model.

T. Nishita, T. Sirai, K. Tadamura, E. Nakamae, "Display of the Earth taking into account atmospheric
scattering", SIGGRAPH 1993; the constants are those Blender's Nishita Sky Texture uses (Earth radius
6360 km, atmosphere up to 6420 km, exponential air and aerosol densities with scale heights 8 km and
1.2 km, a tent-shaped ozone layer from 10 to 40 km peaking at 25 km).

- Air (Rayleigh): β_R(λ) = 8π³ (n² - 1)² / (3 N λ⁴) with n = 1.000295 and N = 2.545e25 m⁻³ (no
  dispersion of n, as Nishita), phase 3 (1 + μ²) / 16π.
- Aerosols (Mie): scattering 2e-5 m⁻¹ at every wavelength, single-scattering albedo 0.9 (extinction
  2.22e-5 m⁻¹), the Cornette-Shanks phase function with g = 0.76.
- Ozone absorbs only: cross-sections measured at 233 K by Serdyuchenko et al. (2014, IUP Bremen),
  averaged in 10 nm bins from 360 nm, times the peak density of a 300 Dobson-unit column spread over
  the tent profile (300 · 2.687e20 / 15000 m⁻³).
- The Sun: a 5778 K blackbody filling its solid angle seen from 1 au (6.794e-5 sr) above the
  atmosphere.

``sky_radiance_table`` integrates the light the Sun scatters once toward the observer (transmittance
from the Sun to each point of the view ray and from there to the observer, Earth's shadow included)
on a grid of view directions, relative to the Sun's azimuth, at every 10 nm of 360-830 nm: W·m⁻²·sr⁻¹·nm⁻¹.
``sun_transmittance`` is the direct beam's transmittance (ozone included: Blender leaves ozone out of
the Sun disc). Directions below the horizon are the horizon faded as Blender does (``ground_fade``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..jit import kernel
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

EARTH_RADIUS_M = 6360e3
ATMOSPHERE_RADIUS_M = 6420e3
RAYLEIGH_SCALE_HEIGHT_M = 8e3
MIE_SCALE_HEIGHT_M = 1.2e3
MIE_SCATTERING_PER_M = 2e-5
MIE_ALBEDO = 0.9
MIE_G = 0.76
AIR_INDEX = 1.000295
AIR_NUMBER_DENSITY_PER_M3 = 2.545e25
OZONE_PEAK_HEIGHT_M = 25e3
OZONE_HALF_WIDTH_M = 15e3
OZONE_PEAK_DENSITY_PER_M3 = 300.0 * 2.687e20 / 15e3
SUN_TEMPERATURE_K = 5778.0
SUN_SOLID_ANGLE_SR = math.pi * (6.957e8 / 1.495978707e11) ** 2
MAX_ALTITUDE_M = 59999.0  # the observer stays inside the atmosphere

#: Ozone absorption cross-sections (m²) in 10 nm bins starting at 360 nm (Serdyuchenko et al. 2014, 233 K).
OZONE_CROSS_SECTION_M2 = np.array([
    1.18e-27, 2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27, 8.451e-27, 1.582e-26, 2.316e-26,
    3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25, 1.602e-25, 2.139e-25, 2.755e-25, 3.091e-25, 3.5e-25,
    4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25, 5.019e-25, 4.305e-25, 3.74e-25, 3.215e-25, 2.662e-25, 2.238e-25,
    1.852e-25, 1.473e-25, 1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26, 5.105e-26, 4.15e-26, 4.228e-26, 3.237e-26,
    2.451e-26, 2.801e-26, 2.534e-26, 1.624e-26, 1.465e-26, 2.078e-26, 1.383e-26, 7.105e-27])

#: Wavelengths of the sky tables (nm): every 10 nm of the visible range.
SKY_WAVELENGTHS_NM = np.arange(VISIBLE_MIN_NM, VISIBLE_MAX_NM + 0.5, 10.0)

VIEW_STEPS = 64
SUN_STEPS = 96  # midpoint rule: the aerosol column (1.2 km scale height) within 0.1 %


def rayleigh_scattering_per_m(wavelength_nm):
    """Sea-level scattering coefficient of air (m⁻¹)."""
    wavelength_m = np.asarray(wavelength_nm, np.float64) * 1e-9
    return 8.0 * math.pi**3 * (AIR_INDEX**2 - 1.0) ** 2 / (3.0 * AIR_NUMBER_DENSITY_PER_M3 * wavelength_m**4)


def ozone_absorption_per_m(wavelength_nm):
    """Absorption coefficient (m⁻¹) at the ozone layer's peak density (bins' values at their centres)."""
    centres = 365.0 + 10.0 * np.arange(len(OZONE_CROSS_SECTION_M2))
    return np.interp(wavelength_nm, centres, OZONE_CROSS_SECTION_M2) * OZONE_PEAK_DENSITY_PER_M3


def solar_irradiance(wavelength_nm):
    """Spectral irradiance of the Sun above the atmosphere (W·m⁻²·nm⁻¹)."""
    from .blackbody import planck_spectral_radiance

    return planck_spectral_radiance(wavelength_nm, SUN_TEMPERATURE_K) * SUN_SOLID_ANGLE_SR


def coefficients(wavelength_nm, air=1.0, dust=1.0, ozone=1.0):
    """[L, 4]: air scattering, aerosol scattering, aerosol extinction, ozone absorption (m⁻¹ at the
    reference densities, scaled by the relative densities)."""
    wavelength_nm = np.asarray(wavelength_nm, np.float64)
    out = np.zeros((len(wavelength_nm), 4))
    out[:, 0] = air * rayleigh_scattering_per_m(wavelength_nm)
    out[:, 1] = dust * MIE_SCATTERING_PER_M
    out[:, 2] = dust * MIE_SCATTERING_PER_M / MIE_ALBEDO
    out[:, 3] = ozone * ozone_absorption_per_m(wavelength_nm)
    return out


@kernel
def _densities(height_m):
    ozone = max(0.0, 1.0 - abs(height_m - OZONE_PEAK_HEIGHT_M) / OZONE_HALF_WIDTH_M)
    return math.exp(-height_m / RAYLEIGH_SCALE_HEIGHT_M), math.exp(-height_m / MIE_SCALE_HEIGHT_M), ozone


@kernel
def _exit_distance(px, py, pz, dx, dy, dz):
    """Distance from a point inside the atmosphere to its outer boundary along a unit direction."""
    b = px * dx + py * dy + pz * dz
    c = px * px + py * py + pz * pz - ATMOSPHERE_RADIUS_M * ATMOSPHERE_RADIUS_M
    return -b + math.sqrt(max(b * b - c, 0.0))


@kernel
def _hits_ground(px, py, pz, dx, dy, dz):
    b = px * dx + py * dy + pz * dz
    if b >= 0.0:
        return False
    c = px * px + py * py + pz * pz - EARTH_RADIUS_M * EARTH_RADIUS_M
    return b * b - c >= 0.0


@kernel
def column_densities(px, py, pz, dx, dy, dz, steps):
    """Air, aerosol and ozone columns (m, at reference density) from a point to space along a unit
    direction: midpoint rule on segments growing quadratically away from the point, where the density
    changes fastest."""
    length = _exit_distance(px, py, pz, dx, dy, dz)
    air = aerosol = ozone = 0.0
    for k in range(steps):
        s0 = length * (k / steps) ** 2
        s1 = length * ((k + 1) / steps) ** 2
        s = 0.5 * (s0 + s1)
        qx, qy, qz = px + s * dx, py + s * dy, pz + s * dz
        height = math.sqrt(qx * qx + qy * qy + qz * qz) - EARTH_RADIUS_M
        r, m, o = _densities(height)
        air += r * (s1 - s0)
        aerosol += m * (s1 - s0)
        ozone += o * (s1 - s0)
    return air, aerosol, ozone


@kernel
def _phase_rayleigh(mu):
    return 3.0 / (16.0 * math.pi) * (1.0 + mu * mu)


@kernel
def _phase_mie(mu):
    g2 = MIE_G * MIE_G
    return 3.0 * (1.0 - g2) * (1.0 + mu * mu) / (8.0 * math.pi * (2.0 + g2) * (1.0 + g2 - 2.0 * MIE_G * mu) ** 1.5)


SUN_TABLE = (96, 256)  # heights x directions of the table of columns toward the Sun


@kernel
def _sun_columns(out):
    """out[h, x] = columns toward the Sun from height (60 km) (h/(H-1))² at the point whose vertical
    makes cos μ = μ_h + (1 - μ_h) (x/(X-1))² with the Sun (μ_h: the horizon's cos at that height)."""
    heights, columns = out.shape[0], out.shape[1]
    for h in range(heights):
        r = EARTH_RADIUS_M + MAX_ALTITUDE_M * (h / (heights - 1)) ** 2
        mu_h = -math.sqrt(max(1.0 - (EARTH_RADIUS_M / r) ** 2, 0.0))
        for x in range(columns):
            mu = min(mu_h + (1.0 - mu_h) * (x / (columns - 1)) ** 2, 1.0)
            sin_mu = math.sqrt(max(1.0 - mu * mu, 0.0))
            air, aerosol, ozone = column_densities(0.0, 0.0, r, sin_mu, 0.0, mu, SUN_STEPS)
            out[h, x, 0] = air
            out[h, x, 1] = aerosol
            out[h, x, 2] = ozone


@kernel
def _columns_toward_sun(table, px, py, pz, sx, sy, sz):
    """Columns from point p toward the Sun (unit s) interpolated in ``_sun_columns``' table; (-1, 0, 0)
    when the Earth hides the Sun."""
    r = math.sqrt(px * px + py * py + pz * pz)
    mu = (px * sx + py * sy + pz * sz) / r
    mu_h = -math.sqrt(max(1.0 - (EARTH_RADIUS_M / r) ** 2, 0.0))
    if mu < mu_h:
        return -1.0, 0.0, 0.0
    heights, columns = table.shape[0], table.shape[1]
    fh = math.sqrt(min(max((r - EARTH_RADIUS_M) / MAX_ALTITUDE_M, 0.0), 1.0)) * (heights - 1)
    fx = math.sqrt(min((mu - mu_h) / (1.0 - mu_h), 1.0)) * (columns - 1)
    h0 = min(int(fh), heights - 2)
    x0 = min(int(fx), columns - 2)
    wh = fh - h0
    wx = fx - x0
    out0 = out1 = out2 = 0.0
    for h, a in ((h0, 1.0 - wh), (h0 + 1, wh)):
        for x, b in ((x0, 1.0 - wx), (x0 + 1, wx)):
            w = a * b
            out0 += w * table[h, x, 0]
            out1 += w * table[h, x, 1]
            out2 += w * table[h, x, 2]
    return out0, out1, out2


@kernel
def _single_scattering(elevations, azimuths, sun_elevation, altitude_m, density, coeff, irradiance, sun_table, out):
    """out[e, a, l] = radiance scattered once toward an observer at ``altitude_m`` looking at elevation
    ``elevations[e]`` and azimuth ``azimuths[a]`` from the Sun (W m⁻² sr⁻¹ nm⁻¹)."""
    sx, sy, sz = math.cos(sun_elevation), 0.0, math.sin(sun_elevation)
    oz = EARTH_RADIUS_M + altitude_m
    count = coeff.shape[0]
    for e in range(elevations.shape[0]):
        for a in range(azimuths.shape[0]):
            ce = math.cos(elevations[e])
            dx, dy, dz = ce * math.cos(azimuths[a]), ce * math.sin(azimuths[a]), math.sin(elevations[e])
            mu = dx * sx + dy * sy + dz * sz
            pr = _phase_rayleigh(mu)
            pm = _phase_mie(mu)
            length = _exit_distance(0.0, 0.0, oz, dx, dy, dz)
            view_air = view_aerosol = view_ozone = 0.0
            for l in range(count):
                out[e, a, l] = 0.0
            for k in range(VIEW_STEPS):
                s0 = length * (k / VIEW_STEPS) ** 2
                s1 = length * ((k + 1) / VIEW_STEPS) ** 2
                ds = s1 - s0
                s = 0.5 * (s0 + s1)
                px, py, pz = s * dx, s * dy, oz + s * dz
                height = math.sqrt(px * px + py * py + pz * pz) - EARTH_RADIUS_M
                r, m, o = _densities(height)
                r *= density[0]
                m *= density[1]
                o *= density[2]
                # Transmittance to the observer up to the middle of this segment.
                air_here = view_air + 0.5 * r * ds
                aerosol_here = view_aerosol + 0.5 * m * ds
                ozone_here = view_ozone + 0.5 * o * ds
                view_air += r * ds
                view_aerosol += m * ds
                view_ozone += o * ds
                sun_air, sun_aerosol, sun_ozone = _columns_toward_sun(sun_table, px, py, pz, sx, sy, sz)
                if sun_air < 0.0:
                    continue
                air_total = air_here + density[0] * sun_air
                aerosol_total = aerosol_here + density[1] * sun_aerosol
                ozone_total = ozone_here + density[2] * sun_ozone
                for l in range(count):
                    depth = coeff[l, 0] * air_total + coeff[l, 2] * aerosol_total + coeff[l, 3] * ozone_total
                    scattered = coeff[l, 0] * r * pr + coeff[l, 1] * m * pm
                    out[e, a, l] += math.exp(-depth) * scattered * irradiance[l] * ds


@dataclass
class SkyTables:
    """The sky of one ``scene.Sky``: ``radiance`` float32 [E, A, L] (W m⁻² sr⁻¹ nm⁻¹) at elevations
    (π/2) (e/(E-1))² above the horizon and azimuths π (a/(A-1))² from the Sun's, at
    ``SKY_WAVELENGTHS_NM``; ``sun_radiance`` [L]: the disc's mean radiance (before limb darkening
    and Blender's Sun Intensity), 0 when the Sun is below the horizon."""

    radiance: np.ndarray
    sun_radiance: np.ndarray
    sun_transmittance: np.ndarray


def sky_tables(sky, elevations: int = 128, azimuths: int = 128) -> SkyTables:
    """Tabulate the sky of a ``scene.Sky`` (relative densities as Blender's, multiplied into the
    reference coefficients; altitude clamped to 0-59999 m as Blender does)."""
    altitude = float(np.clip(sky.altitude_m, 0.0, MAX_ALTITUDE_M))
    density = np.array([sky.air_density, sky.dust_density, sky.ozone_density], np.float64)
    coeff = coefficients(SKY_WAVELENGTHS_NM)
    irradiance = solar_irradiance(SKY_WAVELENGTHS_NM)
    elevation = 0.5 * math.pi * np.linspace(0.0, 1.0, elevations) ** 2
    azimuth = math.pi * np.linspace(0.0, 1.0, azimuths) ** 2
    sun_table = _sun_column_table()
    table = np.zeros((elevations, azimuths, len(SKY_WAVELENGTHS_NM)))
    _single_scattering(elevation, azimuth, float(sky.sun_elevation_rad), altitude, density, coeff, irradiance,
                       sun_table, table)
    transmittance = sun_transmittance(float(sky.sun_elevation_rad), altitude, density)
    half = 0.5 * float(sky.sun_size_rad)
    solid_angle = 2.0 * math.pi * (1.0 - math.cos(half)) if half > 0 else 0.0
    visible = sky.sun_elevation_rad + half > -horizon_dip(altitude) and solid_angle > 0
    sun = irradiance * transmittance / solid_angle if visible else np.zeros_like(irradiance)
    return SkyTables(table.astype(np.float32), sun, transmittance)


_SUN_COLUMNS = []


def _sun_column_table() -> np.ndarray:
    """The columns toward the Sun from every height and direction (the same for every sky)."""
    if not _SUN_COLUMNS:
        table = np.zeros(SUN_TABLE + (3,))
        _sun_columns(table)
        _SUN_COLUMNS.append(table)
    return _SUN_COLUMNS[0]


def horizon_dip(altitude_m: float) -> float:
    """How far below the horizontal the Earth's edge is seen from ``altitude_m`` (rad)."""
    return math.acos(EARTH_RADIUS_M / (EARTH_RADIUS_M + max(altitude_m, 0.0)))


def sun_transmittance(sun_elevation_rad: float, altitude_m: float, density) -> np.ndarray:
    """Transmittance [L] of the direct beam from the Sun at ``sun_elevation_rad`` to the observer
    (0 when the Earth hides the Sun's centre)."""
    d = (math.cos(sun_elevation_rad), 0.0, math.sin(sun_elevation_rad))
    oz = EARTH_RADIUS_M + altitude_m
    if _hits_ground(0.0, 0.0, oz, *d):
        return np.zeros(len(SKY_WAVELENGTHS_NM))
    air, aerosol, ozone = column_densities(0.0, 0.0, oz, d[0], d[1], d[2], 4 * SUN_STEPS)
    coeff = coefficients(SKY_WAVELENGTHS_NM)
    return np.exp(-(coeff[:, 0] * air * density[0] + coeff[:, 2] * aerosol * density[1]
                    + coeff[:, 3] * ozone * density[2]))


@kernel
def ground_fade(z):
    """Blender's ground below the horizon: the horizon's radiance × (1 - 2.5 sin|elevation|)³, 0 below
    sin|elevation| = 0.4."""
    if z >= 0.0:
        return 1.0
    f = 1.0 + 2.5 * z
    return f * f * f if f > 0.0 else 0.0
