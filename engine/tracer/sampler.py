"""Uniform numbers for every dimension of a path: Owen-scrambled Sobol, or independent for tests.

Sobol (default): each 1-D or 2-D sample *slot* of a path (pixel position, lens, wavelengths, and per
bounce the BSDF lobe and direction, light choice and point, roulette) draws the first two dimensions of
the Sobol sequence — a (0,2)-sequence, so the first 2^k samples of a pixel are stratified in every
2-D slot — with the sample index shuffled and both coordinates nested-uniform (Owen) scrambled by hashes
of the pixel, the seed and the slot. This is the padded construction of pbrt-v4 with Burley's
hash-based Owen scrambling (B. Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020, which
Cycles uses too); the Laine-Karras permutation constants are Burley's. Slots are decorrelated by their
independent shuffles, pixels by their seeds, so the image has no structured artefacts.

Independent: a hash of (pixel seed, sample, slot, coordinate) per number — the reference the benchmark
compares the gain of Sobol against.

Integers are held in int64 and masked to 32 bits (numba has no silent uint32 wrap-around that mixes
safely with Python ints); every value is deterministic, so an image depends only on the seed.
"""

from __future__ import annotations

import numpy as np

from .jit import kernel

SOBOL = 0
INDEPENDENT = 1
SAMPLERS = {"sobol": SOBOL, "independent": INDEPENDENT}

# Sample slots of a path. A slot is 1-D or 2-D; per-bounce slots repeat every SLOTS_PER_BOUNCE.
SLOT_PIXEL = 0  # 2-D: position in the pixel (filter)
SLOT_LENS = 1  # 2-D: aperture / exit pupil
SLOT_WAVELENGTH = 2  # 1-D x 3: slots 2, 3, 4 (cie uses the first; gaussian_rgb one per channel)
SLOT_HERO = 5  # 1-D: which carried wavelength is the hero
SLOT_BOUNCE = 6
SLOTS_PER_BOUNCE = 5
BOUNCE_LOBE = 0  # 1-D: which BSDF closure / reflect or refract
BOUNCE_DIRECTION = 1  # 2-D: BSDF direction
BOUNCE_LIGHT = 2  # 1-D: which light
BOUNCE_LIGHT_POINT = 3  # 2-D: point on the light
BOUNCE_ROULETTE = 4  # 1-D: Russian roulette
#: 2-D per bounce, in a range of its own so scenes without media keep every other slot: the distance to
#: a collision in a medium and the wavelength whose extinction samples it (``media.segment``).
SLOT_MEDIUM = 1 << 24
MEDIUM_LIGHT_OFFSET = 1 << 16  # medium_light_slot: past every bounce's medium_slot
# 1-D: the path's ray time in the shutter (motion blur). Numbered far beyond every bounce's slots, so
# turning motion blur on leaves every other dimension, and so still images, as they were.
SLOT_TIME = 1 << 20
#: 2-D per bounce: the rays a material traces itself (Ambient Occlusion, Bevel: ``materials.shader_rays``),
#: ``SHADER_RAY_KINDS`` slots per bounce, in a range of their own so scenes without those nodes sample as before.
SLOT_SHADER_RAYS = 1 << 22
SHADER_RAY_KINDS = 2
#: 2-D, two per step of a subsurface random walk (``subsurface.walk``) at each bounce, in a range of their own so
#: scenes without subsurface scattering sample as before.
SLOT_SUBSURFACE = 1 << 26
SUBSURFACE_SLOTS_PER_BOUNCE = 1 << 10
#: 2-D, one per tentative collision of delta tracking in a grid medium (``media.delta_tracking``) at each
#: bounce, in a range of their own so scenes without grid media sample as before. Steps past
#: ``GRID_SLOTS_PER_BOUNCE`` draw independent numbers (hashed) instead.
SLOT_GRID_MEDIUM = 1 << 27
GRID_SLOTS_PER_BOUNCE = 1 << 12
#: 1-D independent numbers of ratio tracking (``media.ratio_tracking``): a shadow ray may take any number of
#: steps, so each step hashes its number from the path's sample, the ray and the step.
SLOT_RATIO_TRACKING = 1 << 29

_MASK = 0xFFFFFFFF
_INV_2_32 = 1.0 / 4294967296.0


def _sobol_dimension_1_tables() -> np.ndarray:
    """Generator matrix of Sobol dimension 1 (polynomial x + 1, m = 1, 3, 5, 15, ...) applied to each
    byte of the index: table[b, v] is the XOR of the direction numbers of the set bits of v << 8b."""
    direction = np.zeros(32, dtype=np.int64)
    direction[0] = 1 << 31
    for j in range(1, 32):
        direction[j] = direction[j - 1] ^ (direction[j - 1] >> 1)
    table = np.zeros((4, 256), dtype=np.int64)
    for b in range(4):
        for v in range(256):
            acc = 0
            for bit in range(8):
                if v >> bit & 1:
                    acc ^= int(direction[8 * b + bit])
            table[b, v] = acc
    return table


_SOBOL1 = _sobol_dimension_1_tables()


@kernel
def hash32(x):
    """A 32-bit integer hash with good avalanche (Wellons' "lowbias32" constants)."""
    x &= _MASK
    x ^= x >> 16
    x = (x * 0x7FEB352D) & _MASK
    x ^= x >> 15
    x = (x * 0x846CA68B) & _MASK
    x ^= x >> 16
    return x


