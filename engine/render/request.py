"""What a caller asks of one render and what that render reports back.

Blender creates the ``RenderEngine`` and calls its ``render()`` itself, so a batch
script cannot pass arguments to it. ``render_request`` hands a ``RenderRequest``
over for the renders started inside a ``with`` block and yields the
``RenderReport`` those renders fill::

    with render_request(RenderRequest(samples=16)) as report:
        bpy.ops.render.render()
    if report.error: ...

The hand-over lives in a ``ContextVar`` scoped to the block, so nothing outlives
it: a render started elsewhere (F12, another thread) sees no request and uses
the scene's settings, and a report never carries an earlier render's result.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # numpy stays unimported until a render needs it
    import numpy as np


@dataclass
class RenderRequest:
    """Overrides for a render: ``None`` keeps the scene's setting.

    ``sample_offset``: start at this sample of the seed's sequence (chunked
    renders). ``quick_first_pass``: show a 1-sample pass first (interactive
    renders; it changes the random sequence, so batch renders turn it off).
    ``keep_film``: put the float64 mean and the render's fingerprint in the
    report. ``progress_stream``: where to print one line per pass and the
    warnings (e.g. ``sys.stderr``). ``stop_requested``: polled between chunks;
    returning True stops the render as Esc does (batch renders: Ctrl-C).
    ``noise_threshold`` (0: adaptive sampling off), ``min_samples`` and
    ``time_limit_s`` (0: none) override the scene's Sampling settings.
    ``spectral_output``: also write a multispectral EXR there (absolute path;
    None: the scene's Spectral Output setting decides).
    ``show_image``: a finished scene-linear image [H, W, 3] (row 0 at the top) to
    put in the Render Result instead of tracing the scene, so Blender's own
    writers can save it with a scene's output settings (``engine.output.png``).
    """

    samples: int | None = None
    seed: int | None = None
    threads: int | None = None
    noise_threshold: float | None = None
    min_samples: int | None = None
    time_limit_s: float | None = None
    sample_offset: int = 0
    quick_first_pass: bool = True
    keep_film: bool = False
    progress_stream: object = None
    stop_requested: Callable[[], bool] | None = None
    spectral_output: str | None = None
    show_image: np.ndarray | None = None


@dataclass
class FilmSnapshot:
    """The float64 mean [H, W, 3] (row 0 = top) of a finished render, what it was
    rendered from (``fingerprint``, see ``engine.render.fingerprint``) and its samples."""

    mean: np.ndarray
    samples: int
    sample_offset: int
    seed: int
    fingerprint: dict[str, str]


@dataclass
class RenderReport:
    """What one render did.

    ``started``: Prism's engine ran (False when Blender refused the render before
    calling it). ``error``: the message of a failure the user can act on, else
    None. ``cancelled``: stopped early (Esc, or the request's ``stop_requested``);
    the Render Result then holds a partial image. ``warnings``: inputs Prism
    ignored or approximated. ``stats``: the status-bar line of the last pass.
    ``film``: set when the request asked for it and the render finished.
    ``spectral_output``: the multispectral EXR written, if any. ``output_errors``: secondary outputs that
    could not be written (the render and its image stand).
    """

    started: bool = False
    error: str | None = None
    cancelled: bool = False
    warnings: list[str] = field(default_factory=list)
    stats: str = ""
    film: FilmSnapshot | None = None
    spectral_output: str | None = None
    output_errors: list[str] = field(default_factory=list)


_handover: ContextVar[tuple[RenderRequest, RenderReport] | None] = ContextVar("prism_render_request", default=None)


@contextmanager
def render_request(request: RenderRequest | None = None) -> Iterator[RenderReport]:
    """Hand ``request`` (default: the scene's settings, as F12) to the Prism renders
    started inside the block; yield the report they fill."""
    report = RenderReport()
    token = _handover.set((request or RenderRequest(), report))
    try:
        yield report
    finally:
        _handover.reset(token)


def handed_over() -> tuple[RenderRequest, RenderReport]:
    """The request and report of the enclosing ``render_request`` block, or fresh
    defaults (the scene's settings, a report nobody reads) outside one."""
    return _handover.get() or (RenderRequest(), RenderReport())
