"""--merge with numbers at the edge of their range: a merge answers in time and memory that do not
grow with --expect-samples, naming the missing chunks as ranges."""

from __future__ import annotations

import importlib
import time
import tracemalloc

import numpy as np

from helpers.batch import run_batch


def _chunk(chunks, parts, start, end, name):
    return chunks.Chunk(mean=np.full((2, 3, 3), 0.25), seed=0, sample_ranges=((start, end),),
                        fingerprint={part: "1" for part in parts}, png_settings={}, path=name)


def _modules(prism_addon):
    chunks = importlib.import_module(f"{prism_addon.__name__}.engine.render.chunks")
    parts = importlib.import_module(f"{prism_addon.__name__}.engine.render.fingerprint").PARTS
    return chunks, parts


def test_expect_samples_of_two_to_the_32_answers_at_once(prism_addon, tmp_path, capsys, bad_input):
    chunks, parts = _modules(prism_addon)
    chunks.write_chunk(tmp_path / "c0.exr", _chunk(chunks, parts, 0, 1, "c0.exr"))
    began = time.perf_counter()
    tracemalloc.start()
    status, line = run_batch(capsys, "--merge", tmp_path / "c0.exr", "--expect-samples", 4294967296,
                             "--output", tmp_path / "m.exr")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    # Was 8 GB in 60 s (a string per missing chunk); the time bound leaves room for a loaded machine.
    assert peak < 50e6 and time.perf_counter() - began < 60
    assert (status, line) == (1, "Prism: error: The chunk holds 1 of the 4294967296 samples --expect-samples asks "
                                 "for: samples 1..4294967295 are missing (render the 4294967295 chunks from "
                                 "--chunk-seed 1 to 4294967295 with --samples 1).")
    assert not (tmp_path / "m.exr").exists()
    bad_input("--merge c0.exr --expect-samples 4294967296 (one 1-sample chunk)", status, line)


def test_many_gaps_are_summarised_as_the_first_ranges(prism_addon):
    chunks, parts = _modules(prism_addon)
    held = [_chunk(chunks, parts, s, s + 2, f"c{s}.exr") for s in range(0, 40, 6)]  # holds 0-1, 6-7, ...
    try:
        chunks.merge_chunks(held, expect_samples=2**32)
    except chunks.PrismInputError as error:
        message = str(error)
    else:
        raise AssertionError("the merge should be refused")
    assert message == ("The 7 chunks hold 14 of the 4294967296 samples --expect-samples asks for: samples "
                              "2..5, samples 8..11, samples 14..17, samples 20..23 and 3 more range(s) are missing "
                              "(render the 2147483641 chunks --chunk-seed 1..2, 4..5, 7..8, 10..11 and 3 more "
                              "range(s) with --samples 2).")
