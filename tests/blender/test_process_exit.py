"""The bpy processes leave with ``os._exit`` (render.py, the test suite); what they create in the
system temporary folder must go with them all the same."""

import getpass
import os
import subprocess
import sys
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]


def _environment_with_temporary_folder(folder: Path) -> dict:
    environment = dict(os.environ, TMPDIR=str(folder), PYTEST_DEBUG_TEMPROOT=str(folder))
    environment.pop("PYTEST_ADDOPTS", None)
    return environment


def test_render_script_removes_blenders_session_folder(tmp_path):
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    missing = tmp_path / "missing.blend"  # bpy is loaded before the file is looked for
    completed = subprocess.run(
        [sys.executable, str(REPO_ROOT / "render.py"), str(missing), "--output", str(tmp_path / "out.png")],
        capture_output=True, text=True, timeout=300, env=_environment_with_temporary_folder(temporary),
    )
    assert completed.returncode == 1, completed.stderr
    assert "does not exist" in completed.stderr
    assert sorted(path.name for path in temporary.iterdir()) == []


def test_a_second_signal_quits_at_once_without_leaving_anything(tmp_path):
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    leftover = tmp_path / "render.exr.prism-tmp"
    script = f"""
import os, signal, sys, time
from pathlib import Path
import bpy
sys.path.insert(0, {str(REPO_ROOT)!r})
from engine.batch.stop_signals import StopSignals
open({str(leftover)!r}, "wb").close()
with StopSignals() as signals:
    signals.temporary_files.add(Path({str(leftover)!r}))
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(0.1)
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(5)
print("not reached")
"""
    completed = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300,
                               env=_environment_with_temporary_folder(temporary))
    assert completed.returncode == 143, completed.stderr
    assert completed.stderr.strip().splitlines()[-1] == "Prism: SIGTERM again: quitting now."
    assert "not reached" not in completed.stdout
    assert not leftover.exists()
    assert sorted(path.name for path in temporary.iterdir()) == []


def test_a_passing_test_run_removes_its_folders_and_keeps_three_earlier_runs(tmp_path):
    temporary = tmp_path / "tmp"
    runs = temporary / f"pytest-of-{getpass.getuser()}"
    for number in range(5):  # folders of five earlier runs that failed (unlocked, as this suite leaves them)
        (runs / f"pytest-{number}" / "test_that_failed0").mkdir(parents=True)
    one_test = "tests/blender/test_batch_arguments.py::test_output_that_is_a_folder_is_refused"
    completed = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", one_test],
        cwd=REPO_ROOT, capture_output=True, text=True, timeout=300,
        env=_environment_with_temporary_folder(temporary),
    )
    assert completed.returncode == 0, completed.stdout + completed.stderr
    assert "1 passed" in completed.stdout
    left = sorted(str(path.relative_to(temporary)) for path in temporary.rglob("*"))
    assert not any(name.startswith("blender_") for name in left), left
    assert not any(path.name == ".lock" for path in temporary.rglob(".lock")), left
    assert sorted(path.name for path in runs.glob("pytest-[0-9]*")) == ["pytest-2", "pytest-3", "pytest-4"], \
        "pytest keeps the newest three runs' folders and removes a passing run's own"
    assert not (runs / "pytest-5").exists()
