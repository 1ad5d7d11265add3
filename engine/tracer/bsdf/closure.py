"""A closure: one scattering model with its parameters, as a row of numbers (see ``materials``).

Row layout (float64 [CLOSURE_ROW]). Spectral parameters are *sources*, resolved per path into
``spectral[3, K]`` (values at the path's wavelengths) before a BSDF function runs: a source ≥ 0 is a
spectrum-table id, -1 means 1 at every wavelength, and ``≤ -2`` is a colour computed at the hit by the
material's program (``register_source``).

- ``C_KIND``: ``DIFFUSE``, ``CONDUCTOR`` (any microfacet reflection), ``DIELECTRIC``, ``THIN_FILM``,
  ``TRANSLUCENT``, ``TRANSPARENT``, ``SHEEN`` (Blender's microfiber sheen, ``bsdf.sheen``), ``SUBSURFACE``
  (a random walk under the surface: ``spectral[0]`` the albedo, ``spectral[1]`` the radius over its largest,
  ``C_SSS_*``, ``C_ALPHA`` and ``C_ETA`` the entry bounce's roughness and index; ``subsurface``) or ``HAIR``
  (a fibre: Principled Hair's Chiang model, ``bsdf.hair_chiang``; ``bsdf.hair``).
- ``C_WEIGHT``: how often the closure is sampled relative to the others of its material (≥ 0; the
  estimated albedo times the mean tint); f = Σ tint · f_closure does not depend on it.
- ``C_SPECTRUM`` (→ ``spectral[0]``): diffuse/translucent albedo; a conductor's F0 (Schlick, F82) or n;
  the tint of a dielectric Fresnel's F0 (Principled Specular Tint).
- ``C_S1`` (→ ``spectral[1]``): a conductor's k or F82 tint; a dielectric's transmission tint.
- ``C_TINT`` (→ ``spectral[2]``): the closure's weight per wavelength (Mix/Add shader factors, colours of
  Glossy, Glass, Transparent, Principled layering); -1 for 1. ``C_TINT_SCALE`` multiplies it (a
  constant weight above 1 is a reflectance spectrum times its largest component).
- ``C_MIRROR``: set per hit when a reflection closure shares a material with glass and the ray arrived
  from inside: the glass needs the outward normal, the reflection sees its frame mirrored (``dispatch``).
- ``C_ALPHA``: GGX alpha (Blender roughness²); below ``SMOOTH_ALPHA`` the lobe is a perfect mirror/glass. For
  ``SHEEN``: the sheen roughness (Blender's, 0-1, not squared).
- ``C_FRESNEL``: a conductor's reflectance model (``FRESNEL_*``) or a dielectric's mode (``GLASS`` reflects
  and refracts, ``REFRACTION_ONLY`` as Blender's Refraction BSDF).
- ``C_ETA``: index of refraction of a ``FRESNEL_DIELECTRIC`` reflection (Principled specular, coat).
- ``C_GLASS``: row of the material table's glass array (dielectrics); resolved into ``eta``.
- ``C_COAT_NM``, ``C_COAT_IOR``: a thin-film coating over a conductor or dielectric (0 nm: none).
- ``C_FILM_NM``, ``C_FILM_IOR``: a free-standing film (soap bubble).
- ``C_LAYER_ETA``, ``C_LAYER_ROUGHNESS``, ``C_LAYER_F0``: a constant GGX dielectric layer above the closure
  (the Principled specular layer over diffuse, metal or glass): its index (0: no layer), Blender roughness and
  largest normal-incidence reflectance. The closure's tint is scaled per hit by what the layer lets through,
  1 - its albedo seen from the view direction (``materials.layering.under_layer``). ``C_LAYER_MULTISCATTER``: 1 when
  that layer is Multiscatter GGX: its albedo is then what the energy-compensated lobe reflects.
- ``C_MULTISCATTER``: 1 where the Blender node's distribution is Multiscatter GGX (and for the Principled coat,
  which Cycles always compensates): the rough GGX lobe is energy-compensated per hit (``bsdf.multiscatter``,
  applied by ``materials.energy``); 0 for single-scatter GGX.
- ``C_MS_COLOUR``: a spectral source: the average single-scattering Fresnel Fss of a compensated lobe whose
  Fresnel model does not set it (Glossy's colour, a glass's colour or transmission tint); -1 for 1.
- ``C_SHEEN_A``, ``C_SHEEN_B``: the fitted LTC coefficients of a ``SHEEN`` closure at this hit's view
  direction, set per hit with its tint scaled by the fitted albedo (``materials.sheen_setup``).
- ``C_NORMAL``: the program register of the closure's own shading normal (a Principled Coat Normal, or a
  shader whose Normal input differs from the material's), -1 where it shades with the material's normal.
- Set per hit by ``materials.closure_normals`` (0 in the constant rows): ``C_FRAMED`` = 1 where the closure
  scatters about a normal other than the material's, ``C_FRAME_X/Y/Z`` (in the material's shading frame; its
  own normal, or one Cycles' Bump Map Correction raised), with ``C_VIEW_COS`` the view's cosine there;
  ``C_BUMPED`` = 1 where that normal is not the smooth one, ``C_SMOOTH_X/Y/Z`` (the smooth normal in the
  same frame) for Cycles' bump shadowing test (``closure_frame``).
- ``HAIR`` closures (``bsdf.hair``): ``C_HAIR_MODEL`` 0 for Principled Hair (Chiang), ``bsdf.hair_kajiya``'s
  ``REFLECTION`` or ``TRANSMISSION`` for the Hair BSDF's components (RoughnessU, RoughnessV in
  ``C_HAIR_ROUGHNESS``, ``C_HAIR_RADIAL``; Offset in ``C_HAIR_OFFSET``). They keep their node inputs in ``C_HAIR_*`` and are set up per hit by
  ``materials.hair_setup``: ``C_HAIR_ROUGHNESS``, ``C_HAIR_RADIAL`` (Blender's Roughness and Radial Roughness),
  ``C_HAIR_COAT``, ``C_HAIR_IOR``, ``C_HAIR_OFFSET`` (cuticle tilt, radians), ``C_HAIR_RANDOM_ROUGHNESS``,
  ``C_HAIR_RANDOM`` (the Random input; on a strand, where ``C_HAIR_STRAND_RANDOM`` is 1 (Random unlinked),
  the strand's own random number replaces it per hit), ``C_HAIR_MELANIN``,
  ``C_HAIR_REDNESS``, ``C_HAIR_RANDOM_COLOUR`` and ``C_HAIR_SIGMA_MODE`` (``SIGMA_*``: how the absorption is given:
  a colour in ``C_SPECTRUM``, an absorption coefficient in ``C_S1`` (an unbounded source, times
  ``C_HAIR_SIGMA_SCALE``) or melanin with a tint in ``C_SPECTRUM``). Per hit: the absorption coefficient per
  wavelength replaces ``spectral[0]``; ``C_HAIR_V``, ``C_HAIR_S``, ``C_HAIR_M0`` are Cycles' longitudinal variance,
  azimuthal logistic scale and primary-reflection variance; ``C_HAIR_H`` the offset across the fibre (-1..1) seen
  from the view; ``C_HAIR_TX/TY/TZ`` the unit curve tangent (world, then in the material's shading frame once
  ``closure_normals.orient_closures`` ran). ``C_HAIR_TANGENT``: the register of the Hair BSDF's linked Tangent
  (world; it replaces the curve's tangent, as in Cycles), -1 where the curve's own is used.
- ``C_TERMINATOR``: set per hit on the closures of a triangle whose object has a shadow terminator Shading Offset
  (0 in the constant rows): Cycles' frequency multiplier 1 / (1 - offset / 2), which stretches the angle of the
  light to the closure's normal (``closure_frame.terminator_softening``).
"""

