"""Silencing what Blender's C code prints during a render ("Fra:", "Time:", "Saved:"): it writes to the
process's file descriptors 1 and 2 directly, past Python's sys.stdout, so those are pointed at /dev/null
for the block. Prism's own lines go to the request's progress stream and are kept."""

from __future__ import annotations

import os
import sys
from contextlib import contextmanager


@contextmanager
def blender_output_silenced():
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        os.dup2(null, 2)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for descriptor in (*saved, null):
            os.close(descriptor)
