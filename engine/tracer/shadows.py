"""Shadow rays, with free-standing films treated as see-through.

A free-standing film (soap bubble) transmits undeviated (wi = -wo), so light behind
it reaches a point along the straight shadow ray, attenuated by the film's
transmittance T = 1 - R(lambda, theta). Shadow rays therefore pass through film
triangles (closest-hit queries, layer by layer) and pick up T per wavelength; any
other triangle blocks. The path side treats a film transmission as a null event
(it keeps the MIS data of the vertex before it), so light through films is counted
once, by the power heuristic. Without films in the scene, shadow rays are single
occlusion queries.
"""

from __future__ import annotations

import numpy as np

from .accel import REJECTED
from .path_state import offset_origin
from .sampling import dot

MAX_FILM_LAYERS = 8  # film crossings followed per shadow ray; a last occlusion query covers the rest


class ShadowTester:
    def __init__(self, accel, triangles, bsdfs, film_material):
        """``film_material`` [M+1] bool: which material indices are free-standing films."""
        self.accel = accel
        self.tris = triangles
        self.bsdfs = bsdfs
        self.film_material = film_material
        self.see_through = bool(film_material.any())

    def transmittance(self, origin, direction, tmax, lam):
        """Fraction [m,K] of light arriving along each shadow ray (0: blocked), and rays cast."""
        m, k = lam.shape
        if not self.see_through:
            blocked = self.accel.occluded(origin, direction, tmax)
            return np.where(blocked, 0.0, 1.0)[:, None] * np.ones((1, k)), m
        trans = np.ones((m, k))
        active = np.arange(m)
        o = np.array(origin, dtype=np.float64)
        remaining = np.array(tmax, dtype=np.float64)
        rays = 0
        for _ in range(MAX_FILM_LAYERS):
            if len(active) == 0:
                return trans, rays
            d = direction[active]
            tri, t, bu, bv = self.accel.intersect(o[active], d)
            rays += len(active)
            trans[active[tri == REJECTED]] = 0.0
            hit = (tri >= 0) & (t < remaining[active])
            mat = self.tris.material[np.where(hit, tri, 0)]
            film = hit & self.film_material[mat]
            trans[active[hit & ~film]] = 0.0
            if not film.any():
                return trans, rays
            rows = active[film]
            p, ng, _ = self.tris.surface(tri[film], bu[film], bv[film])
            cos = np.abs(dot(d[film], ng))
            for mi in np.unique(mat[film]):
                sel = mat[film] == mi
                r = self.bsdfs[mi].reflectance(np.clip(cos[sel], 0.0, 1.0), lam[rows[sel]])
                trans[rows[sel]] *= 1.0 - np.clip(r, 0.0, 1.0)
            o[rows] = offset_origin(p, ng, d[film])
            remaining[rows] -= t[film]
            active = rows
        if len(active):
            blocked = self.accel.occluded(o[active], direction[active], remaining[active])
            rays += len(active)
            trans[active[blocked]] = 0.0
        return trans, rays
