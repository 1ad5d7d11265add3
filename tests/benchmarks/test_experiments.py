"""The experiments folder's contract: discovery, running, failures skipped with a note, rendering."""

import sys
import types

import pytest

from benchmarks import experiments, findings_tables


@pytest.fixture
def fake_module(monkeypatch):
    """Install ``benchmarks.experiments.<name>`` as an in-memory module."""

    def install(name, **attributes):
        module = types.ModuleType(f"benchmarks.experiments.{name}")
        module.__dict__.update(attributes)
        monkeypatch.setitem(sys.modules, module.__name__, module)
        return name

    return install


def test_discovery_lists_modules_without_underscore(tmp_path, monkeypatch):
    for name in ("b_second.py", "a_first.py", "_helper.py", "README.md"):
        (tmp_path / name).write_text("")
    monkeypatch.setattr(experiments, "FOLDER", tmp_path)
    assert experiments.discover() == ["a_first", "b_second"]


def test_a_module_that_keeps_the_contract_becomes_a_section(fake_module):
    name = fake_module("good", TITLE="Texture cost",
                       run=lambda quick: {"rows": [{"scene": "a", "pass (s)": 0.123456}, {"scene": "b", "n": 3}],
                                          "summary": "Measured."})
    record = experiments.run_one(name, quick=True)
    assert record["title"] == "Texture cost" and "error" not in record
    text = "\n".join(findings_tables._experiment_section(record))
    assert "## Experiment: Texture cost" in text and "Measured." in text
    assert "| scene | pass (s) | n |" in text
    assert "| a | 0.123 |  |" in text and "| b |  | 3 |" in text


def _raises(quick):
    raise ValueError("no texture support yet")


@pytest.mark.parametrize("attributes, message", [
    (dict(TITLE="Raises", run=_raises), "ValueError: no texture support yet"),
    (dict(TITLE="No run"), "no run(quick) function"),
    (dict(TITLE="Bad rows", run=lambda quick: {"rows": "x", "summary": ""}), "must return a dict"),
    (dict(TITLE="Bad row", run=lambda quick: {"rows": [1], "summary": ""}), "every row must be a dict"),
])
def test_a_failing_module_is_skipped_with_a_note(fake_module, attributes, message):
    record = experiments.run_one(fake_module("bad", **attributes), quick=False)
    assert message in record["error"] and "rows" not in record
    text = "\n".join(findings_tables._experiment_section(record))
    assert "Skipped" in text and "bad.py" in text


def test_an_import_error_is_skipped_too():
    record = experiments.run_one("does_not_exist_here", quick=True)
    assert "ModuleNotFoundError" in record["error"]
