"""Stage 3: what happens at each surface a path reached this bounce.

The hit point and its frame (the shading normal flipped to face the ray unless the material is
one-sided glass); dispersion (a path meeting a dispersive material keeps only its hero wavelength, ×K
— each column stays unbiased because the hero is uniform over columns); the material resolved at the
hit (``materials.surface``: its program, when it has one, may also bend the shading normal); light
sampling (``nee``) unless every lobe is a delta; BSDF sampling; roulette; and the path's next ray,
queued. A free-standing film crossed straight through, or a cut-out (Transparent BSDF, alpha), is a
null event for MIS: the path keeps the pdf and ``mis_origin`` of the vertex before it, and the ray
type it had (a camera ray seen through a cut-out is still a camera ray, as in Cycles). A camera path
also stays one through transparent glass (transmission no rougher than the film's threshold, with
Transparent Glass on). A path crossing the surface of a material with a medium enters or leaves it
(``side_medium``); a medium vertex (``MEDIUM_VERTEX``) scatters by its phase function (``media.scatter``).
"""

from __future__ import annotations

from ..bsdf.closure import (C_ALPHA, SAMPLED_DELTA, SAMPLED_DIFFUSE, SAMPLED_NULL, SAMPLED_SUBSURFACE,
                            SAMPLED_TRANSMISSION)
from ..bsdf.dispatch import bsdf_sample
from ..geometry import leave_surface, surface_at
from ..jit import inlined, kernel
from ..materials.light_path import after_scattering, after_transparent, emission_sample, path_ray
from ..materials.shader_rays import ShaderRays
from ..materials.closure_normals import orient_closures
from ..materials.surface import shade_surface
from ..materials.table import (MAT_BOUNDARY, MAT_CLOSURE_NORMALS, MAT_DELTA, MAT_DISPERSIVE, MAT_HAIR, MAT_MEDIUM,
                               MAT_NULL, MAT_ONE_SIDED)
from ..media.boundary import side_medium
from ..media.scatter import scatter_in_medium
from ..sampler import BOUNCE_DIRECTION, BOUNCE_LOBE, bounce_slot, sample_1d, sample_2d
from ..state import (CAMERA_PATH, COLLAPSED, DIRECT_SAMPLED, LAST_DIFFUSE, LAST_TRANSMISSION, MEDIUM_VERTEX,
                     PREV_DELTA, SUBSURFACE_EXIT)
from ..terminator import soften_closures
from ..vec3 import tangents, to_local, to_world
from .bounces import TRANSPARENT, bounces_left, count_crossing, path_bounce
from .caustic_split import classify_vertex
from .caustics_toggles import filter_caustic_closures
from .filter_glossy import blur_alpha, blur_glossy_closures
from .nee import sample_direct
from .surface_vertex import ResolvedBsdf, SurfaceVertex, on_its_geometric_side
from .cryptomatte_write import cryptomatte_vertex
from .data_pass_writes import camera_surface, writes_data_passes
from .pass_writes import first_bounce, surface_features
from .queue import push_ray
from .roulette import survives
from .see_through import surface_alpha
from .subsurface import lambertian_exit, walk_under_surface


@inlined
def collapse_to_hero(state, i):
    """Keep only path ``i``'s hero wavelength, ×K (the others carry nothing from now on)."""
    k = state.throughput.shape[1]
    hero = state.hero[i]
    for c in range(k):
        state.throughput[i, c] = state.throughput[i, c] * k if c == hero else 0.0
    state.flags[i] |= COLLAPSED


@inlined
def _through_transparent_glass(settings, rows, closures, sampled):
    """Whether a sampled event keeps a camera path one (Cycles' Transparent Glass)."""
    if not (settings.transparent_glass and sampled & SAMPLED_TRANSMISSION):
        return False
    for c in range(closures):
        if rows[c, C_ALPHA] > settings.transparent_alpha:
            return False
    return True


@inlined
def sample_scattering(state, i, depth, settings, rows, spectral, eta, closures, wo_l, frame, collapsed, weight, mix):
    """BSDF sampling at path ``i``'s vertex of bounce ``depth`` (its uniforms from that bounce's slots):
    (wi local, wi world, pdf, sampled flags, eta scale, largest ``weight[k]``, the closure sampled)."""
    ps = state.seed[i]
    sample = state.sample[i]
    u_lobe = sample_1d(settings.sampler, ps, sample, bounce_slot(depth, BOUNCE_LOBE))
    u1, u2 = sample_2d(settings.sampler, ps, sample, bounce_slot(depth, BOUNCE_DIRECTION))
    wi_l, pdf, sampled, eta_scale, chosen = bsdf_sample(rows, spectral, eta, closures, wo_l, state.wavelength[i],
                                                        state.hero[i], collapsed, u_lobe, u1, u2, weight, mix)
    largest = 0.0
    for c in range(weight.shape[0]):
        largest = max(largest, weight[c])
    return wi_l, to_world(wi_l, frame[0], frame[1], frame[2]), pdf, sampled, eta_scale, largest, chosen


