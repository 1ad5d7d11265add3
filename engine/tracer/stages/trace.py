"""One chunk of camera paths: the camera stage, then the whole bounce loop in one compiled call.

``stages.bounce_loop`` runs every bounce without the GIL, Embree included. Scenes where some object
hides from some kinds of rays (``visibility_accel.RayClassAccel``: one Embree scene per kind of ray,
chosen per ray in Python), and renders whose queries a benchmark records (``Accel.compiled_loops``
off), still run the loop here, bounce by bounce: the same kernels in the same order, with the queries
on whole queues in between, and the same image.
"""

from __future__ import annotations

from ..camera_clip import clip_far_hits
from ..jit import Launch
from . import bake_camera as _bake_camera
from . import bounce_loop as _bounce_loop
from . import camera as _camera
from . import data_pass_writes as _data_passes
from . import emission as _emission
from . import film as _film
from . import pass_writes as _passes
from . import real_lens as _real_lens
from . import shade as _shade
from . import shadow as _shadow
from . import shadow_catcher as _shadow_catcher
from .bounces import step_limit
from .shadow import shadow_layers

# Called per bounce of every chunk: launched without the dispatcher's per-call typing (``jit.Launch``).
camera_kernel = Launch(_camera.camera_kernel)
bake_camera_kernel = Launch(_bake_camera.bake_camera_kernel)
real_lens_kernel = Launch(_real_lens.real_lens_kernel)
emission_kernel = Launch(_emission.emission_kernel)
shade_kernel = Launch(_shade.shade_kernel)
film_layer_kernel = Launch(_shadow.film_layer_kernel)
shadow_kernel = Launch(_shadow.shadow_kernel)
route_emission_kernel = Launch(_passes.route_emission_kernel)
route_shadows_kernel = Launch(_passes.route_shadows_kernel)
route_end_kernel = Launch(_passes.route_end_kernel)
reset_kernel = Launch(_passes.reset_kernel)
convert_kernel = Launch(_passes.convert_kernel)
ao_kernel = Launch(_data_passes.ao_kernel)
film_kernel = Launch(_film.film_kernel)
catcher_start_kernel = Launch(_shadow_catcher.catcher_start_kernel)
catcher_film_kernel = Launch(_shadow_catcher.catcher_film_kernel)
bounce_loop_kernel = Launch(_bounce_loop.bounce_loop_kernel)



def _trace_shadows(renderer, state, shadows, count, passes, layout, scratch):
    """Deliver the light of the first ``count`` shadow rays that reach their lights; returns rays cast."""
    tables = renderer.tables
    accel = tables.accel if tables.ray_classes is None else tables.ray_classes
    rays = 0
    # a shadow catcher's copies see only catchers (``visibility_accel``): their paths' flags say which
    paths = (state,) if tables.ray_classes is not None else ()
    if (tables.analysis.see_through_films or tables.analysis.see_through_cutouts
            or tables.kernel_settings.has_media or tables.kernel_settings.shadow_linking):
        for layer in range(shadow_layers(tables.kernel_settings.transparent_max_bounces)):
            if count == 0:
                return rays
            hit = accel.intersect_before(shadows.rays, count, *paths)
            rays += count
            count = film_layer_kernel(state, shadows, count, *hit, tables.geometry, tables.material_table.arrays,
                                      passes, layout, tables.spectra, scratch, tables.light_table.arrays, layer)
    if count:
        occluded = accel.occluded(shadows.rays, count, *paths)
        rays += count
        shadow_kernel(state, shadows, count, occluded, passes, layout)
    return rays


