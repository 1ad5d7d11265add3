"""Bake types Prism does not bake (Shadow, UV, Roughness, Environment), and objects camera rays do not see,
are refused with one error naming the object, the bake type or the setting, and the bake writes nothing."""

from __future__ import annotations

import numpy as np
import pytest

from helpers.bake_scenes import bake, baked_image, node_material, uv_plane


@pytest.mark.parametrize("bake_type, name", [("SHADOW", "Shadow"), ("UV", "UV"), ("ROUGHNESS", "Roughness"),
                                             ("ENVIRONMENT", "Environment")])
def test_unsupported_bake_types_are_refused_by_name(prism_addon, fresh_scene, bad_input, bake_type, name):
    material = node_material("Grey", "ShaderNodeBsdfDiffuse")
    plane = uv_plane("Floor", 2.0, material)
    with pytest.raises(RuntimeError) as refused:
        bake(fresh_scene, "PRISM", plane, bake_type, 4)
    assert np.all(baked_image(material)[..., :3] == 0.0)
    message = str(refused.value)
    assert f"Prism cannot bake '{name}' (Render ▸ Bake ▸ Bake Type)" in message and "'Floor'" in message
    bad_input(f"Bake type {name}", 1, message.splitlines()[0].removeprefix("Error: "))


def test_an_object_camera_rays_do_not_see_is_refused_by_name(prism_addon, fresh_scene, bad_input):
    material = node_material("Grey", "ShaderNodeBsdfDiffuse")
    plane = uv_plane("Ghost", 2.0, material)
    plane.visible_camera = False
    with pytest.raises(RuntimeError) as refused:
        bake(fresh_scene, "PRISM", plane, "COMBINED", 4)
    message = str(refused.value)
    assert "Object 'Ghost' is hidden from camera rays" in message and "Ray Visibility ▸ Camera" in message
    bad_input("Bake of an object hidden from camera rays", 1, message.splitlines()[0].removeprefix("Error: "))
