"""What a parity scene is (``ParityScene``) and what comparing it found (``ParityResult``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

#: The verdict where both engines support what a scene uses: |mean luminance Prism / Cycles - 1| below it.
LUMINANCE_TOLERANCE = 0.02

#: How the frame(s) of a scene are rendered and read back: one image; every view layer of one render (a
#: multilayer EXR, the layers side by side); every frame of the scene's frame range (an animation render,
#: the frames side by side).
OUTPUTS = ("still", "layers", "frames")


@dataclass(frozen=True)
class ParityScene:
    """One scene of the harness.

    ``build()`` builds it in the current (emptied) file. ``exercises`` names the Blender settings it
    uses, in the UI's words. ``samples`` per pixel for both engines: as few as keep the 2 % verdict clear
    of noise (see docs/parity.md, "Noise"). ``expected_warning``: a phrase of the warning Prism prints
    because it does not model something the scene uses; the scene then gets that warning instead of a
    ratio verdict. ``known_difference``: why the engines differ beyond tolerance, found and not yet
    fixed (the test marks the scene xfail with it). ``bounces``: the bounce limit of both engines.
    """

    name: str
    exercises: str
    build: Callable[[], None]
    samples: int = 16
    output: str = "still"
    bounces: int = 4
    expected_warning: str | None = None
    known_difference: str | None = None

    def __post_init__(self):
        assert self.output in OUTPUTS, self.output


@dataclass
class EngineImage:
    """One engine's render of a scene: scene-linear RGBA [H, W, 4] (row 0 on top; several layers or
    frames side by side), what Prism warned or refused with, and the render's wall time."""

    rgba: np.ndarray | None
    seconds: float
    warnings: list[str] = field(default_factory=list)
    error: str | None = None


@dataclass
class ParityResult:
    """A scene compared: ``ratio`` = mean Rec.709 luminance Prism / Cycles (absolute, linear), ``rel_mse``
    = mean over pixels and channels of (Prism - Cycles)² / (Cycles² + 0.01), ``alpha_difference`` = mean
    |alpha Prism - alpha Cycles|; None where an image is missing (refused, or of another size)."""

    scene: ParityScene
    prism: EngineImage
    cycles: EngineImage
    ratio: float | None
    rel_mse: float | None
    alpha_difference: float | None
    picture: str | None = None  # the side-by-side PNG, relative to the docs folder

    @property
    def matched_warning(self) -> str | None:
        """The warning Prism printed that names what the scene expects it not to model."""
        phrase = self.scene.expected_warning
        if phrase is None:
            return None
        found = [w for w in self.prism.warnings + [self.prism.error or ""] if phrase in w]
        return found[0] if found else None

    @property
    def within_tolerance(self) -> bool:
        return self.ratio is not None and abs(self.ratio - 1.0) < LUMINANCE_TOLERANCE

    @property
    def verdict(self) -> str:
        """'match', 'differs', 'warned' (an expected warning printed), 'silent' (expected a warning, none
        came) or 'no image'."""
        if self.scene.expected_warning is not None:
            return "warned" if self.matched_warning else "silent"
        if self.ratio is None:
            return "no image"
        return "match" if self.within_tolerance else "differs"
