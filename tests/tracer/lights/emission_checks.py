"""Light-path emission exactly as the kernels sample it, vectorised for tests (not a test module)."""

from types import SimpleNamespace

import numpy as np

from engine.tracer.geometry import FRAME_TIME, prepare_geometry
from engine.tracer.jit import kernel
from engine.tracer.lights.caustic_targets import (beam_pdf, build_caustic_targets, direction_pdf, sample_beam,
                                                  sample_direction)
from engine.tracer.lights.emission import sample_emission
from engine.tracer.materials.table import MAT_DELTA

from .light_checks import SceneLights


@kernel
def _emit_many(lights, materials, spectra, geometry, targets, u, lam, origin, direction, beta, index, rows, registers):
    for i in range(u.shape[0]):
        o, d, light = sample_emission(lights, materials, spectra, geometry, targets, u[i, 0], (u[i, 1], u[i, 2]),
                                      u[i, 3], (u[i, 4], u[i, 5]), lam[i], beta[i], rows, registers, FRAME_TIME)
        origin[i, 0], origin[i, 1], origin[i, 2] = o
        direction[i, 0], direction[i, 1], direction[i, 2] = d
        index[i] = light


@kernel
def _directions(targets, x, u, out, pdf):
    for i in range(u.shape[0]):
        d, p = sample_direction(targets, (x[0], x[1], x[2]), u[i, 0], u[i, 1], u[i, 2])
        out[i, 0], out[i, 1], out[i, 2] = d
        pdf[i] = p


@kernel
def _direction_pdfs(targets, x, d, out):
    for i in range(d.shape[0]):
        out[i] = direction_pdf(targets, (x[0], x[1], x[2]), (d[i, 0], d[i, 1], d[i, 2]))


@kernel
def _beams(targets, d, u, origin, pdf):
    for i in range(u.shape[0]):
        o, p = sample_beam(targets, (d[0], d[1], d[2]), u[i, 0], u[i, 1], u[i, 2])
        origin[i, 0], origin[i, 1], origin[i, 2] = o
        pdf[i] = p


@kernel
def _beam_pdfs(targets, d, q, out):
    for i in range(q.shape[0]):
        out[i] = beam_pdf(targets, (q[i, 0], q[i, 1], q[i, 2]), (d[0], d[1], d[2]))


def targets_of(scene):
    """The ``CausticTargets`` of ``scene`` (camera at the world origin: world and kernel space agree)."""
    lights = SceneLights(scene)
    geometry, _, _ = prepare_geometry(scene, np.zeros(3))
    return build_caustic_targets(geometry, lights.materials.flags, MAT_DELTA)


class Emission:
    """Light paths started in ``scene`` (lights and targets as a render with the camera at the origin)."""

    def __init__(self, scene):
        self.lights = SceneLights(scene)
        self.targets = targets_of(scene)

    def sample(self, u, wavelength_nm=550.0):
        """Starts of light paths from uniforms ``u`` [n, 6]: origin, direction, beta (at ``wavelength_nm``,
        divided by the light's spectrum there), light index."""
        n = len(u)
        out = SimpleNamespace(origin=np.empty((n, 3)), direction=np.empty((n, 3)), beta=np.empty((n, 1)),
                              light=np.empty(n, np.int64))
        lights = self.lights
        _emit_many(lights.arrays, lights.materials, lights.spectra, lights.geometry, self.targets,
                   np.ascontiguousarray(u, dtype=np.float64), np.full((n, 1), wavelength_nm), out.origin,
                   out.direction, out.beta, out.light, lights.scratch.emitter_rows, lights.scratch.registers)
        out.beta = out.beta[:, 0]
        return out


def sample_directions(targets, x, u):
    d, pdf = np.empty((len(u), 3)), np.empty(len(u))
    _directions(targets, np.asarray(x, np.float64), np.ascontiguousarray(u, dtype=np.float64), d, pdf)
    return d, pdf


def direction_pdfs(targets, x, d):
    out = np.empty(len(d))
    _direction_pdfs(targets, np.asarray(x, np.float64), np.ascontiguousarray(d, dtype=np.float64), out)
    return out


def sample_beams(targets, d, u):
    origin, pdf = np.empty((len(u), 3)), np.empty(len(u))
    _beams(targets, np.asarray(d, np.float64), np.ascontiguousarray(u, dtype=np.float64), origin, pdf)
    return origin, pdf


def beam_pdfs(targets, d, q):
    out = np.empty(len(q))
    _beam_pdfs(targets, np.asarray(d, np.float64), np.ascontiguousarray(q, dtype=np.float64), out)
    return out


def chi_square_p(counts, expected):
    """p-value of observed ``counts`` against ``expected`` (same total); bins expecting < 5 are pooled."""
    from scipy import stats

    counts, expected = np.ravel(counts).astype(np.float64), np.ravel(expected).astype(np.float64)
    expected = expected * counts.sum() / expected.sum()
    small = expected < 5
    if small.any():
        counts = np.append(counts[~small], counts[small].sum())
        expected = np.append(expected[~small], expected[small].sum())
        if expected[-1] < 5:  # still too small: into the smallest other bin
            smallest = int(np.argmin(expected[:-1]))
            counts[smallest] += counts[-1]
            expected[smallest] += expected[-1]
            counts, expected = counts[:-1], expected[:-1]
    return stats.chisquare(counts, expected).pvalue


def sphere_bins(directions, nz=16, nphi=32):
    """Counts of unit ``directions`` in equal-solid-angle bins (z, φ) about the world axes."""
    z = np.clip((directions[:, 2] + 1) / 2 * nz, 0, nz - 1e-9).astype(int)
    phi = np.arctan2(directions[:, 1], directions[:, 0]) % (2 * np.pi)
    p = np.clip(phi / (2 * np.pi) * nphi, 0, nphi - 1e-9).astype(int)
    return np.bincount(z * nphi + p, minlength=nz * nphi).reshape(nz, nphi)


def reference_directions(targets, x, n, seed):
    """``n`` directions drawn from ``direction_pdf`` by rejection from the uniform sphere: the density
    alone, independent of the sampler's own construction."""
    rng = np.random.default_rng(seed)
    total = sum(2 * np.pi * (1 - np.sqrt(max(0.0, 1 - (r / max(np.linalg.norm(c - x), r)) ** 2))) if
                np.linalg.norm(c - x) > r else 4 * np.pi for c, r in zip(targets.spheres[:, :3], targets.spheres[:, 3]))
    bound = len(targets.spheres) / total
    kept = []
    while sum(len(k) for k in kept) < n:
        z = rng.uniform(-1, 1, 4 * n)
        phi = rng.uniform(0, 2 * np.pi, 4 * n)
        r = np.sqrt(1 - z * z)
        d = np.stack([r * np.cos(phi), r * np.sin(phi), z], -1)
        kept.append(d[rng.random(4 * n) * bound < direction_pdfs(targets, x, d)])
    return np.concatenate(kept)[:n]


def same_distribution_p(counts_a, counts_b):
    """p-value that two histograms come from one distribution (chi-square homogeneity); bins with
    fewer than 10 samples in both together are pooled."""
    from scipy import stats

    a, b = np.ravel(counts_a).astype(np.float64), np.ravel(counts_b).astype(np.float64)
    small = a + b < 10
    a = np.append(a[~small], a[small].sum())
    b = np.append(b[~small], b[small].sum())
    keep = a + b > 0
    return stats.chi2_contingency(np.stack([a[keep], b[keep]]))[1]
