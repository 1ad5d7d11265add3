"""Wavefront unidirectional path tracer with next-event estimation and MIS.

One call traces a chunk of camera paths bounce by bounce: every step is a numpy
operation over all live paths (one Embree batch per bounce, one occlusion batch
for shadow rays). Radiance is carried per wavelength [n,K].

Estimator. At each surface vertex (up to ``max_bounces`` bounces, as Cycles: 0 =
direct light only) one light is chosen (probability proportional to its power) and
sampled (next-event estimation, skipped on pure-delta materials), and the BSDF is
sampled to continue. Hits on emitters by BSDF-sampled rays and light samples are
combined with the power heuristic. ``use_mis=False``: light samples carry full
weight, emitters hit by BSDF rays count only after a delta (specular) bounce, on
camera rays, or if they are never light-sampled (the world). Both are unbiased.
Blender lights are invisible to camera rays (they appear in reflections); the
world is found only by escaping rays (BSDF sampling), so its weight is 1.
Russian roulette from ``russian_roulette_depth`` keeps a path with probability
min(1, sqrt(max throughput x eta'^2 scale)) and divides survivors by it (unbiased for
any probability > 0). The square root (Cycles' choice) kills dim paths later than
min(1, throughput) (pbrt's): on the grey Cornell box (albedo 0.6) it costs 8 % more
rays for 21 % less variance.

Wavelengths: a path carries K wavelengths; its hero column is uniform over the K
columns. At a dispersive material (and at a dispersive camera) only the hero is
kept, x K, the others are zeroed: each column's estimate stays unbiased because
it is the hero with probability 1/K. Scenes without dispersion never run that code.
"""

from __future__ import annotations

import numpy as np

from .accel import REJECTED
from .bsdf.diffuse import Diffuse, DiffuseSet
from .path_state import (add_rows, collapse_to_hero, compact, offset_distance, offset_origin, roll_columns,
                         shading_frame, unroll_columns)
from .sampling import dot, power_heuristic, row_max, rows_finite, to_local, to_world, where_rows
from .shadows import ShadowTester
from .path_spectra import PathWavelengths

SHADOW_SHORTEN = 1e-4  # shadow rays stop this fraction short of the light sample


def continuation_probability(throughput):
    """Russian-roulette survival probability [n] of paths whose largest per-wavelength
    throughput (x eta'^2 scale, per carried wavelength) is ``throughput`` [n]."""
    return np.minimum(1.0, np.sqrt(throughput))


