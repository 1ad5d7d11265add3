"""Cycles' shadow catcher in the bounce loop: the split of a camera path where it meets a catcher, and what
each sample leaves in the catcher's film columns (``shadow_catcher_film`` says what they become).

Where a camera path (``CAMERA_PATH``: no scattering yet but cut-outs and transparent glass, Cycles'
PATH_RAY_TRANSPARENT_BACKGROUND) first meets an object marked Shadow Catcher (Object ▸ Visibility ▸ Mask)
that is not a holdout, it splits, as Cycles' ``integrator_split_shadow_catcher`` does:

- the path itself (``CATCHER_HIT``) shades the catcher with every object, as before, into Combined only;
  what it brought until then is the matte (its radiance and transparency at the split, the split
  counting as see-through by the throughput's mean);
- a copy (``CATCHER_PASS``) starts from the same state (random numbers included, as Cycles copies its
  path state) with no radiance but the catcher's own emission at the hit, sees only shadow catchers (``visibility_accel``: camera, bounce and shadow
  rays) and only the emitters of the catcher's world (``catcher_lights``); its light is the catcher
  without the other objects. The copy takes a free row after the chunk's paths (``ChunkBuffers`` holds
  two rows a path in scenes with a catcher) and the row of its path is kept, so the film adds it to that
  sample.

Neither splits again. ``catcher_film_kernel`` turns each sample's share into Rec.709 columns once the
chunk's paths have ended. Everything here runs behind ``KernelSettings.shadow_catcher``.
"""

from __future__ import annotations

from ..jit import inlined, kernel
from ..lights import environment
from ..shadow_catcher_film import BACKGROUND_RGB, CATCHER_RGB, MATTE_RGB, MATTE_TRANSPARENCY, SPLITS
from ..spectra.wavelength_sampling import radiance_to_rgb
from ..state import CAMERA_PATH, CATCHER_HIT, CATCHER_PASS
from ..visibility import HOLDOUT, SHADOW_CATCHER


@inlined
def copy_path(state, i, j):
    """Row ``j`` of ``state`` becomes a copy of row ``i`` (every ``PathState`` field)."""
    state.pixel[j] = state.pixel[i]
    state.sample[j] = state.sample[i]
    state.seed[j] = state.seed[i]
    state.hero[j] = state.hero[i]
    state.flags[j] = state.flags[i]
    state.medium[j] = state.medium[i]
    state.eta_scale[j] = state.eta_scale[i]
    state.prev_pdf[j] = state.prev_pdf[i]
    state.min_pdf[j] = state.min_pdf[i]
    state.hit_triangle[j] = state.hit_triangle[i]
    state.hit_u[j] = state.hit_u[i]
    state.hit_v[j] = state.hit_v[i]
    state.hit_t[j] = state.hit_t[i]
    state.transparency[j] = state.transparency[i]
    state.time[j] = state.time[i]
    state.receiver[j] = state.receiver[i]
    state.ray_travelled[j] = state.ray_travelled[i]
    for k in range(state.wavelength.shape[1]):
        state.wavelength[j, k] = state.wavelength[i, k]
        state.wavelength_pdf[j, k] = state.wavelength_pdf[i, k]
        state.throughput[j, k] = state.throughput[i, k]
        state.radiance[j, k] = state.radiance[i, k]
    for c in range(3):
        state.origin[j, c] = state.origin[i, c]
        state.direction[j, c] = state.direction[i, c]
        state.mis_origin[j, c] = state.mis_origin[i, c]
    for c in range(state.light_path.shape[1]):
        state.light_path[j, c] = state.light_path[i, c]
    for c in range(state.crossings.shape[1]):
        state.crossings[j, c] = state.crossings[i, c]


@inlined
def splits_here(state, i, geometry, triangle):
    """Whether path ``i`` splits at ``triangle`` (Cycles' ``kernel_shadow_catcher_is_path_split_bounce``)."""
    flags = geometry.flags[triangle]
    return (flags & SHADOW_CATCHER != 0 and flags & HOLDOUT == 0 and state.flags[i] & CAMERA_PATH != 0
            and state.flags[i] & CATCHER_HIT == 0)