def trace_chunk(renderer, buffers, first, count, samples_per_pixel, first_sample, glass_clamps):
    """Trace paths ``first .. first + count`` of the pass into ``buffers`` (``buffers.rgb[:count]`` holds
    their colours afterwards); returns (rays cast, rays dropped as non-finite)."""
    state = buffers.state
    tables = renderer.tables
    settings = tables.kernel_settings
    materials = tables.material_table.arrays
    lights = tables.light_table.arrays
    geometry = tables.geometry
    spectra = tables.spectra
    wavelengths = tables.wavelengths
    rejected = buffers.counters
    rejected[0] = 0
    current = buffers.rays[0]
    if renderer.bake_rays is not None:  # a bake: each pixel's ray from the renderer's table
        queued = bake_camera_kernel(state, current, renderer.bake_rays, wavelengths, settings, renderer._pixels,
                                    first, count, samples_per_pixel, first_sample)
    elif renderer.camera.lens is None:
        queued = camera_kernel(state, current, renderer.camera.data, wavelengths, settings,
                               renderer._pixels, first, count, samples_per_pixel, first_sample)
    else:
        queued = real_lens_kernel(state, current, renderer.camera.data, renderer.camera.lens_tables,
                                  wavelengths, settings, renderer._pixels, first, count, samples_per_pixel,
                                  first_sample)
    rejected[0] += count - queued
    passes = renderer.pass_data(buffers)
    layout = tables.pass_layout.kernel
    if layout.columns:
        reset_kernel(passes, layout, count)
    if settings.shadow_catcher:  # its scenes trace here, with ray classes (``visibility_accel``)
        catcher_start_kernel(passes, count)
    see_through = bool(tables.analysis.see_through_films or tables.analysis.see_through_cutouts
                        or tables.kernel_settings.has_media or tables.kernel_settings.shadow_linking)
    if tables.ray_classes is None and tables.accel.compiled_loops:
        accel = tables.accel  # held until the call returns: it owns the Embree scene the loop traces
        rays_cast = bounce_loop_kernel(buffers.loop, tables.arrays, accel.caster(), renderer.camera.data, passes,
                                       layout, count, queued, glass_clamps, see_through, layout.light >= 0)
        return rays_cast, int(rejected[0])
    route_light = layout.light >= 0
    rays_cast = 0
    for depth in range(step_limit(settings.max_bounces, settings.transparent_max_bounces)):
        if queued == 0:
            break
        if tables.ray_classes is None:
            hit = tables.accel.intersect(current, queued)
        else:
            hit = tables.ray_classes.intersect(current, queued, state, depth)
        if depth == 0:
            hit = clip_far_hits(hit, current, queued, renderer.camera.data)
        rays_cast += queued
        surfaces = emission_kernel(state, current, queued, *hit, geometry, materials, lights, spectra, settings,
                                   depth, buffers.surface, passes, layout, buffers.scratch, tables.accel.caster())
        if route_light:
            route_emission_kernel(state, passes, layout, current, queued, depth)
        if surfaces == 0:
            break
        following = buffers.rays[1] if current is buffers.rays[0] else buffers.rays[0]
        queued, shadowed = shade_kernel(state, buffers.surface, surfaces, geometry, materials, lights, spectra,
                                        settings, depth, following, buffers.shadows, buffers.scratch, glass_clamps,
                                        rejected, passes, layout, tables.accel.caster())
        if shadowed:
            rays_cast += _trace_shadows(renderer, state, buffers.shadows, shadowed, passes, layout, buffers.scratch)
        if route_light:
            route_shadows_kernel(state, passes, layout, buffers.surface, surfaces)
        if layout.ao >= 0 and passes.ao_count[0] > 0:  # the AO pass's rays see every object
            ao_rays = int(passes.ao_count[0])
            passes.ao_free[:ao_rays] = tables.accel.occluded(passes.ao_rays, ao_rays)
            rays_cast += ao_rays
            ao_kernel(passes, layout, ao_rays)
        current = following
    if route_light:
        route_end_kernel(state, passes, layout, count)
    film_kernel(state, count, wavelengths, buffers.rgb)
    if layout.slots:
        convert_kernel(state, passes, layout, wavelengths, count)
    if settings.shadow_catcher:
        catcher_film_kernel(state, passes, layout, wavelengths, buffers.rgb, count)
    return rays_cast, int(rejected[0])
