"""``Scene.validate`` on vertices: a NaN or absurdly distant vertex that a triangle uses is refused with its
object's name; one that no triangle uses (a stray vertex) cannot spoil the image and passes."""

import math

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.primitive_checks import MAX_DISTANCE_M
from engine.tracer.scene import Camera, Material

from .tracer_scenes import look_at, make_scene, quad


def _card_with_a_stray_vertex(used, value):
    """A card (4 vertices) and a fifth vertex set to ``value``, used by a third triangle when ``used``."""
    verts, tris = quad((0, 0, 0), (1, 0, 0), (0, 1, 0))
    verts = np.vstack([verts, [value, 0.0, 0.0]])
    if used:
        tris = np.vstack([tris, [0, 1, 4]])
    camera = Camera("cam", look_at((0, 0, 3.0), (0, 0, 0), up=(0, 1, 0)), (8, 8))
    return make_scene([(verts, tris, 0)], [Material("card")], camera)


@pytest.mark.parametrize("value, message", [(math.nan, "NaN or infinite"), (math.inf, "NaN or infinite"),
                                            (10 * MAX_DISTANCE_M, "from the world origin")])
def test_a_bad_vertex_a_triangle_uses_is_refused(value, message):
    with pytest.raises(PrismInputError, match=message):
        _card_with_a_stray_vertex(True, value).validate()


@pytest.mark.parametrize("value", [math.nan, math.inf, 10 * MAX_DISTANCE_M])
def test_a_bad_vertex_no_triangle_uses_passes(value):
    _card_with_a_stray_vertex(False, value).validate()


def test_a_good_scene_passes():
    _card_with_a_stray_vertex(True, 2.0).validate()
