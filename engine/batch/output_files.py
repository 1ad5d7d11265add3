"""Output files of a batch run: written whole or not at all, named per frame.

Every image goes to a temporary file in the output's own folder and is then
moved onto the output's name with one ``os.replace`` (atomic on POSIX and
Windows within a file system): a reader, a crash or Ctrl-C sees either the old
file or the complete new one.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..tracer.errors import PrismInputError


def frame_output(output: Path, frame: int) -> Path:
    """An output of a frame range: ``out_###.png`` → ``out_007.png``; without ``#``,
    ``out.png`` → ``out_0007.png`` (every frame needs its own file)."""
    if "#" in output.name:
        return numbered_output(output, frame)
    return output.with_name(f"{output.stem}_{frame:04d}{output.suffix}")


def numbered_output(output: Path, frame: int) -> Path:
    """The last run of ``#`` in the file name becomes ``frame``, zero-padded to its length (the sign
    counts), as Blender numbers its outputs: ``out_###.png`` → ``out_007.png``. A name without
    ``#`` is returned as it is."""
    name = output.name
    runs = list(re.finditer(r"#+", name))
    if not runs:
        return output
    run = runs[-1]
    return output.with_name(f"{name[: run.start()]}{frame:0{len(run.group())}d}{name[run.end():]}")


def partial_output(output: Path) -> Path:
    """Where an interrupted render's image goes when asked to keep it: ``out.exr`` → ``out.partial.exr``."""
    return output.with_name(f"{output.stem}.partial{output.suffix}")


def temporary_sibling(output: Path) -> Path:
    """A hidden name in ``output``'s folder, unique to this process, with the same suffix (the
    writers choose the format by it) and no ``#`` (Blender would put a frame number there)."""
    stem = output.stem.replace("#", "_")
    return output.with_name(f".{stem}.prism-{os.getpid()}.tmp{output.suffix}")


def _cannot_write(path: Path, error: OSError) -> PrismInputError:
    return PrismInputError(
        f"Cannot write '{path}': {error.strerror or error}. Choose a folder that exists and that you can write to."
    )


def _check_folders(output: Path) -> None:
    for folder in reversed(output.parents):
        if folder.exists() and not folder.is_dir():
            raise PrismInputError(
                f"Cannot write '{output}': '{folder}' is a file, not a folder. Choose another output folder."
            )


def check_writable(output: Path) -> None:
    """``PrismInputError`` naming ``output`` unless a file can be written there (its folder is created)."""
    temporary = temporary_sibling(output)
    _check_folders(output)
    try:
        output.parent.mkdir(parents=True, exist_ok=True)
        temporary.touch()
        temporary.unlink()
    except OSError as error:
        raise _cannot_write(output, error) from None


@contextmanager
def atomic_output(output: Path, signals=None) -> Iterator[Path]:
    """Yield a temporary path for ``output``; when the block ends normally, move it onto ``output``.

    When the block raises, the temporary file is deleted and ``output`` is left as
    it was. ``signals`` (a ``StopSignals``) deletes it too if the process is
    killed by a second Ctrl-C. The folder is created, and checked writable,
    before the block runs, so a render never starts only to fail at the end.
    """
    output = Path(output)
    temporary = temporary_sibling(output)
    check_writable(output)
    if signals is not None:
        signals.temporary_files.add(temporary)
    try:
        yield temporary
        if not temporary.is_file():
            raise PrismInputError(f"Prism rendered but Blender wrote no image for '{output}': see Blender's message above.")
        try:
            os.replace(temporary, output)
        except OSError as error:
            raise _cannot_write(output, error) from None
    finally:
        if temporary.exists():
            temporary.unlink()
        if signals is not None:
            signals.temporary_files.discard(temporary)
