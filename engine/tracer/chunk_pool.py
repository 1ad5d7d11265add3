"""A pass's chunks on Prism's worker threads: cut into chunks, run a bounded window of them at a time,
results handed back in chunk order, cancellable from any thread.

Chunk order is what keeps an image independent of the thread count: the film adds samples in path
order (see ``film``), so results are consumed in the order the chunks were cut, whichever thread
finished first.
"""

from __future__ import annotations

import os
import threading
from concurrent.futures import CancelledError, ThreadPoolExecutor

MAX_CHUNK_PATHS = 1 << 16  # largest chunk one thread traces at once (memory ~0.5 kB per path)
#: Below this a chunk's fixed cost (a few compiled calls from Python, ~50 µs with the GIL held, and copying
#: its results) is no longer small against its paths' tracing (~1 µs a path and more).
MIN_CHUNK_PATHS = 1024
#: Chunks per worker thread in a pass: paths differ in length (glass, escapes), so one chunk per thread
#: leaves threads idle at the end of the pass; a few each let the pool balance them.
CHUNKS_PER_THREAD = 4
#: Chunks in flight per worker thread: bounds the memory of a huge frame's results waiting their turn.
WINDOW_PER_THREAD = 4


def chunk_size(path_count: int, threads: int, samples_per_pixel: int = 1) -> int:
    """Paths per chunk: ``CHUNKS_PER_THREAD`` chunks per thread (each chunk holds the GIL for its few
    compiled calls from Python, so not more), within the bounds above, and a multiple of ``samples_per_pixel`` (a chunk never
    splits a pixel's samples of a pass: see ``film``)."""
    chunks = max(threads, 1) * CHUNKS_PER_THREAD
    size = max(MIN_CHUNK_PATHS, min(MAX_CHUNK_PATHS, -(-path_count // chunks)))
    return int(max(samples_per_pixel, size - size % samples_per_pixel))


def available_cores() -> int:
    """The CPUs this process may run on (its affinity mask, which containers and ``taskset`` narrow), else
    every CPU the machine has."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # macOS and Windows have no affinity mask in Python
        return max(1, os.cpu_count() or 1)


def worker_threads(requested: int) -> int:
    """Threads for ``requested`` (0 or less: one per available core), at most one per available core: a
    chunk is compiled work that never waits on I/O, so threads beyond the cores only take turns on them, and
    each brings its own chunk's state into the caches they share (a 384 x 384 pass ran at 0.71x the paths per
    second of 2 threads with 16 on 2 cores). Images do not depend on the thread count (``film``)."""
    cores = available_cores()
    return min(cores, int(requested)) if requested and requested > 0 else cores


class ChunkPool:
    """Worker threads that run a pass's chunks; ``cancel()`` stops the pass in progress."""

    def __init__(self, requested_threads: int):
        self.workers = worker_threads(requested_threads)
        self._executor = ThreadPoolExecutor(self.workers)
        self._cancel = threading.Event()
        self._lock = threading.Lock()
        self._jobs = {}

    def chunks(self, path_count: int, samples_per_pixel: int) -> list[tuple[int, int]]:
        """(start, stop) of each chunk of a pass of ``path_count`` paths."""
        size = chunk_size(path_count, self.workers, samples_per_pixel)
        bounds = list(range(0, path_count, size)) + [path_count]
        return list(zip(bounds[:-1], bounds[1:]))

    def resize(self, requested_threads: int) -> None:
        """Use ``worker_threads(requested_threads)`` threads from now on (between passes)."""
        workers = worker_threads(requested_threads)
        if workers != self.workers:
            self._executor.shutdown(wait=True)
            self.workers, self._executor = workers, ThreadPoolExecutor(workers)

    @property
    def cancelled(self) -> bool:
        return self._cancel.is_set()

    def reset(self) -> None:
        """Accept work again after a cancel."""
        self._cancel.clear()

    def run(self, chunks, work):
        """Run ``work(*chunk)`` for each chunk, ``WINDOW_PER_THREAD`` per thread in flight; yields
        (index, result) in chunk order. Stops early once cancelled; the caller calls ``drop()`` when it
        is done (also on an error) so no chunk is left queued or running."""
        jobs = self._jobs
        window = WINDOW_PER_THREAD * self.workers
        for i in range(len(chunks)):
            with self._lock:
                for j in range(i, min(i + window, len(chunks))):
                    if j not in jobs and not self._cancel.is_set():
                        jobs[j] = self._executor.submit(work, *chunks[j])
            job = jobs.get(i)
            if job is None:
                return
            try:
                result = job.result()
            except CancelledError:
                return
            with self._lock:
                del jobs[i]
            yield i, result
            if self._cancel.is_set():
                return

    def cancel(self) -> None:
        """Stop the pass in progress (thread-safe, returns at once): queued chunks are dropped, running
        ones finish; nothing new starts until ``reset``."""
        self._cancel.set()
        with self._lock:
            jobs = list(self._jobs.values())
        for job in jobs:
            job.cancel()

    def drop(self) -> None:
        """Cancel queued chunks and wait for running ones (after a pass, a cancel or an error)."""
        with self._lock:
            jobs = list(self._jobs.values())
            self._jobs.clear()
        for job in jobs:
            job.cancel()
        for job in jobs:
            if not job.cancelled():
                try:
                    job.result()
                except Exception:  # noqa: BLE001 - the pass is abandoned anyway
                    pass

    def close(self) -> None:
        """Cancel outstanding work and stop the threads (idempotent)."""
        self._cancel.set()
        self.drop()
        self._executor.shutdown(wait=True, cancel_futures=True)

    def close_now(self) -> None:
        """Stop the threads without waiting (a renderer being garbage-collected)."""
        self._executor.shutdown(wait=False, cancel_futures=True)
