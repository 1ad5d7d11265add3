"""What both peer runners share: the command line, timing sweeps, output files.

A peer runs in its own process (``python -m benchmarks.peers.<name> ...``) so a
crash in its JIT or in bpy's exit cannot take the harness down, and writes an
``.npz`` with ``spp`` [S], ``seconds`` [R, S], ``images`` [R, S, H, W, 3] and, for
a reference, ``reference`` / ``reference_variance`` [H, W, 3] (variance of the
mean, from independent chunks).
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np


def parse_args(description: str):
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--resolution", type=int, default=64)
    parser.add_argument("--spp", type=int, nargs="*", default=[])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--first-repeat", type=int, default=0,
                        help="number of the first repeat (its seeds): a harness can interleave single repeats")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--max-bounces", type=int, default=8)
    parser.add_argument("--reference-spp", type=int, default=0, help="total spp of a reference (0: none)")
    parser.add_argument("--reference-chunks", type=int, default=8)
    parser.add_argument("--out", required=True)
    return parser.parse_args()


def sweep(render, spp_list, repeats, first_repeat=0):
    """Fresh renders at each spp, ``repeats`` times with distinct seeds (repeat ``r`` has the same
    seeds whichever process renders it).

    ``render(spp, seed) -> (image [H, W, 3], seconds)``: the renderer times only
    its own work. Returns (seconds [R, S], images [R, S, H, W, 3])."""
    seconds, images = [], []
    for r in range(first_repeat, first_repeat + repeats):
        row_t, row_i = [], []
        for k, spp in enumerate(spp_list):
            image, t = render(spp, 1000 * (r + 1) + k)
            row_t.append(t)
            row_i.append(image)
        seconds.append(row_t)
        images.append(row_i)
    return np.array(seconds), np.array(images, dtype=np.float32)


def reference(render, total_spp, chunks):
    """Mean and variance of the mean of ``chunks`` independent renders."""
    per = max(1, total_spp // chunks)
    start = time.perf_counter()
    parts = np.array([render(per, 7_000_000 + c)[0] for c in range(chunks)], dtype=np.float64)
    elapsed = time.perf_counter() - start
    mean = parts.mean(axis=0)
    variance = parts.var(axis=0, ddof=1) / chunks
    return mean.astype(np.float32), variance.astype(np.float32), per * chunks, elapsed


def save(path, args, spp_list, seconds, images, info, ref=None):
    data = dict(spp=np.asarray(spp_list, dtype=np.int64), seconds=seconds, images=images,
                info=np.array(json.dumps(info)))
    if ref is not None:
        mean, variance, ref_spp, ref_seconds = ref
        data.update(reference=mean, reference_variance=variance, reference_spp=ref_spp,
                    reference_seconds=ref_seconds)
    np.savez_compressed(path, **data)


def load(path):
    """The peer's output as a dict (``info`` decoded)."""
    with np.load(path, allow_pickle=False) as f:
        out = {k: f[k] for k in f.files}
    out["info"] = json.loads(str(out["info"]))
    return out
