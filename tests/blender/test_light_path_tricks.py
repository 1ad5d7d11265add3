"""Cycles' Light Paths tricks read from a scene: only the values it sets (Prism's default stays unbiased),
and true warnings for what Prism renders differently."""

from __future__ import annotations

from importlib import import_module

import pytest


@pytest.fixture
def tricks(prism_addon):
    return import_module(f"{prism_addon.__name__}.engine.export.light_path_tricks")


def test_cycles_defaults_are_not_applied_but_set_values_are(prism_addon, fresh_scene, tricks):
    settings = import_module(f"{prism_addon.__name__}.engine.export.settings")
    assert fresh_scene.cycles.sample_clamp_indirect == 10.0  # Cycles' default, never set on this scene
    default = settings.export_settings(fresh_scene).light_path_tricks
    assert not default.biased and default.clamp_indirect == 0.0 and default.filter_glossy == 0.0
    fresh_scene.cycles.sample_clamp_direct = 4.0
    fresh_scene.cycles.sample_clamp_indirect = 10.0  # set explicitly, even to Cycles' default value: honoured
    fresh_scene.cycles.caustics_refractive = False
    read = settings.export_settings(fresh_scene).light_path_tricks
    assert (read.clamp_direct, read.clamp_indirect, read.caustics_reflective, read.caustics_refractive) == (
        4.0, 10.0, True, False)
    assert read.kernel_limits() == (12.0, 30.0)  # Cycles' kernel compares |R| + |G| + |B| with 3 × the limit
    assert tricks.light_path_trick_warnings(fresh_scene) == []


def test_reflective_only_is_warned_and_filter_glossy_is_rendered(prism_addon, fresh_scene, tricks):
    """Filter Glossy is rendered (``test_filter_glossy.py``), so it is read and not warned."""
    settings = import_module(f"{prism_addon.__name__}.engine.export.settings")
    fresh_scene.cycles.blur_glossy = 1.0
    fresh_scene.cycles.caustics_reflective = False
    messages = tricks.light_path_trick_warnings(fresh_scene)
    assert not any("Filter Glossy" in m for m in messages)
    assert any("Reflective is off" in m and "reflection of glass" in m for m in messages)
    read = settings.export_settings(fresh_scene).light_path_tricks
    assert read.filter_glossy == 1.0 and read.biased
