"""Output files of a batch run: whole or not at all, and Ctrl-C noted rather than raised mid-write."""

from __future__ import annotations

import os
import signal

import pytest

from engine.batch.output_files import atomic_output, frame_output, numbered_output, partial_output
from engine.batch.stop_signals import StopSignals
from engine.tracer.errors import PrismInputError


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    output = tmp_path / "render.exr"
    output.write_bytes(b"yesterday")
    with pytest.raises(RuntimeError), atomic_output(output) as temporary:
        temporary.write_bytes(b"half an ima")
        raise RuntimeError("the writer died")
    assert output.read_bytes() == b"yesterday" and os.listdir(tmp_path) == ["render.exr"]
    with atomic_output(output) as temporary:
        assert temporary.parent == output.parent and "#" not in temporary.name and temporary.suffix == ".exr"
        temporary.write_bytes(b"today")
    assert output.read_bytes() == b"today" and os.listdir(tmp_path) == ["render.exr"]


def test_a_writer_that_writes_nothing_is_an_error_not_a_missing_file(tmp_path):
    with pytest.raises(PrismInputError, match="wrote no image for"), atomic_output(tmp_path / "x.png"):
        pass
    assert os.listdir(tmp_path) == []


def test_frame_and_partial_names(tmp_path):
    assert frame_output(tmp_path / "shot_###.png", 7).name == "shot_007.png"
    assert frame_output(tmp_path / "shot.png", -3).name == "shot_-003.png"
    assert partial_output(tmp_path / "shot_007.exr").name == "shot_007.partial.exr"
    # One frame (no --frames): '#' becomes its number, a name without '#' stays as given.
    assert numbered_output(tmp_path / "v2_##_shot_###.png", 7).name == "v2_##_shot_007.png"
    assert numbered_output(tmp_path / "shot_#.exr", -12).name == "shot_-12.exr"
    assert numbered_output(tmp_path / "shot.exr", 7) == tmp_path / "shot.exr"


def test_the_first_signal_asks_to_stop_and_handlers_are_restored():
    before = signal.getsignal(signal.SIGINT)
    with StopSignals() as signals:
        assert not signals.stop_requested()
        os.kill(os.getpid(), signal.SIGINT)  # Python runs the handler at the next bytecode: no KeyboardInterrupt
        assert signals.stop_requested() and signals.exit_status == 130 and signals.signal_name() == "SIGINT"
    assert signal.getsignal(signal.SIGINT) is before
