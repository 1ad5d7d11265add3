"""The kernel cache folder a user chooses through ``$PRISM_KERNEL_CACHE`` is used, or refused by name:
never replaced without a word by numba's ``__pycache__`` beside the sources. Imports no numba."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from engine.tracer import kernel_folder
from engine.tracer.errors import PrismInputError

ROOT = Path(__file__).resolve().parents[2]


def test_a_chosen_folder_is_created_and_used(tmp_path, monkeypatch):
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path / "kernels"))
    assert kernel_folder.prepare_kernel_directory()
    assert kernel_folder.kernel_directory().is_dir()
    assert kernel_folder.kernel_directory().is_relative_to(tmp_path / "kernels")


@pytest.mark.parametrize("variable", ["PRISM_KERNEL_CACHE", "NUMBA_CACHE_DIR"])
def test_a_chosen_path_that_is_a_file_is_refused_by_name(tmp_path, monkeypatch, variable):
    taken = tmp_path / "cache.txt"
    taken.write_text("a file")
    monkeypatch.delenv("PRISM_KERNEL_CACHE", raising=False)
    monkeypatch.setenv(variable, str(taken))
    with pytest.raises(PrismInputError, match=rf"^{variable} is '{taken}', where Prism cannot keep its compiled "
                                              rf"kernels \(it is a file, not a folder\): point {variable} at a folder"):
        kernel_folder.prepare_kernel_directory()
    monkeypatch.setenv(variable, str(taken / "below"))
    with pytest.raises(PrismInputError, match=r"\(a file stands where one of its folders should be\)"):
        kernel_folder.prepare_kernel_directory()
    assert taken.read_text() == "a file"


def test_the_check_imports_no_numba(tmp_path):
    code = ("import sys; from engine.tracer import kernel_folder; kernel_folder.prepare_kernel_directory(); "
            "sys.exit('numba' in sys.modules)")
    environment = dict(os.environ, PRISM_KERNEL_CACHE=str(tmp_path / "k"))
    assert subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=environment).returncode == 0
