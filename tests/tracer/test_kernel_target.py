"""Kernels compiled for a portable CPU level (``kernel_target``): numba generates code for that level,
keys and caches it apart from this CPU's own kernels, and shipped kernels land where numba looks."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from engine.tracer import kernel_folder, kernel_target

ROOT = Path(__file__).resolve().parents[2]
LEVEL = "x86-64-v3"


def test_the_subfolder_of_each_tracer_folder_is_numbas():
    from numba.core.caching import _CacheLocator

    folders = kernel_folder.tracer_source_folders()
    assert folders[0] == kernel_folder.tracer_root() == Path(os.path.abspath(kernel_folder.__file__)).parent
    assert {"stages", "bsdf", "media"} <= {f.name for f in folders}
    for folder in folders:
        assert kernel_folder.numba_subfolder(folder) == _CacheLocator.get_suitable_cache_subpath(str(folder / "m.py"))


def test_a_level_has_its_own_folder_and_stamp(tmp_path, monkeypatch):
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path))
    assert kernel_folder.numba_directory(kernel_target.HOST) == kernel_folder.kernel_directory()
    assert kernel_folder.numba_directory(LEVEL) == kernel_folder.kernel_directory() / LEVEL
    kernel_folder.mark_cache_warm(LEVEL)
    assert kernel_folder.cache_is_warm(LEVEL) and not kernel_folder.cache_is_warm(kernel_target.HOST)


def test_unknown_levels_are_refused():
    with pytest.raises(ValueError, match="unknown kernel CPU target 'pentium'"):
        kernel_target.use("pentium")


_COMPILE = """
import json, sys
from engine.tracer import kernel_target
kernel_target.use(sys.argv[1] or None)
from engine.warmup.child import compile_counter
compiled = compile_counter()
import numpy as np
from engine.tracer import jit
from engine.tracer.spectra import dispersion
from numba.core.registry import cpu_target
row = np.array([1.0, 300.0, 2500.0, 1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653])
index, _ = dispersion.refractive_index(row, 587.56)
print(json.dumps({"index": index, "compiled": len(compiled), "numba_cache": jit.numba.config.CACHE_DIR,
                  "magic": list(cpu_target.target_context.codegen().magic_tuple()), "target": kernel_target.current()}))
"""


def _compile(level: str, cache: Path) -> dict:
    environment = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    environment["PRISM_KERNEL_CACHE"] = str(cache)
    result = subprocess.run([sys.executable, "-c", _COMPILE, level], cwd=ROOT, env=environment, capture_output=True,
                            text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.splitlines()[-1])


@pytest.mark.skipif(not kernel_target.host_supports(LEVEL), reason=f"this CPU cannot run {LEVEL} code")
def test_a_portable_level_compiles_caches_and_loads_apart_from_the_hosts(tmp_path):
    first = _compile(LEVEL, tmp_path)
    assert abs(first["index"] - 1.5168) < 1e-4  # N-BK7 at the d line, computed by v3 code
    assert first["target"] == LEVEL and first["magic"][1:] == [LEVEL, ""]
    level_folder = Path(first["numba_cache"])
    assert level_folder.name == LEVEL and first["compiled"] > 0
    assert list(level_folder.rglob("dispersion.refractive_index-*.nbi"))
    again = _compile(LEVEL, tmp_path)  # a fresh process loads the level's kernel: nothing compiles
    assert again["compiled"] == 0 and again["index"] == first["index"]
    host = _compile("", tmp_path)  # this CPU's kernels are keyed apart: they compile
    assert host["target"] is None and host["magic"][1] != LEVEL and host["compiled"] > 0
    assert Path(host["numba_cache"]) == level_folder.parent


def test_numba_set_up_before_the_choice_keeps_this_cpus_kernels(tmp_path):
    # Something else used numba first: its code generator is this CPU's, so jit falls back to this CPU's
    # kernels (and folder) rather than key this CPU's code as the level's.
    code = ("from numba.core.registry import cpu_target; cpu_target.target_context.codegen()\n"
            "from engine.tracer import kernel_target; kernel_target.use('x86-64-v3')\n"
            "from engine.tracer import jit, kernel_folder\n"
            "assert kernel_target.current() is None, kernel_target.current()\n"
            "assert jit.numba_directory() == kernel_folder.kernel_directory()\n"
            "try:\n    kernel_target.use('x86-64-v3')\nexcept RuntimeError as e:\n    print(e)\n")
    environment = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    environment["PRISM_KERNEL_CACHE"] = str(tmp_path)
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=environment, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "kernels are already compiled for this CPU in this process"
