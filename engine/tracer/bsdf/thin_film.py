"""Free-standing thin film (soap bubble): a layer of index ``C_FILM_IOR`` and thickness ``C_FILM_NM`` in
air. Its faces are parallel, so transmitted light leaves undeviated (wi = -wo); reflection is specular.
Airy reflectance R(λ, θ) per wavelength, T = 1 - R (no absorption). Both lobes are deltas, chosen with
p = mean R over the carried wavelengths, weights R_k / p and T_k / (1 - p). Shadow rays pass through
films (``stages.shadow``), attenuated by T.
"""

from __future__ import annotations

import math

from ..jit import kernel
from .closure import C_FILM_IOR, C_FILM_NM, SAMPLED_DELTA, SAMPLED_TRANSMISSION
from .dielectric import choice_probability
from .optics import thin_film_reflectance


@kernel
def film_reflectance(row, cos_i, wavelength_nm):
    """Reflectance of the film in air at one wavelength."""
    return thin_film_reflectance(cos_i, wavelength_nm, row[C_FILM_NM], 1.0, row[C_FILM_IOR], complex(1.0, 0.0))


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale); ``weight[k]`` = R_k / p or T_k / (1 - p)."""
    for k in range(weight.shape[0]):
        weight[k] = film_reflectance(row, wo[2], wavelength_nm[k])
    p = choice_probability(weight, hero, collapsed)
    if u0 < p:
        for k in range(weight.shape[0]):
            weight[k] = weight[k] / p
            if not math.isfinite(weight[k]):
                weight[k] = 0.0
        return (-wo[0], -wo[1], wo[2]), math.inf, SAMPLED_DELTA, 1.0
    for k in range(weight.shape[0]):
        weight[k] = (1.0 - weight[k]) / (1.0 - p)
        if not math.isfinite(weight[k]):
            weight[k] = 0.0
    return (-wo[0], -wo[1], -wo[2]), math.inf, SAMPLED_DELTA | SAMPLED_TRANSMISSION, 1.0


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """Both lobes are deltas: nothing to evaluate."""
    f[:] = 0.0
    return 0.0