@kernel
def reverse_bits32(x):
    x &= _MASK
    x = ((x >> 1) & 0x55555555) | ((x & 0x55555555) << 1)
    x = ((x >> 2) & 0x33333333) | ((x & 0x33333333) << 2)
    x = ((x >> 4) & 0x0F0F0F0F) | ((x & 0x0F0F0F0F) << 4)
    x = ((x >> 8) & 0x00FF00FF) | ((x & 0x00FF00FF) << 8)
    return ((x >> 16) | (x << 16)) & _MASK


@kernel
def laine_karras_permutation(x, seed):
    x = (x + seed) & _MASK
    x ^= (x * 0x6C50B47C) & _MASK
    x ^= (x * 0xB82F1E52) & _MASK
    x ^= (x * 0xC7AFE638) & _MASK
    x ^= (x * 0x8D22F6E6) & _MASK
    return x


@kernel
def nested_uniform_scramble(x, seed):
    """Owen scrambling of the 32-bit fraction x / 2^32 (base 2)."""
    return reverse_bits32(laine_karras_permutation(reverse_bits32(x), seed))


@kernel
def sobol_dimension_1(index):
    return (_SOBOL1[0, index & 0xFF] ^ _SOBOL1[1, (index >> 8) & 0xFF]
            ^ _SOBOL1[2, (index >> 16) & 0xFF] ^ _SOBOL1[3, (index >> 24) & 0xFF])


@kernel
def pixel_seed(pixel, seed):
    """The sampler seed of one pixel of a render with ``seed``."""
    return hash32(hash32(pixel) ^ hash32(seed ^ 0x9E3779B9))


@kernel
def _slot_seed(pixel_seed_value, slot):
    return hash32(pixel_seed_value + (slot + 1) * 0x9E3779B9)


@kernel
def _combine(seed, value):
    """A second seed from ``seed`` for another coordinate (Boost's hash_combine, as Burley uses)."""
    return (seed ^ (value + 0x9E3779B9 + ((seed << 6) & _MASK) + (seed >> 2))) & _MASK


@kernel
def sample_2d(kind, pixel_seed_value, sample_index, slot):
    """Two uniforms in [0, 1) for ``slot`` of sample ``sample_index`` of the pixel."""
    seed = _slot_seed(pixel_seed_value, slot)
    if kind == INDEPENDENT:
        a = hash32(seed ^ hash32(sample_index * 2 + 0x2545F491))
        b = hash32(seed ^ hash32(sample_index * 2 + 0x2545F492))
        return a * _INV_2_32, b * _INV_2_32
    index = nested_uniform_scramble(sample_index & _MASK, seed)
    # Sobol dimension 0 is the bit reversal: its scramble reverse(LK(reverse(reverse(i)))) simplifies.
    x = reverse_bits32(laine_karras_permutation(index, _combine(seed, 1)))
    y = nested_uniform_scramble(sobol_dimension_1(index), _combine(seed, 2))
    return x * _INV_2_32, y * _INV_2_32


@kernel
def sample_1d(kind, pixel_seed_value, sample_index, slot):
    """One uniform in [0, 1) for ``slot`` of sample ``sample_index`` of the pixel."""
    seed = _slot_seed(pixel_seed_value, slot)
    if kind == INDEPENDENT:
        return hash32(seed ^ hash32(sample_index * 2 + 0x2545F491)) * _INV_2_32
    index = nested_uniform_scramble(sample_index & _MASK, seed)
    return reverse_bits32(laine_karras_permutation(index, _combine(seed, 1))) * _INV_2_32


@kernel
def bounce_slot(depth, which):
    """The slot of per-bounce dimension ``which`` (``BOUNCE_*``) at bounce ``depth``."""
    return SLOT_BOUNCE + depth * SLOTS_PER_BOUNCE + which


@kernel
def shader_ray_slot(depth, kind):
    """The 2-D slot of a material's own rays of ``kind`` (0 ambient occlusion, 1 bevel) at bounce ``depth``:
    a node with N samples draws sample index ``sample × N + j`` of it, so a pixel's samples together form
    one stratified sequence (Cycles' ``path_branched_rng_2D`` does the same)."""
    return SLOT_SHADER_RAYS + depth * SHADER_RAY_KINDS + kind


@kernel
def subsurface_slot(depth, step, which):
    """The 2-D slot of decision ``which`` (0: wavelength and distance, 1: direction, 2: guided or not) of step
    ``step`` of the random walk that starts at bounce ``depth``."""
    return SLOT_SUBSURFACE + depth * SUBSURFACE_SLOTS_PER_BOUNCE + 3 * step + which


@kernel
def grid_medium_uniforms(kind, pixel_seed_value, sample_index, depth, step):
    """Two uniforms for tentative collision ``step`` of delta tracking along the ray of bounce ``depth``."""
    if step < GRID_SLOTS_PER_BOUNCE:
        return sample_2d(kind, pixel_seed_value, sample_index, SLOT_GRID_MEDIUM + depth * GRID_SLOTS_PER_BOUNCE + step)
    return sample_2d(INDEPENDENT, pixel_seed_value, sample_index, SLOT_GRID_MEDIUM + hash32(depth * 7919 + step))


@kernel
def medium_slot(depth):
    """The 2-D slot of the medium decisions of the ray traced at bounce ``depth``."""
    return SLOT_MEDIUM + depth


@kernel
def medium_light_slot(depth):
    """The 2-D slot of the equiangular decisions (strategy and light, distance) of the ray traced at bounce
    ``depth`` (``media.equiangular``): apart from ``medium_slot``, so scenes without them sample as before."""
    return SLOT_MEDIUM + MEDIUM_LIGHT_OFFSET + depth
