"""One package name for the tracer in the whole test run: ``engine...`` imports ``prism_spectral.engine...``.

Tracer tests import ``engine.tracer...`` (the repository root on sys.path); Blender tests, the batch
renders they start and the warm-up child use the add-on as ``prism_spectral``. numba's kernel cache is
kept per package name (``engine.tracer.kernel_folder``: the index pickles kernel argument types by
module name), so under two names every kernel compiled twice per run, several minutes each. With this
alias both spellings are one module object, named ``prism_spectral.engine...``, whose kernels compile
once into one cache folder. The add-on's ``__init__`` (which imports bpy) is not run by the alias:
tracer tests still run without Blender.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys

from render import ADDON_PACKAGE, addon_package_shell

ALIASED = "engine"


class EngineAlias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds ``engine`` and ``engine.*`` as the already-importable ``prism_spectral.engine...``."""

    def __init__(self) -> None:
        self._real_specs: dict[str, object] = {}

    def find_spec(self, fullname, path=None, target=None):
        if fullname != ALIASED and not fullname.startswith(ALIASED + "."):
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        module = importlib.import_module(f"{ADDON_PACKAGE}.{spec.name}")
        # importlib sets ``__spec__`` to the alias's spec after this; exec_module puts the real one back.
        self._real_specs[module.__name__] = module.__spec__
        return module

    def exec_module(self, module) -> None:
        module.__spec__ = self._real_specs.pop(module.__name__)


def install() -> None:
    """Alias ``engine`` before any test module imports it (idempotent)."""
    if any(isinstance(finder, EngineAlias) for finder in sys.meta_path):
        return
    if ALIASED in sys.modules:
        raise RuntimeError(f"'{ALIASED}' was imported before the alias: its kernels would compile twice")
    addon_package_shell()
    sys.meta_path.insert(0, EngineAlias())
