"""What the scene emits, spectrum by spectrum: (spectrum id, power) of every light, every emissive
material and the world, for the wavelength sampler to follow (``spectra.wavelength_guide``).

Powers are in the units light selection uses (spectra are luminance-normalised, so they compare): a
light's row power, π Σ area × strength for an emissive material, and for the world's background the
power it sends through the scene's bounding sphere (``LightTable.world_emission``: π L · π R² for a
constant world of radiance L, as a sun's E · π R²; π R² ∫ L dω for an image or a sky, with the
spectrum of its mean colour).
"""

from __future__ import annotations

import math

import numpy as np

from .row import ENVIRONMENT, L_KIND, L_SPECTRUM, MESH


def emitter_spectra(light_table, materials) -> list[tuple[int, float]]:
    """(spectrum id, power > 0) pairs; ``light_table`` a ``lights.table.LightTable``, ``materials`` the
    ``materials.table.MaterialArrays``."""
    arrays = light_table.arrays
    emitters = []
    for row, power in zip(arrays.rows[: len(light_table.names)], light_table.power):
        if int(row[L_KIND]) not in (MESH, ENVIRONMENT) and power > 0:
            emitters.append((int(row[L_SPECTRUM]), float(power)))
    mesh = arrays.mesh
    if len(mesh.material):
        area = mesh.geometry[:, 12]
        for material in np.unique(mesh.material):
            strength = float(materials.emission_strength[material])
            power = math.pi * strength * float(area[mesh.material == material].sum())
            if power > 0:
                emitters.append((int(materials.emission_spectrum[material]), power))
    if light_table.world_emission is not None and light_table.world_emission[1] > 0:
        emitters.append((int(light_table.world_emission[0]), float(light_table.world_emission[1])))
    return emitters