class Integrator:
    def __init__(self, accel, triangles, bsdfs, lights, mode, camera, settings, analysis):
        self.accel = accel
        self.tris = triangles
        self.bsdfs = bsdfs
        self.lights = lights
        self.mode = mode
        self.camera = camera
        self.settings = settings
        self.analysis = analysis
        self.use_mis = bool(settings.use_mis)
        self.max_depth = int(settings.max_bounces)
        self.rr_depth = int(settings.russian_roulette_depth)
        self.delta_material = np.array([b is not None and b.delta for b in bsdfs] + [True], dtype=bool)
        self.two_sided = np.array([b is None or b.two_sided for b in bsdfs] + [True], dtype=bool)
        self.disperses = np.array([b is not None and b.disperses for b in bsdfs] + [False], dtype=bool)
        self.film_material = np.array([b is not None and b.kind == "thin_film" for b in bsdfs] + [False], dtype=bool)
        self.shadows = ShadowTester(accel, triangles, bsdfs, self.film_material)
        # All plain diffuse materials form one shading group (one call, see DiffuseSet).
        self.group = np.arange(len(bsdfs) + 1)
        diffuse = {i: b for i, b in enumerate(bsdfs) if type(b) is Diffuse}
        self.diffuse_set = DiffuseSet(diffuse, len(bsdfs) + 1) if len(diffuse) > 1 else None
        self.diffuse_group = min(diffuse) if self.diffuse_set is not None else -1
        self.group[list(diffuse)] = self.diffuse_group

    # -- helpers over material groups ------------------------------------------------
    def _by_material(self, mat, method, inputs, n_outputs, outputs=None):
        """Run BSDF ``method`` per shading group (a material, or all diffuse materials)
        present in ``mat`` [n] and reassemble its ``n_outputs`` row arrays in row order
        (``outputs(result)`` -> tuple). One stable argsort per call: gathers and the final
        un-permutation are ``np.take`` (row fancy indexing of 2-D arrays is several times
        slower), rows keep their order within a group."""
        outputs = outputs or (lambda r: r)
        if len(mat) == 0:
            return outputs(getattr(self.bsdfs[0], method)(*inputs))
        key = self.group[mat] if self.diffuse_set is not None else mat
        if key.min() == key.max():  # one group: no gather/scatter
            return outputs(self._call(int(key[0]), mat, method, inputs))
        order = np.argsort(key, kind="stable")
        sorted_key = np.take(key, order)
        cuts = np.flatnonzero(sorted_key[1:] != sorted_key[:-1]) + 1
        parts = []
        for a, b in zip(np.concatenate([[0], cuts]), np.concatenate([cuts, [len(mat)]])):
            rows = order[a:b]
            g = int(sorted_key[a])
            sub_mat = np.take(mat, rows) if g == self.diffuse_group else None
            parts.append(outputs(self._call(g, sub_mat, method, tuple(np.take(x, rows, axis=0) for x in inputs))))
        inverse = np.empty_like(order)
        inverse[order] = np.arange(len(order))
        return tuple(np.take(np.concatenate([part[j] for part in parts]), inverse, axis=0)
                     for j in range(n_outputs))

    def _call(self, g, mat, method, inputs):
        if g == self.diffuse_group and mat.min() != mat.max():
            return getattr(self.diffuse_set, method)(mat, *inputs)
        m = int(mat[0]) if g == self.diffuse_group else g
        return getattr(self.bsdfs[m], method)(*inputs)

    def _eval(self, mat, wo, wi, lam, hero, collapsed):
        return self._by_material(mat, "eval", (wo, wi, lam, hero, collapsed), 2)

    def _sample(self, mat, wo, lam, u, hero, collapsed):
        return self._by_material(mat, "sample", (wo, lam, u, hero, collapsed), 5,
                                 lambda s: (s.wi, s.weight, s.pdf, s.delta, s.eta_scale))

    # -- camera ----------------------------------------------------------------------
    def camera_rays(self, pixel_xy, lens_uv, lam, hero):
        if getattr(self.camera, "disperses", False):
            o, d, w = self.camera.generate_rays(pixel_xy, lens_uv, roll_columns(lam, hero))
            return o, d, unroll_columns(np.asarray(w, dtype=np.float64), hero), True
        o, d, w = self.camera.generate_rays(pixel_xy, lens_uv, lam)
        return o, d, np.asarray(w, dtype=np.float64), False

    # -- the path loop ---------------------------------------------------------------
    def trace(self, pixel_xy, lens_uv, lam, hero, rng):
        """Trace one path per row; returns (radiance [n,K], rays_cast)."""
        n, k = lam.shape
        o, d, beta, cam_collapsed = self.camera_rays(pixel_xy, lens_uv, lam, hero)
        lam = PathWavelengths(lam)
        radiance = np.zeros((k, n))  # wavelength-major: see add_rows
        idx = np.arange(n)
        collapsed = np.full(n, cam_collapsed)
        live = (row_max(beta) > 0) & rows_finite(beta)
        if not live.all():  # e.g. rays a real lens blocks: nothing to trace
            idx, o, d, beta, lam, hero, collapsed = compact(live, idx, o, d, beta, lam, hero, collapsed)
        mis_o = o.copy()  # last vertex that was not a film crossing: light pdfs are measured from it
        prev_pdf = np.zeros(len(idx))
        prev_delta = np.ones(len(idx), dtype=bool)
        eta_scale = np.ones(len(idx))
        rays = 0
        lights = self.lights
        for depth in range(self.max_depth + 2):
            if len(idx) == 0:
                break
            tri, t, bu, bv = self.accel.intersect(o, d)
            rays += len(idx)
            sent = tri != REJECTED
            if not sent.all():  # a non-finite ray: the path ends here, adding nothing
                idx, o, d, t, tri, bu, bv, beta, lam, hero, collapsed, eta_scale, mis_o, prev_pdf, prev_delta = compact(
                    sent, idx, o, d, t, tri, bu, bv, beta, lam, hero, collapsed, eta_scale, mis_o, prev_pdf, prev_delta)
            light_id = np.full(len(idx), -1)
            if depth > 0:
                for li, light in lights.hittable:
                    tl = light.intersect(o, d)
                    closer = tl < t
                    t = np.where(closer, tl, t)
                    light_id = np.where(closer, li, light_id)
            on_light = light_id >= 0
            tri = np.where(on_light, -1, tri)
            self._emission_from_hits(radiance, idx, mis_o, o, d, t, tri, light_id, lam, beta, prev_pdf, prev_delta,
                                     depth)
            if depth == self.max_depth + 1:
                break
            keep = tri >= 0
            if not keep.all():  # o and t are not used below; the MIS data only through films
                idx, d, tri, bu, bv, beta, lam, hero, collapsed, eta_scale = compact(
                    keep, idx, d, tri, bu, bv, beta, lam, hero, collapsed, eta_scale)
                if self.shadows.see_through:
                    mis_o, prev_pdf, prev_delta = compact(keep, mis_o, prev_pdf, prev_delta)
            if len(idx) == 0:
                break
            p, ng, ns = self.tris.surface(tri, bu, bv)
            mat = self.tris.material[tri]
            wo = -d
            if self.analysis.dispersion:
                disp = self.disperses[mat] & ~collapsed
                if disp.any():
                    rows = np.flatnonzero(disp)
                    sub_c = collapsed[rows]
                    beta[rows] = collapse_to_hero(beta[rows], hero[rows], sub_c)
                    collapsed[rows] = sub_c
            cos_og = dot(wo, ng)
            eps = offset_distance(p)
            flip = self.two_sided[mat] & (cos_og < 0)
            nf = where_rows(flip, -ns, ns)
            frame = shading_frame(nf)
            wo_l = to_local(wo, *frame)
            if len(lights):
                rows, add, r = self._next_event(p, ng, frame, mat, cos_og, eps, wo_l, lam, hero, collapsed, beta,
                                                rng)
                add_rows(radiance, np.take(idx, rows), add)
                rays += r
            u = rng.random((len(idx), 3))
            wi_l, weight, pdf, delta, es = self._sample(mat, wo_l, lam, u, hero, collapsed)
            wi = to_world(wi_l, *frame)
            cos_ig = dot(wi, ng)
            ok = self._consistent(cos_og, cos_ig, wo_l, wi_l) & (row_max(weight) > 0)
            beta = beta * weight
            eta_scale = eta_scale * es
            if depth + 1 >= self.rr_depth:
                k_eff = np.where(collapsed, k, 1)
                survive = continuation_probability(row_max(beta) / k_eff * eta_scale)
                alive = rng.random(len(idx)) < survive
                beta = beta / np.where(alive, survive, 1.0)[:, None]
                ok &= alive
            o = offset_origin(p, ng, wi, eps, cos_ig)
            d = wi
            if self.shadows.see_through:
                null = self.film_material[mat] & (wo_l[:, 2] * wi_l[:, 2] < 0)  # straight through a film
                prev_pdf = np.where(null, prev_pdf, pdf)
                prev_delta = np.where(null, prev_delta, delta)
                mis_o = where_rows(null, mis_o, p)
            else:
                prev_pdf, prev_delta, mis_o = pdf, delta, p
            if not ok.all():
                idx, o, d, beta, lam, hero, collapsed, eta_scale, prev_pdf, prev_delta, mis_o = compact(
                    ok, idx, o, d, beta, lam, hero, collapsed, eta_scale, prev_pdf, prev_delta, mis_o)
        return np.ascontiguousarray(radiance.T), rays

    @staticmethod
    def _consistent(cos_og, cos_ig, wo_l, wi_l):
        """Reflection must stay on wo's side of the geometric surface, transmission cross it
        (``cos_og``, ``cos_ig``: wo.ng and wi.ng)."""
        reflect = wo_l[:, 2] * wi_l[:, 2] > 0
        same = cos_og * cos_ig > 0
        return reflect == same

    def _mis_emitter(self, pdf_light, prev_pdf, prev_delta):
        if self.use_mis:
            return np.where(prev_delta, 1.0, power_heuristic(prev_pdf, pdf_light))
        return prev_delta.astype(np.float64)

    def _emission_from_hits(self, radiance, idx, mis_o, o, d, t, tri, light_id, lam, beta, prev_pdf, prev_delta,
                            depth):
        """Add emission found by the rays o + t d; MIS densities of light sampling are
        those seen from ``mis_o`` (the ray origin, or the vertex before film crossings)."""
        lights = self.lights
        sel = lights.select_prob
        t_mis = t + dot(o - mis_o, d)  # distance from mis_o along the (straight) ray
        for li, light in lights.hittable:
            rows = np.flatnonzero(light_id == li)
            if len(rows):
                le = light.emitted(mis_o[rows], d[rows], t[rows], lam[rows])
                pdf_l = sel[li] * light.pdf(mis_o[rows], d[rows], t_mis[rows])
                w = self._mis_emitter(pdf_l, prev_pdf[rows], prev_delta[rows])
                add_rows(radiance, idx[rows], beta[rows] * le * w[:, None])
        escaped = (tri < 0) & (light_id < 0)
        if escaped.any():
            rows = np.flatnonzero(escaped)
            if not lights.world.black:
                add_rows(radiance, idx[rows], beta[rows] * lights.world.escaped(d[rows], lam[rows]))
            if depth > 0:
                for li, sun in lights.distant:
                    le = sun.escaped(d[rows], lam[rows])
                    w = self._mis_emitter(sel[li] * sun.pdf_escaped(d[rows]), prev_pdf[rows], prev_delta[rows])
                    add_rows(radiance, idx[rows], beta[rows] * le * w[:, None])
        mesh = lights.mesh
        if mesh is not None:
            hit = tri >= 0
            rows = np.flatnonzero(hit)
            rows = rows[mesh.row_of_triangle[tri[rows]] >= 0]
            if len(rows):
                le = mesh.radiance(tri[rows], lam[rows])
                if depth == 0:
                    w = np.ones(len(rows))
                else:
                    pdf_l = sel[lights.mesh_index] * mesh.pdf(mis_o[rows], d[rows], t_mis[rows], tri[rows])
                    w = self._mis_emitter(pdf_l, prev_pdf[rows], prev_delta[rows])
                add_rows(radiance, idx[rows], beta[rows] * le * w[:, None])

    def _next_event(self, p, ng, frame, mat, cos_og, eps, wo_l, lam, hero, collapsed, beta, rng):
        """Light-sampled contributions at the current vertices: (rows [m] of the vertices
        that get one, their values [m,K], shadow rays cast). Pure-delta materials get none."""
        n, k = lam.shape
        nothing = np.zeros(0, dtype=np.int64), np.zeros((0, k)), 0
        nee = ~self.delta_material[mat]
        if not nee.all():
            rows = np.flatnonzero(nee)
            if len(rows) == 0:
                return nothing
            p, ng, mat, cos_og, eps, wo_l, lam, hero, collapsed, beta = compact(
                nee, p, ng, mat, cos_og, eps, wo_l, lam, hero, collapsed, beta)
            frame = tuple(compact(nee, *frame))
        else:
            rows = None
        lights = self.lights
        m = len(p)
        u = rng.random((m, 4))
        if len(lights) == 1:
            light = lights.lights[0]
            wi, dist, li_val, pdf_l = light.sample(p, u[:, :3], lam)
            is_delta = np.full(m, light.delta)
        else:
            choice = np.minimum(np.searchsorted(lights.select_cdf, u[:, 3], side="right"), len(lights) - 1)
            wi = np.zeros((m, 3))
            dist = np.zeros(m)
            li_val = np.zeros((m, k))
            pdf_l = np.zeros(m)
            is_delta = np.zeros(m, dtype=bool)
            for j in np.unique(choice):
                sub = np.flatnonzero(choice == j)
                light = lights.lights[j]
                wi[sub], dist[sub], li_val[sub], pdf_l[sub] = light.sample(p[sub], u[sub, :3], lam[sub])
                is_delta[sub] = light.delta
        pdf_l = pdf_l * (lights.select_prob[0] if len(lights) == 1 else lights.select_prob[choice])
        wi_l = to_local(wi, *frame)
        f, pdf_b = self._eval(mat, wo_l, wi_l, lam, hero, collapsed)
        cos_ig = dot(wi, ng)
        ok = (pdf_l > 0) & self._consistent(cos_og, cos_ig, wo_l, wi_l)
        if self.use_mis:
            w = np.where(is_delta, 1.0, power_heuristic(pdf_l, pdf_b))
        else:
            w = 1.0
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.where(ok, w * np.abs(wi_l[:, 2]) / np.where(ok, pdf_l, 1.0), 0.0)
        contrib = beta * f
        contrib *= li_val
        contrib *= scale[:, None]
        send = row_max(contrib) > 0
        if not send.any():
            return nothing
        s = np.flatnonzero(send)
        p, ng, wi, eps, cos_ig, ds, lam, contrib = compact(send, p, ng, wi, eps, cos_ig, dist, lam, contrib)
        origin = offset_origin(p, ng, wi, eps, cos_ig)
        tmax = np.where(np.isfinite(ds), ds * (1.0 - SHADOW_SHORTEN), 1e30)
        trans, cast = self.shadows.transmittance(origin, wi, tmax, lam)
        contrib *= trans
        return (s if rows is None else rows[s]), contrib, cast