@inlined
def split_at_catcher(state, i, triangle, u, v, t, lights, spectra, passes, layout, d):
    """Split path ``i`` at the catcher it hit (``triangle`` at ``u``, ``v``, distance ``t`` along ``d``): its
    matte and the world behind the catcher go to its columns, and the copy, listed for shading at the same
    hit, is returned (its row)."""
    k_count = state.radiance.shape[1]
    column = layout.catcher
    mean = 0.0
    for k in range(k_count):
        passes.catcher_matte[i, k] = state.radiance[i, k]
        mean += state.throughput[i, k]
    passes.values[i, column + SPLITS] = 1.0
    passes.values[i, column + MATTE_TRANSPARENCY] = state.transparency[i] + mean / k_count
    # the world behind the catcher, for Combined on an opaque film (Cycles' SHADOW_CATCHER_BACKGROUND)
    env = lights.camera_environment if lights.backplate else lights.environment
    if env.kind != environment.ENV_NONE:
        fp = environment.footprint(env, d)
        for k in range(k_count):
            passes.catcher_background[i, k] += state.throughput[i, k] * environment.value(env, spectra, fp,
                                                                                         state.wavelength[i, k])
    state.flags[i] |= CATCHER_HIT
    j = passes.catcher_next[0]
    passes.catcher_next[0] = j + 1
    passes.catcher_copy[i] = j
    copy_path(state, i, j)
    state.flags[j] |= CATCHER_PASS
    for k in range(k_count):
        state.radiance[j, k] = 0.0
    state.hit_triangle[j] = triangle
    state.hit_u[j] = u
    state.hit_v[j] = v
    state.hit_t[j] = t
    return j


@inlined
def share_emission(state, i, j, passes):
    """The copy ``j`` also receives what path ``i`` got since its split: the catcher's own emission at the hit
    (Cycles' copy shades the catcher surface, emission included, into the catcher's pass)."""
    for k in range(state.radiance.shape[1]):
        state.radiance[j, k] += state.radiance[i, k] - passes.catcher_matte[i, k]


@inlined
def background_seen(state, i, settings, passes, k, value):
    """The world's ``value`` (wavelength column ``k``) seen directly by camera path ``i``, for Combined on an
    opaque film (Cycles' Background pass, which it adds with a catcher)."""
    if settings.shadow_catcher and state.flags[i] & CAMERA_PATH:
        passes.catcher_background[i, k] += value


@kernel
def catcher_start_kernel(passes, count):
    """Paths 0 .. count-1 have not split; their copies will take rows from ``count`` on."""
    for i in range(count):
        passes.catcher_copy[i] = -1
        for k in range(passes.catcher_matte.shape[1]):
            passes.catcher_matte[i, k] = 0.0
            passes.catcher_background[i, k] = 0.0
    passes.catcher_next[0] = count


@kernel
def catcher_film_kernel(state, passes, layout, ws, rgb, count):
    """Each of paths 0 .. count-1's catcher columns as Rec.709 (``rgb``: their Combined colours, from
    ``film_kernel``): the copy's light, the matte (all of the path's light if it did not split), the world
    seen."""
    column = layout.catcher
    for i in range(count):
        j = passes.catcher_copy[i]
        wavelength, pdf = state.wavelength[i], state.wavelength_pdf[i]
        if j >= 0:
            r, g, b = radiance_to_rgb(ws, state.radiance[j], state.wavelength[j], state.wavelength_pdf[j])
            passes.values[i, column + CATCHER_RGB] = r
            passes.values[i, column + CATCHER_RGB + 1] = g
            passes.values[i, column + CATCHER_RGB + 2] = b
            r, g, b = radiance_to_rgb(ws, passes.catcher_matte[i], wavelength, pdf)
        else:
            r, g, b = rgb[i, 0], rgb[i, 1], rgb[i, 2]
            passes.values[i, column + MATTE_TRANSPARENCY] = state.transparency[i]
        passes.values[i, column + MATTE_RGB] = r
        passes.values[i, column + MATTE_RGB + 1] = g
        passes.values[i, column + MATTE_RGB + 2] = b
        r, g, b = radiance_to_rgb(ws, passes.catcher_background[i], wavelength, pdf)
        passes.values[i, column + BACKGROUND_RGB] = r
        passes.values[i, column + BACKGROUND_RGB + 1] = g
        passes.values[i, column + BACKGROUND_RGB + 2] = b