@kernel
def shade_kernel(state, surface, count, geometry, materials, lights, spectra, settings, depth, next_rays, shadows,
                 scratch, glass_clamps, rejected, passes, layout, caster):
    """Shade the ``count`` paths listed in ``surface``; returns (rays queued in ``next_rays``, shadow
    rays queued in ``shadows``). ``scratch`` is a ``state.ShadingScratch``; ``glass_clamps`` and
    ``rejected`` (int64 counters) are incremented; ``passes`` / ``layout``: see ``stages.pass_writes``;
    ``caster`` (``embree.queries.RayCaster``) traces the rays of materials' Ambient Occlusion and Bevel nodes."""
    k = state.wavelength.shape[1]
    rows, spectral, eta, weight, li, f, mix, registers, _ = scratch
    has_lights = lights.select_prob.shape[0] > 0
    has_media = settings.has_media
    queued = 0
    shadowed = 0
    for s in range(count):
        i = surface.path[s]
        if has_media and state.flags[i] & MEDIUM_VERTEX:
            pushed, lit = scatter_in_medium(state, i, lights, materials, spectra, geometry, settings, depth, next_rays,
                                            queued, shadows, shadowed, scratch, rejected)
            queued += pushed
            shadowed += lit
            continue  # a camera path is no longer one after a medium vertex: Cryptomatte attributes it to nothing
        bounce = path_bounce(state, i, depth)
        final = not bounces_left(state, i, bounce, settings)  # only going through a cut-out or a film is left
        triangle = state.hit_triangle[i]
        p, ng, ns = surface_at(geometry, triangle, state.hit_u[i], state.hit_v[i], state.time[i])
        material = geometry.material[triangle]
        exiting = state.flags[i] & SUBSURFACE_EXIT != 0  # where a random walk left: a Lambertian lobe instead
        state.flags[i] &= ~SUBSURFACE_EXIT
        mflags = 0 if exiting else materials.flags[material]
        if mflags & MAT_DISPERSIVE and not state.flags[i] & COLLAPSED:
            collapse_to_hero(state, i)
        collapsed = state.flags[i] & COLLAPSED != 0
        wo = (-state.direction[i, 0], -state.direction[i, 1], -state.direction[i, 2])
        cos_og = wo[0] * ng[0] + wo[1] * ng[1] + wo[2] * ng[2]
        backfacing = cos_og < 0.0
        facing_ng = (-ng[0], -ng[1], -ng[2]) if backfacing else ng
        facing_ns = (-ns[0], -ns[1], -ns[2]) if backfacing else ns
        lam = state.wavelength[i]
        hero = state.hero[i]
        if settings.light_path:
            path_ray(registers, state, i, state.hit_t[i])
        rays = ShaderRays(caster, settings.sampler, state.seed[i], state.sample[i], depth, state.time[i],
                          state.min_pdf[i])
        if exiting:
            closures, n = lambertian_exit(rows, spectral), facing_ns
        else:
            closures, n = shade_surface(materials, spectra, geometry, material, triangle, state.hit_u[i],
                                        state.hit_v[i], p, facing_ng, facing_ns, wo, backfacing, lam, hero, rows,
                                        spectral, eta, registers, glass_clamps, rays)
        soften_closures(geometry, triangle, rows, closures)  # Cycles' shadow terminator Shading Offset
        if settings.caustics_filtered and depth > 0 and state.flags[i] & LAST_DIFFUSE:
            filter_caustic_closures(settings, rows, spectral, closures)
        blurred = False
        if settings.filter_glossy > 0.0:
            blurred = blur_glossy_closures(rows, closures, blur_alpha(settings, state.min_pdf[i]))
        seen_n = n if settings.shaded_normals else facing_ns  # the first-hit passes' normal, facing the ray
        flipped = backfacing and mflags & MAT_ONE_SIDED != 0
        if flipped:
            n = (-n[0], -n[1], -n[2])
        if mflags & (MAT_CLOSURE_NORMALS | MAT_HAIR):
            orient_closures(rows, closures, n, flipped)
        tangent, bitangent = tangents(n)
        frame = (tangent, bitangent, n)
        wo_l = to_local(wo, tangent, bitangent, n)
        if writes_data_passes(state, i, layout, mflags):  # a surface the camera sees, perhaps through cut-outs
            camera_surface(state, passes, layout, settings, geometry, i, p, facing_ng, facing_ns, seen_n, material,
                           triangle, registers, surface_alpha(rows, spectral, closures), bounce)
        if has_lights and not final and (not mflags & MAT_DELTA or blurred):
            if settings.light_path:
                emission_sample(registers, state, i)
            if layout.light >= 0 and bounce == 0 and (state.flags[i] & CAMERA_PATH or exiting):
                state.flags[i] |= DIRECT_SAMPLED  # light sampled before any scattering: Direct in the passes
            vertex = SurfaceVertex(p, ng, frame, wo_l, facing_ns)
            lit = sample_direct(state, i, vertex, ResolvedBsdf(rows, spectral, eta, closures, collapsed), lights,
                                materials, spectra, geometry, settings, depth, shadows, shadowed, li, f, mix, passes,
                                layout, scratch)
            if lit and has_media and mflags & MAT_MEDIUM:
                shadows.medium[shadowed] = side_medium(materials, material, shadows.direction[shadowed], ng,
                                                       state.medium[i])
            shadowed += lit
        wi_l, wi, pdf, sampled, eta_scale, largest, chosen = sample_scattering(state, i, depth, settings, rows,
                                                                               spectral, eta, closures, wo_l, frame,
                                                                               collapsed, weight, mix)
        # A film crossed straight through, or a cut-out (Transparent BSDF, alpha): a null event for MIS. Light
        # paths end at cut-outs (they are not specular), so for the caustic split only films are null.
        film_crossing = (mflags & MAT_NULL) != 0 and wo_l[2] * wi_l[2] < 0.0
        null_crossing = film_crossing or (sampled & SAMPLED_NULL) != 0
        if final and not null_crossing:
            continue
        cos_ig = wi[0] * ng[0] + wi[1] * ng[1] + wi[2] * ng[2]
        transmitted = sampled & SAMPLED_TRANSMISSION != 0
        valid = largest > 0.0 and pdf > 0.0 and on_its_geometric_side(cos_og, cos_ig, transmitted)
        if layout.columns > 0:
            if layout.cryptomatte >= 0 and state.flags[i] & CAMERA_PATH:
                cryptomatte_vertex(state, passes, layout, settings, i, depth, triangle, material, rows, spectral,
                                   closures, sampled)
            if not valid:
                weight[:] = 0.0
            if not mflags & MAT_DELTA:
                surface_features(state, passes, layout, i, p, n, weight, spectra)
            if layout.light >= 0 and state.flags[i] & CAMERA_PATH and not sampled & SAMPLED_NULL:
                first_bounce(state, passes, layout, i, rows, spectral, eta, closures, wo_l, wi_l, lam, hero, collapsed,
                             sampled, weight, mix[0], spectra)
        if not valid:
            continue
        for c in range(k):
            state.throughput[i, c] *= weight[c]
        if sampled & SAMPLED_SUBSURFACE:  # under the surface: walk now, shade the exit at the next bounce
            state.flags[i] &= ~(CAMERA_PATH | LAST_DIFFUSE | LAST_TRANSMISSION)
            if survives(state, i, depth, bounce, settings, collapsed):
                pushed = walk_under_surface(state, i, rays, geometry, triangle, rows[chosen], spectral[chosen], p,
                                            facing_ng, wi, next_rays, queued, (li, f, mix[0]))
                if pushed:  # the walk is no bounce: Cycles counts the exit's reflection alone
                    count_crossing(state, i, False)
                queued += pushed
            continue
        state.eta_scale[i] *= eta_scale
        if not sampled & SAMPLED_NULL:
            if state.flags[i] & CAMERA_PATH and not _through_transparent_glass(settings, rows, closures, sampled):
                state.flags[i] &= ~CAMERA_PATH
            state.flags[i] = (state.flags[i] & ~(LAST_DIFFUSE | LAST_TRANSMISSION)) | (
                LAST_TRANSMISSION if sampled & SAMPLED_TRANSMISSION
                else (LAST_DIFFUSE if sampled & SAMPLED_DIFFUSE else 0))
        # Roulette counts scatterings and transparent bounces apart; a volume's boundary is no bounce and plays none
        # (Cycles). A random walk's exit played at its entry.
        boundary = null_crossing and mflags & MAT_BOUNDARY != 0
        played = state.crossings[i, TRANSPARENT] if null_crossing else bounce
        if not (exiting or boundary) and not survives(state, i, depth, played, settings, collapsed):
            continue
        if null_crossing:
            count_crossing(state, i, not boundary)
        if settings.light_path or settings.kind_limits:
            if null_crossing:
                after_transparent(state, i, not boundary)
            else:
                after_scattering(state, i, sampled)
        if settings.light_tracing:
            classify_vertex(state, i, mflags, sampled, film_crossing)
        if not null_crossing:
            state.prev_pdf[i] = pdf
            if sampled & SAMPLED_DELTA:
                state.flags[i] |= PREV_DELTA
            else:
                state.flags[i] &= ~PREV_DELTA
                state.min_pdf[i] = min(state.min_pdf[i], pdf)  # Filter Glossy's measure of an unlikely path
            for c in range(3):
                state.mis_origin[i, c] = p[c]
            if settings.light_linking or settings.shadow_linking:  # the receiver of what this ray finds
                state.receiver[i] = lights.links.receiver_set[triangle]
        if has_media and mflags & MAT_MEDIUM:
            state.medium[i] = side_medium(materials, material, wi, ng, state.medium[i])
        origin, _ = leave_surface(geometry, triangle, state.hit_u[i], p, ng, wi, state.time[i])
        pushed = push_ray(state, next_rays, queued, i, origin, wi)
        queued += pushed
        rejected[0] += 1 - pushed
    return queued, shadowed
