"""A closure: one scattering model with its parameters, as a row of numbers (see ``materials``).

Row layout (float64 [CLOSURE_ROW]); spectral parameters are spectrum-table ids, resolved per path into
``spectral[2, K]`` (values at the path's wavelengths) before a BSDF function runs:

- ``C_KIND``: ``DIFFUSE``, ``CONDUCTOR``, ``DIELECTRIC`` or ``THIN_FILM``.
- ``C_WEIGHT``: the closure's weight in its material (f = Σ weight · f_closure).
- ``C_SPECTRUM``: diffuse albedo, or a conductor's normal-incidence reflectance (Schlick) when it has
  no measured n, k; -1 if unused. Resolved into ``spectral[0]``.
- ``C_ALPHA``: GGX alpha (Blender roughness²); below ``SMOOTH_ALPHA`` the lobe is a perfect mirror/glass.
- ``C_GLASS``: row of the material table's glass array (dielectrics); resolved into ``eta``.
- ``C_COAT_NM``, ``C_COAT_IOR``: a thin-film coating over a conductor or dielectric (0 nm: none).
- ``C_N``, ``C_K``: spectrum ids of a conductor's measured n and k (-1: Schlick). Resolved into
  ``spectral[0]`` and ``spectral[1]``.
- ``C_FILM_NM``, ``C_FILM_IOR``: a free-standing film (soap bubble).
"""

from __future__ import annotations

DIFFUSE = 0
CONDUCTOR = 1
DIELECTRIC = 2
THIN_FILM = 3
KIND_NAMES = {DIFFUSE: "diffuse", CONDUCTOR: "conductor", DIELECTRIC: "dielectric", THIN_FILM: "thin_film"}

C_KIND = 0
C_WEIGHT = 1
C_SPECTRUM = 2
C_ALPHA = 3
C_GLASS = 4
C_COAT_NM = 5
C_COAT_IOR = 6
C_N = 7
C_K = 8
C_FILM_NM = 9
C_FILM_IOR = 10
CLOSURE_ROW = 11

SMOOTH_ALPHA = 1e-3  # below this GGX alpha a lobe is treated as a perfect specular (delta) one
MAX_CLOSURES = 8  # closures one material may combine

# What a sampled direction was (returned by every ``sample``; ``SAMPLED_DIFFUSE`` is added by
# ``dispatch.bsdf_sample`` when the chosen closure is diffuse).
SAMPLED_DELTA = 1
SAMPLED_TRANSMISSION = 2
SAMPLED_DIFFUSE = 4
