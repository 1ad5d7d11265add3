"""Crossing a medium's surface, in the kernels: the ``MediaArrays`` row a ray travels in on the far side
(``media.nesting`` builds the table it reads)."""

from __future__ import annotations

from ..jit import inlined


@inlined
def side_medium(materials, material, direction, ng, current):
    """The ``media`` row a ray leaving a surface of ``material`` (which holds a medium) along ``direction``
    travels in, coming from row ``current`` (-1: none): inward (against the geometric normal ``ng``) the media
    it was in and this one, outward those without this one (``media.nesting``)."""
    inward = direction[0] * ng[0] + direction[1] * ng[1] + direction[2] * ng[2] < 0.0
    return materials.media.next_medium[current + 1, materials.medium[material], 1 if inward else 0]
