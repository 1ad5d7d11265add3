"""Ray tracing through lens surfaces: exact hits, Snell's law, fates and recorded paths."""

import math

import numpy as np

from engine.tracer.lens.media import AIR, constant_medium
from engine.tracer.lens.ray_fate import FATE_ALIVE, FATE_BLOCKED, FATE_MISSED, FATE_TIR
from engine.tracer.lens.system import TOWARD_FILM, TOWARD_SCENE, LensSystem, Surface


def _biconvex(n=1.5168, r1=100.0, r2=-80.0, t=8.0, stop_d=20.0, aperture=30.0):
    glass = constant_medium(n)
    return LensSystem((
        Surface(math.inf, 1.0, stop_d, AIR, True),
        Surface(r1, t, aperture, glass),
        Surface(r2, 0.0, aperture, AIR),
    ), name="biconvex")


def test_hits_lie_on_the_spheres_and_obey_snell():
    lens = _biconvex()
    rng = np.random.default_rng(0)
    n = 200
    origins = np.column_stack([rng.uniform(-6, 6, (n, 2)), np.full(n, -20.0)])
    directions = np.column_stack([rng.uniform(-0.05, 0.05, (n, 2)), np.ones(n)])
    res = lens.trace(origins, directions, 550.0, toward=TOWARD_FILM, record_path=True)
    assert res.alive.all()
    assert res.path.shape == (4, n, 3)
    z = lens.vertex_z_mm
    for k, radius in ((1, 100.0), (2, -80.0)):
        p = res.path[k + 1]
        centre = z[k] + radius
        dist = np.sqrt(p[:, 0] ** 2 + p[:, 1] ** 2 + (p[:, 2] - centre) ** 2)
        np.testing.assert_allclose(dist, abs(radius), rtol=1e-12)
    # Snell at the first glass surface: n1 sin(i) = n2 sin(t) about the surface normal.
    p = res.path[2]
    d_in = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    d_glass = res.path[3] - p
    d_glass /= np.linalg.norm(d_glass, axis=1, keepdims=True)
    normal = np.column_stack([p[:, 0], p[:, 1], p[:, 2] - (z[1] + 100.0)]) / 100.0
    sin_i = np.linalg.norm(np.cross(d_in, normal), axis=1)
    sin_t = np.linalg.norm(np.cross(d_glass, normal), axis=1)
    np.testing.assert_allclose(sin_i, 1.5168 * sin_t, rtol=1e-10, atol=1e-14)


def test_reverse_trace_retraces_the_forward_ray():
    lens = _biconvex()
    origins = np.array([[3.0, -2.0, -30.0], [0.0, 5.0, -30.0]])
    directions = np.array([[0.01, 0.02, 1.0], [0.0, -0.03, 1.0]])
    fwd = lens.trace(origins, directions, 500.0, toward=TOWARD_FILM)
    back = lens.trace(fwd.origins + 5.0 * fwd.directions, -fwd.directions, 500.0, toward=TOWARD_SCENE)
    assert back.alive.all()
    d0 = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    np.testing.assert_allclose(-back.directions, d0, atol=1e-12)
    # The reversed ray passes through the original origin.
    t = (origins[:, 2] - back.origins[:, 2]) / back.directions[:, 2]
    np.testing.assert_allclose(back.origins + t[:, None] * back.directions, origins, atol=1e-9)


def test_fates_blocked_missed_and_tir_are_recorded():
    lens = _biconvex(stop_d=4.0)
    origins = np.array([[0.0, 0.0, -10.0], [3.0, 0.0, -10.0], [0.0, 0.0, -10.0]])
    directions = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]])
    res = lens.trace(origins, directions, 550.0, toward=TOWARD_FILM, record_path=True)
    assert res.fate.tolist() == [FATE_ALIVE, FATE_BLOCKED, FATE_MISSED]
    assert res.surface.tolist() == [-1, 0, 0]
    assert np.allclose(res.path[1, 1], [3.0, 0.0, 0.0])  # where the stop blocked it
    assert np.isnan(res.path[2, 1]).all() and np.isnan(res.path[1, 2]).all()
    assert res.fate_names()[1] == "blocked at surface 0"
    # Inside dense glass, a marginal ray meeting a strongly curved exit face is totally reflected.
    glass = constant_medium(1.9)
    ball = LensSystem((Surface(math.inf, 1.0, 19.0, AIR, True), Surface(math.inf, 8.0, 19.0, glass),
                       Surface(-10.0, 0.0, 19.0, AIR)))
    res = ball.trace([[9.0, 0.0, -1.0], [1.0, 0.0, -1.0]], [[0.0, 0.0, 1.0]] * 2, 550.0, toward=TOWARD_FILM)
    assert res.fate.tolist() == [FATE_TIR, FATE_ALIVE] and res.surface.tolist() == [2, -1]


def test_each_ray_uses_its_own_wavelength():
    dispersive = LensSystem((
        Surface(math.inf, 1.0, 20.0, AIR, True),
        Surface(50.0, 5.0, 20.0, _cauchy()),
        Surface(math.inf, 0.0, 20.0, AIR),
    ))
    origins = np.tile([5.0, 0.0, -5.0], (3, 1))
    directions = np.tile([0.0, 0.0, 1.0], (3, 1))
    wl = np.array([450.0, 550.0, 650.0])
    mixed = dispersive.trace(origins, directions, wl, toward=TOWARD_FILM)
    for k in range(3):
        single = dispersive.trace(origins[k:k + 1], directions[k:k + 1], wl[k], toward=TOWARD_FILM)
        np.testing.assert_allclose(mixed.directions[k], single.directions[0], atol=1e-15)
    # Blue bends more than red.
    assert mixed.directions[0, 0] < mixed.directions[1, 0] < mixed.directions[2, 0]


def _cauchy():
    from engine.tracer.lens.media import FunctionMedium

    return FunctionMedium(lambda wl: 1.5 + 5000.0 / wl**2, "cauchy")
