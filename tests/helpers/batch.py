"""Running ``render.py`` in process (the ``blender -b -P render.py --`` argument path) and reading
what it printed."""

from __future__ import annotations

import importlib


def last_line(stderr: str) -> str:
    """The last non-empty line: where the batch script puts its one-line verdict."""
    lines = [line for line in stderr.strip().splitlines() if line.strip()]
    return lines[-1] if lines else ""


def run_batch_stderr(capsys, *arguments, in_blender: bool = True) -> tuple[int, str]:
    """``render.main`` on ``arguments`` (str()-ed); its exit status and all it printed on stderr."""
    render = importlib.import_module("render")
    capsys.readouterr()
    status = render.main([str(a) for a in arguments], in_blender=in_blender)
    return status, capsys.readouterr().err


def run_batch(capsys, *arguments, in_blender: bool = True) -> tuple[int, str]:
    """``render.main`` on ``arguments`` (str()-ed); its exit status and last stderr line."""
    status, stderr = run_batch_stderr(capsys, *arguments, in_blender=in_blender)
    return status, last_line(stderr)
