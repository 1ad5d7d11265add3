"""Bake types and pass filters → the passes Prism renders and how they add up, as Cycles 4.5 sets up a bake
(``BlenderSession::bake``): light passes divided by colour unless Color is on, Color alone the colour, the
Combined filter's switches summing what is left on, and the image itself when every switch is on."""

import numpy as np
import pytest

from engine.render.bake_types import (FILTER_COLOR, FILTER_DIFFUSE, FILTER_DIRECT, FILTER_EMIT, FILTER_GLOSSY,
                                      FILTER_INDIRECT, BakeTerm, bake_recipe, baked_value, refusal)

EVERYTHING = -1  # what Blender hands over when the operator's filter is left at its default


def test_light_kinds_follow_direct_indirect_and_color():
    assert bake_recipe("DIFFUSE", EVERYTHING).terms == (BakeTerm(("DiffDir", "DiffInd"), "DiffCol"),)
    assert bake_recipe("GLOSSY", FILTER_DIRECT).terms == (BakeTerm(("GlossDir",)),)
    assert bake_recipe("TRANSMISSION", FILTER_INDIRECT | FILTER_COLOR).terms == (BakeTerm(("TransInd",), "TransCol"),)
    assert bake_recipe("DIFFUSE", FILTER_COLOR).terms == (BakeTerm(("DiffCol",)),)
    assert bake_recipe("DIFFUSE", 0).terms == (BakeTerm(("DiffCol",)),)


def test_the_combined_filter_sums_what_is_left_on():
    assert bake_recipe("COMBINED", EVERYTHING).terms == (BakeTerm(("Combined",)),)
    assert bake_recipe("COMBINED", EVERYTHING).passes == ()
    recipe = bake_recipe("COMBINED", FILTER_DIRECT | FILTER_DIFFUSE | FILTER_GLOSSY | FILTER_EMIT)
    assert recipe.terms == (BakeTerm(("DiffDir",), "DiffCol"), BakeTerm(("GlossDir",), "GlossCol"),
                            BakeTerm(("Emit",)))
    assert set(recipe.passes) == {"DiffDir", "DiffCol", "GlossDir", "GlossCol", "Emit"}
    assert bake_recipe("COMBINED", FILTER_EMIT | FILTER_DIFFUSE).terms == (BakeTerm(("Emit",)),)


def test_first_hit_types_need_no_bounce():
    for bake_type, name in (("EMIT", "Emit"), ("NORMAL", "Normal"), ("AO", "AO"), ("POSITION", "Position")):
        recipe = bake_recipe(bake_type, EVERYTHING)
        assert recipe.first_hit_only and recipe.passes == (name,)


def test_the_baked_value_adds_light_times_colour():
    shape = (2, 3, 3)
    passes = {"DiffDir": np.full(shape, 2.0), "DiffInd": np.full(shape, 0.5), "DiffCol": np.full(shape, 0.4),
              "Emit": np.full(shape, 0.1)}
    image = np.full(shape, 7.0)
    assert np.allclose(baked_value(bake_recipe("DIFFUSE", EVERYTHING), image, passes), 1.0)
    assert np.allclose(baked_value(bake_recipe("COMBINED", EVERYTHING), image, passes), 7.0)
    combined = bake_recipe("COMBINED", FILTER_DIRECT | FILTER_DIFFUSE | FILTER_EMIT)
    assert np.allclose(baked_value(combined, image, {**passes, "GlossDir": passes["Emit"]}), 0.9)


@pytest.mark.parametrize("bake_type", ["SHADOW", "UV", "ROUGHNESS", "ENVIRONMENT", "SOMETHING_NEW"])
def test_other_types_are_refused_by_their_menu_name(bake_type):
    message = refusal(bake_type)
    assert message.startswith("Prism cannot bake '") and "Render ▸ Bake ▸ Bake Type" in message
    with pytest.raises(ValueError):
        bake_recipe(bake_type, EVERYTHING)
    assert refusal("COMBINED") is None