from __future__ import annotations

DIFFUSE = 0
CONDUCTOR = 1
DIELECTRIC = 2
THIN_FILM = 3
TRANSLUCENT = 4
TRANSPARENT = 5
SHEEN = 6
SUBSURFACE = 7
HAIR = 8
KIND_NAMES = {DIFFUSE: "diffuse", CONDUCTOR: "conductor", DIELECTRIC: "dielectric", THIN_FILM: "thin_film",
              TRANSLUCENT: "translucent", TRANSPARENT: "transparent", SHEEN: "sheen", SUBSURFACE: "subsurface",
              HAIR: "hair"}

C_KIND = 0
C_WEIGHT = 1
C_SPECTRUM = 2
C_ALPHA = 3
C_GLASS = 4
C_COAT_NM = 5
C_COAT_IOR = 6
C_S1 = 7
C_TINT = 8
C_FILM_NM = 9
C_FILM_IOR = 10
C_FRESNEL = 11
C_ETA = 12
C_TINT_SCALE = 13
C_MIRROR = 14
C_LAYER_ETA = 15
C_LAYER_ROUGHNESS = 16
C_LAYER_F0 = 17
C_MULTISCATTER = 18
C_MS_COLOUR = 19
C_LAYER_MULTISCATTER = 20
C_SHEEN_A = 21
C_SHEEN_B = 22
C_NORMAL = 23
C_FRAMED = 24
C_FRAME_X = 25
C_FRAME_Y = 26
C_FRAME_Z = 27
C_VIEW_COS = 28
C_BUMPED = 29
C_SMOOTH_X = 30
C_SMOOTH_Y = 31
C_SMOOTH_Z = 32
C_HAIR_ROUGHNESS = 33
C_HAIR_RADIAL = 34
C_HAIR_COAT = 35
C_HAIR_IOR = 36
C_HAIR_OFFSET = 37
C_HAIR_RANDOM_ROUGHNESS = 38
C_HAIR_RANDOM = 39
C_HAIR_MELANIN = 40
C_HAIR_REDNESS = 41
C_HAIR_RANDOM_COLOUR = 42
C_HAIR_SIGMA_MODE = 43
C_HAIR_SIGMA_SCALE = 44
C_HAIR_V = 45
C_HAIR_S = 46
C_HAIR_M0 = 47
C_HAIR_H = 48
C_HAIR_TX = 49
C_HAIR_TY = 50
C_HAIR_TZ = 51
C_HAIR_MODEL = 52
C_HAIR_STRAND_RANDOM = 53
C_HAIR_TANGENT = 54
C_TERMINATOR = 55
CLOSURE_ROW = 56

