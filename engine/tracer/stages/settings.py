"""The scalars every stage reads, as one value the kernels take (``KernelSettings``)."""

from __future__ import annotations

from collections import namedtuple

#: max_bounces, roulette_depth (first vertex depth where roulette may end a path, minus one),
#: transparent_max_bounces (Cycles' Transparent Max Bounces: cut-outs and films a path goes straight through,
#: counted apart from its bounces: ``stages.bounces``),
#: use_mis, sampler (``sampler.SOBOL`` / ``INDEPENDENT``), seed; light_tracing (caustic paths come from
#: light tracing and path tracing skips them: ``stages.caustic_split``); film_transparent (the background
#: seen by camera paths is see-through), transparent_glass (camera paths stay camera paths through
#: transmission of roughness² at most ``transparent_alpha``), as Cycles' Film ▸ Transparent;
#: Cycles' Light Paths tricks (``path_tricks``): ``clamping`` (a flag: either clamp is on), ``clamp_direct`` /
#: ``clamp_indirect`` (limits on |R| + |G| + |B| of one contribution, inf when off), ``caustics_filtered`` (a
#: flag: a caustics toggle is off), ``caustics_reflective`` / ``caustics_refractive``; ``wavelengths`` the
#: render's ``WavelengthSampling`` (a clamp measures a contribution in Rec.709); ``has_media``: some material
#: has a volume inside (``media``) or the World has one: paths track their medium, and scenes without media skip
#: that code; ``outside_medium``: the ``media`` row of the World's Volume, the medium outside every mesh medium
#: (-1: vacuum); ``camera_medium``: the row camera rays start in (the mesh media around the camera with the
#: World's, ``media.nesting``, else ``outside_medium``); ``equiangular``: media and a light with a position, so collisions
#: in media are also sampled toward lights (``media.equiangular``);
#: ``filter_glossy``: 1 / Cycles' Filter Glossy, 0 when off (``stages.filter_glossy``);
#: ``light_linking`` / ``shadow_linking``: some emitter lights only some objects / has its shadows cast by
#: only some objects (``light_linking``); scenes without either skip that code; ``light_path``: some material
#: reads Blender's Light Path node (``materials.light_path``): paths keep their ray kind and bounce counts;
#: ``shaded_normals``: the first surface's Normal and AO passes take its shading normal (Bump, Normal Map)
#: instead of the interpolated one, as Cycles bakes them (a bake sets it: ``Renderer.set_bake_rays``;
#: renders keep False); ``shadow_catcher``: some object is a shadow catcher: camera paths split where they
#: meet one (``stages.shadow_catcher``); scenes without one skip that code; ``kind_limits``: some Cycles per-kind
#: limit (Max Bounces ▸ Diffuse, Glossy, Transmission, Volume) is below Max Bounces: paths count their bounces by
#: kind (``materials.light_path``) and ``bounce_limits`` (diffuse, glossy, transmission, volume) bound them
#: (``stages.bounces.bounces_left``).
KernelSettings = namedtuple(
    "KernelSettings",
    "max_bounces roulette_depth use_mis sampler seed light_tracing film_transparent transparent_glass transparent_alpha "
    "clamping clamp_direct clamp_indirect caustics_filtered caustics_reflective caustics_refractive wavelengths "
    "has_media outside_medium camera_medium equiangular filter_glossy light_linking shadow_linking light_path "
    "shaded_normals shadow_catcher transparent_max_bounces kind_limits bounce_limits",
    defaults=(False, False, 8, False, (8, 8, 8, 8)),
)
