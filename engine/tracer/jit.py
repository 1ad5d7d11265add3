"""Compiled kernels: the one decorator every numba function of the tracer uses, and their disk cache.

numba is imported by this module only, and this module only by kernel modules, so nothing compiles or
imports numba until a render needs it (never at Blender start-up). Compiled machine code is cached on
disk so only the first render on a machine pays for compilation:

- ``configure_cache(directory)`` chooses the cache directory; it must be called before the first kernel
  module is imported (Blender passes a folder under the extension's user directory, which is writable
  even when the extension itself is installed read-only). Kernels go to a subfolder named after the
  package this copy of the tracer was imported as and the fingerprint of its sources
  (``kernel_directory()``; kernels compiled for a portable CPU level go to a subfolder named after it,
  ``numba_directory()``, see ``kernel_target``). Without it the directory is
  ``$PRISM_KERNEL_CACHE``, else ``$NUMBA_CACHE_DIR``, else a per-user cache folder
  (``~/.cache/prism-spectral/kernels`` on Linux, ``~/Library/Caches/...`` on macOS,
  ``%LOCALAPPDATA%\\prism-spectral\\kernels`` on Windows).
- ``cache_is_warm()`` says whether this exact tracer source was compiled into that directory before,
  so the first render can say "Compiling Prism kernels (first render only)"; ``mark_cache_warm()`` records
  it after a render compiled everything.

These cache functions live in ``kernel_folder`` (no numba there, so the add-on can ask whether the cache is
warm at Blender start-up) and are re-exported here.

``Launch`` calls a kernel from Python without the dispatcher typing its arguments on every call (the
stage kernels, called once per bounce of every chunk).

Kernel options: ``nogil`` (chunks run on threads), ``cache``, numpy's error model (a division by zero
gives inf or NaN, which the film counts and drops, instead of raising inside a kernel). No fastmath:
NaN checks must stay meaningful and the image must not depend on reassociation.
"""

from __future__ import annotations

import numba
import numpy as np
from numba.core import types
from numba.core.typing.typeof import Purpose

# The cache's folders and stamp live in a module without numba (the add-on asks them at Blender start-up).
from . import kernel_target
from .kernel_folder import (  # noqa: F401 - re-exported: jit is where kernel modules and tools look
    _PACKAGE,
    cache_directory,
    cache_is_warm,
    configure_cache,
    kernel_directory,
    mark_cache_warm,
    numba_directory,
    prepare_kernel_directory,
    source_fingerprint,
)


def _apply_cpu_target() -> None:
    """Make numba generate code for ``kernel_target.current()``: before any kernel is decorated, since
    numba makes its code generator (target machine and cache key) once, on first use."""
    target = kernel_target.current()
    if target is not kernel_target.HOST:
        before = numba.config.CPU_NAME, numba.config.CPU_FEATURES
        numba.config.CPU_NAME, numba.config.CPU_FEATURES = target, ""  # the level's own features, no more
        from numba.core.registry import cpu_target

        if cpu_target.target_context.codegen().magic_tuple()[1:] != (target, ""):
            # Something else in this process used numba first: its code generator is this CPU's.
            numba.config.CPU_NAME, numba.config.CPU_FEATURES = before
            target = kernel_target.HOST
    kernel_target.applied(target)


_apply_cpu_target()


# No NRT (numba's reference-counted memory): every array belongs to the Python caller, kernels
# allocate nothing (scratch memory is passed in), and no atomic reference counting runs per array
# access or view -- with it, a bounce cost 3-10x more, and more again with two threads sharing tables.
_OPTIONS = dict(nogil=True, cache=True, error_model="numpy", _nrt=False)
_njit = numba.njit(**_OPTIONS)
_njit_inline = numba.njit(inline="always", **_OPTIONS)


def _use_cache_directory():
    # A folder chosen through $PRISM_KERNEL_CACHE that cannot be used is an error naming it; an unusable
    # default leaves numba its own fallback (``__pycache__`` next to the sources, or no cache).
    if prepare_kernel_directory():
        numba.config.CACHE_DIR = str(numba_directory())  # read by numba when a function is decorated


def kernel(function):
    """Decorator for kernels and the per-path functions they call (compiled on first use, once per signature,
    cached). A kernel called from a kernel is linked into it, and LLVM inlines it there when it is small."""
    _use_cache_directory()
    return _njit(function)


def inlined(function):
    """Decorator for large per-path functions that take the scene's tables (named tuples of arrays): inlined
    where they are called, so the tables are not passed as hundreds of flattened arguments per call. numba
    copies and types the body again at every call site, which costs compile time there: a function called
    from many places that takes arrays or small tables is better a ``kernel`` (docs/tracer_core.md)."""
    _use_cache_directory()
    return _njit_inline(function)


class Launch:
    """Calls ``kernel`` (a compiled kernel) from Python without numba typing every argument on every call.

    numba's dispatcher types each argument to pick the machine code; a named tuple of tables is typed in
    Python, array by array: ~15-20 µs per stage kernel call, with the GIL held, on every bounce of every
    chunk. Here an array's type is looked up by its dtype and flags, a table tuple's by identity (the
    same tables serve a whole render), and the machine code compiled for exactly those types is called
    directly (its wrapper still releases the GIL). Anything not compiled yet for those types goes
    through the dispatcher, which compiles or converts as usual."""

    _TUPLES_KEPT = 64  # tuples whose types are remembered (a few per render; new ones push old ones out)

    def __init__(self, kernel):
        self.kernel = kernel
        self.__name__ = kernel.__name__
        self.__wrapped__ = kernel
        self._arrays = {}
        self._tuples = {}
        self._compiled = {}

    def _type(self, value):
        kind = type(value)
        if kind is np.ndarray:
            flags = value.flags
            key = (value.dtype, value.ndim, flags.c_contiguous, flags.f_contiguous, flags.writeable, flags.aligned)
            found = self._arrays.get(key)
            if found is None:
                found = self._arrays[key] = numba.typeof(value, Purpose.argument)
            return found
        if kind is int and -(1 << 63) <= value < (1 << 63):
            return types.int64
        if kind is float:
            return types.float64
        if kind is bool:
            return types.boolean
        if isinstance(value, tuple):
            kept = self._tuples.get(id(value))
            if kept is not None and kept[0] is value:  # the tuple is kept alive, so its id is not reused
                return kept[1]
            found = numba.typeof(value, Purpose.argument)
            if len(self._tuples) >= self._TUPLES_KEPT:
                self._tuples.clear()
            self._tuples[id(value)] = (value, found)
            return found
        return numba.typeof(value, Purpose.argument)

    def __call__(self, *args):
        argument_types = tuple([self._type(a) for a in args])
        # numba's types are interned: their ids name them (hashing the types themselves costs ~30 µs)
        key = tuple([id(t) for t in argument_types])
        found = self._compiled.get(key)
        if found is None:
            compiled = self.kernel.overloads.get(argument_types)
            if compiled is None:
                return self.kernel(*args)
            found = self._compiled[key] = (argument_types, compiled.entry_point)  # the types stay alive
        return found[1](*args)
