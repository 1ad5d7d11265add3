"""Which copy of a data-block the export reads settings from: the original, or the depsgraph's evaluated one.

The original holds what the user or a script set last, even when the depsgraph has not re-copied it
(a Python edit to a setting does not tag the data-block for evaluation). But an animation render
(Render ▸ Render Animation) evaluates a depsgraph of its own per frame and leaves the original at the
current frame: keyframed or driven values are right only in the evaluated copy, which is what Cycles
reads. So: the evaluated copy where the data-block or its node tree is animated or driven, else the
original. Found by the parity harness (``benchmarks/parity``: frame_range, animated_shading).
"""

from __future__ import annotations


def _animated(datablock) -> bool:
    animation = getattr(datablock, "animation_data", None) if datablock is not None else None
    return animation is not None and (animation.action is not None or len(animation.drivers) > 0)


def settings_source(datablock):
    """``datablock`` (evaluated or original) as the copy to read its settings from (see the module)."""
    original = datablock.original
    if _animated(original) or _animated(getattr(original, "node_tree", None)):
        return datablock
    return original
