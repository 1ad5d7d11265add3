"""What the batch script (``render.py`` in process, on the current scene) does with a bad input: refuse it
with one error line, or render and print the warning. Both return (exit status, the line shown) for the
bad-input inventory."""

from __future__ import annotations

from .batch import run_batch, run_batch_stderr


def batch_refusal(capsys, tmp_path, message: str) -> tuple[int, str]:
    """The batch render of the current scene exits 1 with ``Prism: error: <message>`` and writes nothing."""
    output = tmp_path / "refused.png"
    status, line = run_batch(capsys, "--samples", 1, "--output", output)
    assert (status, line) == (1, f"Prism: error: {message}")
    assert not output.exists()
    return status, line


def batch_warning(capsys, tmp_path, warning: str) -> tuple[int, str]:
    """The batch render of the current scene renders (exit 0) and prints ``Prism: warning: <warning>``."""
    output = tmp_path / "warned.png"
    status, stderr = run_batch_stderr(capsys, "--samples", 1, "--output", output)
    shown = f"Prism: warning: {warning}"
    assert status == 0 and output.is_file(), stderr
    assert shown in stderr, stderr
    return status, shown
