"""``MediumSpec``: a medium as the export layer hands it to the tracer (Blender's settings).

Cycles' volume closures, per unit length (metres): Volume Scatter adds scattering σ_s = density × colour,
Volume Absorption adds absorption σ_a = density × (1 - colour), Principled Volume adds σ_s = density ×
colour and σ_a = density × max(1 - colour, 0) × max(1 - sqrt(absorption colour), 0); emission (Principled's
Emission Strength × Emission Color) is radiance added per metre travelled, not scaled by density, and so is
its blackbody emission, σ_SB 10⁻⁶ / π × mix(1, T⁴, Blackbody Intensity) × Blackbody Tint × the blackbody
colour of luminance 1 at Temperature T. Prism upsamples each colour to a reflectance spectrum
(``spectra.rgb_to_spectrum``) and uses Planck's law for the blackbody, so σ_s, σ_a and the emission are
functions of wavelength. A Volume object's Temperature Attribute grid multiplies the Temperature point
by point (``temperature_grid``).
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class MediumSpec:
    """``scatter``: (density, rgb) terms, σ_s(λ) = Σ density × R_rgb(λ); ``absorb``: (density, rgb, ...)
    terms, σ_a(λ) = Σ density × Π (1 - R_rgb(λ)) over the term's colours; ``anisotropy``: the
    Henyey-Greenstein g of the scattering (-1..1); ``emission``: (strength, rgb, temperature_k) terms of
    emitted radiance per metre: strength × the RGB emission of ``rgb`` when ``temperature_k`` is None, else
    strength × the luminance-1 blackbody spectrum at ``temperature_k`` tinted by ``rgb``; ``density_grid``
    (a ``density_grid.DensityGrid``), when set, multiplies σ_s and σ_a point by point (a grid medium: delta
    and ratio tracking), else the medium is homogeneous. ``blackbody``: the Principled Volumes' blackbody
    settings as (weight, blackbody intensity, temperature_k, tint rgb), kept beside their ``emission`` term
    (evaluated at temperature_k) for a ``temperature_grid`` (a ``DensityGrid``, with a ``density_grid``
    only): when set, the temperature is temperature_k × max(grid value, 0) point by point, as Cycles'
    Temperature Attribute, and those terms replace the blackbody terms of ``emission``
    (``temperature_emission``). ``density_varies``: the density terms are per unit of a density the material's
    program computes per point (``ShaderProgram.volume_density``), which the render bakes onto a
    ``density_grid`` over the mesh (``baked_density``) at voxels of Cycles' step size over ``step_rate``
    (Material ▸ Settings ▸ Volume ▸ Step Rate); ``density_attributes`` {name: colour slot}: the attributes that
    density reads (on a Volume object, its grids of those names); ``voxel_inputs`` (a
    ``voxel_inputs.VoxelInputs``) where the density is baked on a Volume object's voxels instead of a grid over
    a mesh. ``phase``: the scattering's phase function as a mixture of lobes (weight, kind, parameters)
    (``phase_functions``), tabulated; empty: Henyey-Greenstein of ``anisotropy``. ``emission_field``:
    (weight, rgb) terms of emitted radiance per metre per unit of an Emission Strength the material's program
    computes per point (``ShaderProgram.volume_emission``), baked like the density to ``strength_grid`` (its
    attributes ``emission_attributes``); the emission is then the ``emission`` terms plus the strength × these
    (``temperature_emission``)."""

    name: str
    scatter: list = field(default_factory=list)
    absorb: list = field(default_factory=list)
    anisotropy: float = 0.0
    emission: list = field(default_factory=list)
    density_grid: object = None
    blackbody: list = field(default_factory=list)
    temperature_grid: object = None
    density_varies: bool = False
    step_rate: float = 1.0
    density_attributes: dict = field(default_factory=dict)
    voxel_inputs: object = None
    emission_field: list = field(default_factory=list)
    emission_attributes: dict = field(default_factory=dict)
    strength_grid: object = None

    @property
    def emitting_grid(self):
        """The grid whose value the emission varies with (temperature or strength), or None."""
        return self.temperature_grid if self.temperature_grid is not None else self.strength_grid

    @property
    def varies(self) -> bool:
        """Whether the material's program computes something of this medium per point (baked)."""
        return self.density_varies or bool(self.emission_field)
    phase: list = field(default_factory=list)