# How a ``HAIR`` closure's absorption is given (``C_HAIR_SIGMA_MODE``), Principled Hair's parametrizations.
SIGMA_COLOUR = 0  # Direct Coloring: the colour in ``C_SPECTRUM``
SIGMA_ABSORPTION = 1  # Absorption Coefficient: ``C_S1`` × ``C_HAIR_SIGMA_SCALE`` (1/fibre diameter)
SIGMA_MELANIN = 2  # Melanin Concentration (``C_HAIR_MELANIN``, ``C_HAIR_REDNESS``) plus the tint in ``C_SPECTRUM``

# A ``SUBSURFACE`` closure's own parameters, in columns only films and coatings use otherwise.
C_SSS_RADIUS = C_FILM_NM  # the largest mean free path (m): Radius × Scale; spectral[1] is Radius / its largest
C_SSS_ANISOTROPY = C_FILM_IOR  # Henyey-Greenstein g inside (clamped as Cycles' bssrdf_setup)
C_SSS_METHOD = C_COAT_NM  # SSS_RANDOM_WALK or SSS_SKIN (the entry bounce and the radius, ``subsurface``)
SSS_RANDOM_WALK = 0.0
SSS_SKIN = 1.0


# Conductor (microfacet reflection) reflectance models.
FRESNEL_SCHLICK = 0  # F0 = spectral[0]
FRESNEL_CONDUCTOR = 1  # measured n = spectral[0], k = spectral[1]
FRESNEL_NONE = 2  # F = 1 (Blender's Glossy BSDF: the colour is the closure's tint)
FRESNEL_F82 = 3  # F82-tint: F0 = spectral[0], tint at 82° = spectral[1] (Principled metallic)
FRESNEL_DIELECTRIC = 4  # a dielectric's reflection at C_ETA, F0 tinted by spectral[0] (specular, coat)

# Dielectric modes.
GLASS = 0
REFRACTION_ONLY = 1

SMOOTH_ALPHA = 1e-3  # below this GGX alpha a lobe is treated as a perfect specular (delta) one
MAX_CLOSURES = 16  # closures one material may combine

# What a sampled direction was (returned by every ``sample``; ``SAMPLED_DIFFUSE`` is added by
# ``dispatch.bsdf_sample`` when the chosen closure is diffuse).
SAMPLED_DELTA = 1
SAMPLED_TRANSMISSION = 2
SAMPLED_NULL = 4  # straight through without scattering (Transparent BSDF): a null event for MIS
SAMPLED_DIFFUSE = 8
SAMPLED_SUBSURFACE = 16  # into the surface for a random walk (``bsdf.subsurface_entry``, ``stages.subsurface``)


def register_source(register: int) -> float:
    """The source value of a colour computed into registers ``register .. register + 2``."""
    return float(-2 - int(register))
