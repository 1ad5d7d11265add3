"""A pytest plugin for an environment without the bpy module (``make test-numpy``'s numpy 2 run:
bpy 4.5 pins numpy < 2). The repository root is the add-on package, and its ``__init__`` imports
bpy; pytest would import it to set the package up. Collected as a plain directory instead, the tracer
tests (which import ``engine.tracer`` only) run without it.

    PYTHONPATH=tests python -m pytest -p helpers.without_bpy tests/tracer/spectra
"""

from __future__ import annotations

from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]


@pytest.hookimpl(tryfirst=True)
def pytest_collect_directory(path, parent):
    """The repository root as a ``Dir``, not a ``Package`` (whose setup would import the add-on)."""
    if Path(path) == REPO_ROOT:
        return pytest.Dir.from_parent(parent, path=path)
    return None
