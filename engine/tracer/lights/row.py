"""A light as a row of numbers (float64 [LIGHT_ROW]), positions in metres relative to the camera.

Columns: ``L_KIND``; ``L_SPECTRUM`` (spectrum-table id of its luminance-normalised spectrum);
``L_SCALE`` (intensity W/sr of a point/spot, radiance of a sphere, area light or sun disc, irradiance
W/m² of a delta sun); ``L_P*`` (position or centre); ``L_N*`` (spot axis, area normal — the side that
emits — or the direction toward the sun); ``L_U*``, ``L_V*`` (area axes); ``L_HALF_U``, ``L_HALF_V``,
``L_AREA``; ``L_RADIUS`` (sphere); ``L_SPOT`` (1 for spots), ``L_COS_HALF`` (cosine of half the spot
size), ``L_SMOOTH`` ((1 - cos_half) · blend); ``L_COS_MAX``, ``L_ONE_MINUS_COS`` (sun disc);
``L_LIMB`` (limb darkening of a sun disc: radiance × (1 - L_LIMB (1 - μ)), μ the cosine on the solar
surface); ``L_CAMERA`` (1: seen by camera rays); ``L_SPREAD_TAN`` (tan of half an area light's spread,
0: no spread limit), ``L_SPREAD_NORM`` (the spread falloff's normalisation); ``L_SOFT`` (1: a point or
spot light with Blender's Soft Falloff, its radius a disc facing what it lights, ``lights.point``).
"""

from __future__ import annotations

POINT = 0  # delta (spot when L_SPOT)
SPHERE = 1  # a point/spot light with a radius
RECTANGLE = 2
DISK = 3
SUN = 4  # delta direction
SUN_DISK = 5  # a sun with an angular diameter, seen by escaping rays
MESH = 6  # every emissive triangle, one light for selection
ENVIRONMENT = 7  # the world's background (``lights.environment``), one light for selection
KIND_NAMES = {POINT: "point", SPHERE: "point", RECTANGLE: "area", DISK: "area", SUN: "sun", SUN_DISK: "sun",
              MESH: "emissive meshes", ENVIRONMENT: "world"}

(L_KIND, L_SPECTRUM, L_SCALE, L_PX, L_PY, L_PZ, L_NX, L_NY, L_NZ, L_UX, L_UY, L_UZ, L_VX, L_VY, L_VZ, L_HALF_U,
 L_HALF_V, L_AREA, L_RADIUS, L_SPOT, L_COS_HALF, L_SMOOTH, L_COS_MAX, L_ONE_MINUS_COS, L_LIMB, L_CAMERA, L_SPREAD_TAN,
 L_SPREAD_NORM, L_SOFT) = range(29)
LIGHT_ROW = 29
