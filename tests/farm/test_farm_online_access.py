"""The Farm panel talks HTTP to a Flamenco Manager, so the manifest declares the ``network`` permission,
and while Blender's Allow Online Access is off (``bpy.app.online_access`` False, read-only: patched here
through ``operators.online_access``) Prism makes no request: the submit operator refuses naming the
preference, the panel says so and greys the button out."""

from __future__ import annotations

import tomllib
from pathlib import Path

import bpy
import pytest

from helpers import panel_layout

REPO_ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def offline(prism_addon, monkeypatch):
    """Online access off, and every HTTP request the Flamenco client would make recorded."""
    requests = []
    monkeypatch.setattr(prism_addon.operators.online_access, "online_access_allowed", lambda: False)
    manager = prism_addon.farm.manager.FlamencoManager
    monkeypatch.setattr(manager, "_request", lambda self, method, path, body=None: requests.append(path) or {})
    return requests


def test_manifest_declares_the_network_permission_with_a_reason():
    manifest = tomllib.loads((REPO_ROOT / "blender_manifest.toml").read_text("utf-8"))
    reason = manifest["permissions"]["network"]
    assert "Flamenco" in reason and len(reason) <= 64 and not reason.endswith(".")  # Blender's limits


def test_submit_makes_no_request_while_online_access_is_off(offline, fresh_scene, tmp_path):
    fresh_scene.prism.farm.manager_url = "http://127.0.0.1:8080"
    fresh_scene.prism.farm.output_path = str(tmp_path / "out" / "prism_####.exr")
    with pytest.raises(RuntimeError) as refused:  # an ERROR report raises in background mode
        bpy.ops.prism.farm_submit()
    assert "online access is off" in str(refused.value)
    assert "Preferences ▸ System ▸ Network" in str(refused.value)
    assert offline == []  # not even the version probe
    assert not (tmp_path / "out").exists()


def test_panel_says_online_access_is_off_and_greys_out_submit(prism_addon, offline, fresh_scene):
    log = panel_layout.draw(prism_addon.ui.panel_farm.PRISM_PT_farm, panel_layout.context(fresh_scene))
    assert any("online access is off" in text for text in panel_layout.labels(log))
    assert offline == []


def test_panel_has_no_warning_while_online_access_is_on(prism_addon, fresh_scene, monkeypatch):
    monkeypatch.setattr(prism_addon.operators.online_access, "online_access_allowed", lambda: True)
    log = panel_layout.draw(prism_addon.ui.panel_farm.PRISM_PT_farm, panel_layout.context(fresh_scene))
    assert not any("online access" in text for text in panel_layout.labels(log))
