"""The scene's lights exactly as the kernels sample and hit them, vectorised for tests (not a test module)."""

from types import SimpleNamespace

import numpy as np

from engine.tracer.geometry import FRAME_TIME, prepare_geometry
from engine.tracer.jit import kernel
from engine.tracer.lights.dispatch import emitter_pdf, intersect_light, light_hit, sample_light
from engine.tracer.lights.table import build_lights
from engine.tracer.materials.table import build_materials
from engine.tracer.spectra.table import SpectrumTable, spectrum_value
from engine.tracer.state import new_shading_scratch


@kernel
def _sample_many(lights, materials, spectra, geometry, p, u, lam, wi, dist, li, pdf, delta, rows, registers, time):
    for i in range(p.shape[0]):
        w, d, q, is_delta, _, _ = sample_light(lights, materials, spectra, geometry, (p[i, 0], p[i, 1], p[i, 2]),
                                            u[i, 2], u[i, 0], u[i, 1], lam[i], li[i], rows, registers, time)
        wi[i, 0], wi[i, 1], wi[i, 2] = w
        dist[i] = d
        pdf[i] = q
        delta[i] = is_delta


@kernel
def _hit_many(lights, o, d, t_max, index, t, factor, pdf):
    for i in range(o.shape[0]):
        oi = (o[i, 0], o[i, 1], o[i, 2])
        di = (d[i, 0], d[i, 1], d[i, 2])
        index[i], t[i] = intersect_light(lights, oi, di, t_max[i])
        if index[i] >= 0:
            factor[i], pdf[i] = light_hit(lights, index[i], oi, di, t[i])


@kernel
def _emitter_pdf_many(lights, geometry, triangle, d, t, pdf, time):
    for i in range(d.shape[0]):
        pdf[i] = emitter_pdf(lights, geometry, triangle[i], (d[i, 0], d[i, 1], d[i, 2]), t[i], time)


class SceneLights:
    """Light tables of ``scene`` (camera at the world origin unless ``offset`` says otherwise)."""

    def __init__(self, scene, offset=(0.0, 0.0, 0.0)):
        spectra = SpectrumTable()
        used = set(np.unique(scene.triangle_material).tolist())
        table = build_materials(scene.materials, used, spectra)
        self.materials = table.arrays
        self.geometry = prepare_geometry(scene, offset)[0]
        self.scratch = new_shading_scratch(1, table.register_count)
        self.table = build_lights(scene, spectra, np.asarray(scene.vertices, np.float64) - offset,
                                  np.asarray(scene.triangles, np.int32), np.asarray(scene.triangle_material, np.int32),
                                  self.materials.emission_strength, np.asarray(offset, np.float64))
        self.arrays = self.table.arrays
        self.spectra = spectra.arrays()

    def spectrum_at(self, light, wavelength_nm=550.0):
        return spectrum_value(self.spectra, int(self.arrays.rows[light, 1]), wavelength_nm)

    def sample(self, p, u, wavelength_nm=550.0, time=FRAME_TIME):
        """Samples toward lights from points ``p`` [n,3] with uniforms ``u`` [n,3] (u[:, 2] picks the light) at ray
        time ``time`` (moving emitters where they are then)."""
        n = len(p)
        lam = np.full((n, 1), wavelength_nm)
        out = SimpleNamespace(wi=np.empty((n, 3)), dist=np.empty(n), li=np.empty((n, 1)), pdf=np.empty(n),
                              delta=np.empty(n, bool))
        _sample_many(self.arrays, self.materials, self.spectra, self.geometry, np.ascontiguousarray(p, dtype=np.float64),
                     np.ascontiguousarray(u, dtype=np.float64), lam, out.wi, out.dist, out.li, out.pdf, out.delta,
                     self.scratch.emitter_rows, self.scratch.registers, float(time))
        out.li = out.li[:, 0]
        return out

    def hit(self, o, d, t_max=None):
        """(light index or -1, distance, radiance factor, pdf incl. selection) of rays against hittable lights."""
        n = len(o)
        t_max = np.full(n, np.inf) if t_max is None else np.asarray(t_max, np.float64)
        index, t, factor, pdf = np.empty(n, np.int64), np.empty(n), np.zeros(n), np.zeros(n)
        _hit_many(self.arrays, np.ascontiguousarray(o, dtype=np.float64), np.ascontiguousarray(d, dtype=np.float64),
                  t_max, index, t, factor, pdf)
        return index, t, factor, pdf

    def emitter_pdf(self, triangle, d, t, time=FRAME_TIME):
        pdf = np.empty(len(d))
        _emitter_pdf_many(self.arrays, self.geometry, np.asarray(triangle, np.int64),
                          np.ascontiguousarray(d, dtype=np.float64), np.asarray(t, np.float64), pdf, float(time))
        return pdf
