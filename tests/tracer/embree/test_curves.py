"""Round Catmull-Rom curves through Prism's Embree layer against closed forms.

A segment whose 4 control points are collinear and equally spaced is the straight line between its middle
two, and with one radius the sphere swept along it is a capsule (a cylinder with hemispherical caps): its
ray intersection is analytic. Rows (segments follow the triangle and a sphere), distances and the surface
point and normal rebuilt from the hit code (``curves.curve_surface``) are compared with it; bent strands
check that the rebuilt point is where the ray met the tube, and rays leaving a tube's offset surface do not
find it again."""

import numpy as np
import pytest

from engine.tracer.curves import Strands, curve_at, curve_surface, padded_strands
from engine.tracer.embree.curves import CurveGeometry
from engine.tracer.embree.errors import EmbreeError
from engine.tracer.embree.layout import new_ray_hit_record
from engine.tracer.embree.queries import RayCaster, closest_hits, occlusion
from engine.tracer.embree.scene import Scene, TriangleGeometry
from engine.tracer.embree.spheres import SphereGeometry
from engine.tracer.state import HitRecord, RayQueue

TRIANGLE = np.array([[-4.0, -4.0, -3.0], [4.0, -4.0, -3.0], [0.0, 4.0, -3.0]])
SPHERE = np.array([[2.0, 2.0, 2.0, 0.3]], np.float32)


def _capsules(seed=2, count=10):
    """(controls float32 [4 count, 4], segments, ends a [count, 3], b [count, 3], radius [count])."""
    rng = np.random.default_rng(seed)
    a = rng.uniform(-1.5, 1.5, (count, 3))
    b = a + rng.normal(size=(count, 3)) * 0.6
    r = rng.uniform(0.02, 0.2, count)
    steps = np.stack([2 * a - b, a, b, 2 * b - a], axis=1)  # equally spaced on the line through a and b
    controls = np.concatenate([steps, np.repeat(r[:, None, None], 4, axis=1)], axis=2).reshape(-1, 4)
    return controls.astype(np.float32), np.arange(count) * 4, a, b, r


def _analytic(a, b, r, origin, direction):
    """(capsule index or -1; t; unit normal; margin from a grazing ray or a tie) of the nearest hit on the
    capsules' cylinder walls, float64, and whether a ray meets some capsule's end cap (the part of the end
    spheres outside the cylinder) first: Embree sweeps a circle along the curve (its documentation of round
    curves) and ends it with no complete cap, so those rays are left out."""
    o, d = origin.astype(np.float64), direction.astype(np.float64)
    n, count = len(o), len(a)
    best_t = np.full(n, np.inf)
    best = np.full(n, -1)
    normal = np.zeros((n, 3))
    margin = np.full(n, np.inf)
    first_cap = np.full(n, np.inf)
    for k in range(count):
        axis = b[k] - a[k]
        length = np.linalg.norm(axis)
        w = axis / length
        oa = o - a[k]
        dp = d - (d @ w)[:, None] * w
        op = oa - (oa @ w)[:, None] * w
        qa = np.einsum("ij,ij->i", dp, dp)
        qb = np.einsum("ij,ij->i", dp, op)
        qc = np.einsum("ij,ij->i", op, op) - r[k] ** 2
        disc = qb * qb - qa * qc
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.where(disc > 0, (-qb - np.sqrt(np.maximum(disc, 0))) / qa, np.inf)
            along = np.einsum("ij,j->i", oa + np.where(np.isfinite(t), t, 0)[:, None] * d, w)
        t = np.where((along >= 0) & (along <= length) & (t > 0), t, np.inf)
        graze = np.where(disc > 0, disc / (qa * r[k] ** 2 + 1e-30), np.inf)
        for centre, outward in ((a[k], -w), (b[k], w)):
            oc = o - centre
            sb = np.einsum("ij,ij->i", oc, d)
            sa = np.einsum("ij,ij->i", d, d)
            sd = sb * sb - sa * (np.einsum("ij,ij->i", oc, oc) - r[k] ** 2)
            for sign in (-1.0, 1.0):
                ts = (-sb + sign * np.sqrt(np.maximum(sd, 0))) / sa
                beyond = (oc + ts[:, None] * d) @ outward > 0
                first_cap = np.minimum(first_cap, np.where((sd > 0) & (ts > 0) & beyond, ts, np.inf))
        closer = t < best_t
        finite = np.isfinite(t) & np.isfinite(best_t)
        tie = np.where(finite, np.abs(t - np.where(finite, best_t, 0)) / np.maximum(np.minimum(t, best_t), 1e-9),
                       np.inf)
        margin = np.minimum(margin, np.where(np.isfinite(t), np.minimum(graze, tie), np.inf))
        best_t = np.where(closer, t, best_t)
        best = np.where(closer, k, best)
        p = o + np.where(np.isfinite(t), t, 0)[:, None] * d
        centre = a[k] + np.clip((p - a[k]) @ w, 0, length)[:, None] * w
        normal = np.where(closer[:, None], (p - centre) / r[k], normal)
    capped = np.isfinite(first_cap) & (first_cap <= best_t * (1 + 1e-3))
    return best, best_t, normal, margin, capped


def _trace(scene, origin, direction, caster_rows, time=None):
    caster = RayCaster(scene.handle, *new_ray_hit_record(), **caster_rows)
    n = len(origin)
    hits = HitRecord(np.empty(n, np.int32), np.empty(n, np.float32), np.empty(n, np.float32), np.empty(n, np.float32))
    queue = RayQueue(np.arange(n, dtype=np.int32), origin, direction, np.full(n, 1e30, np.float32),
                     np.full(n, 0.5) if time is None else time)
    closest_hits(caster, queue, n, False, hits)
    blocked = np.empty(n, np.int32)
    occlusion(caster, queue, n, blocked)
    return hits, blocked


def _surface(controls, segments, hits, chosen, first_curve, motion=None, time=None):
    """(points, geometric normals, shading normals) rebuilt from the hits ``chosen`` (at their rays' ``time``
    where the curves have ``motion``)."""
    strands = Strands(controls, segments) if motion is None else Strands(controls, segments, motion)
    times = np.full(len(hits.triangle), 0.5) if time is None else time
    rebuilt = [curve_surface(strands, int(row) - first_curve, float(u), float(v), float(tau))
               for row, u, v, tau in zip(hits.triangle[chosen], hits.u[chosen], hits.v[chosen], times[chosen])]
    return tuple(np.array([r[i] for r in rebuilt]) for i in range(3))


def test_straight_segments_match_the_analytic_capsule():
    controls, segments, a, b, r = _capsules()
    segments32 = segments.astype(np.int32)
    scene = Scene([TriangleGeometry(TRIANGLE.astype(np.float32), np.array([[0, 1, 2]])), SphereGeometry(SPHERE),
                   CurveGeometry(controls, segments)])
    rng = np.random.default_rng(5)
    n = 30000
    origin = rng.uniform(-2.0, 2.0, (n, 3))
    toward = rng.uniform(-1.5, 1.5, (n, 3))  # aim at the capsules' region, so many rays hit them
    direction = (toward - origin) * rng.uniform(0.5, 2.0, (n, 1))  # not unit
    outside = _outside(a, b, r, origin)
    origin, direction = origin[outside].astype(np.float32), direction[outside].astype(np.float32)
    rows = dict(curve_geometry=2, first_curve=2, curves=controls, curve_segments=segments32)
    hits, blocked = _trace(scene, origin, direction, rows)
    best, t, normal, margin, capped = _analytic(a, b, r, origin, direction)
    clear = (margin > 1e-3) & ~capped & (hits.triangle != 0) & (hits.triangle != 1)  # the triangle, the sphere
    on_curve = clear & (best >= 0)
    assert on_curve.sum() > 2500 and (clear & (best < 0) & (hits.triangle < 0)).sum() > 1000
    np.testing.assert_array_equal(hits.triangle[clear], np.where(best[clear] >= 0, 2 + best[clear], -1))
    np.testing.assert_allclose(hits.t[on_curve], t[on_curve], rtol=1e-4, atol=1e-5)
    p, nrm, shading = _surface(controls, segments32, hits, on_curve, 2)
    np.testing.assert_allclose(shading, nrm, atol=1e-6)  # one radius: no lean
    hit_point = origin[on_curve].astype(np.float64) + t[on_curve, None] * direction[on_curve].astype(np.float64)
    error_m = np.linalg.norm(p - hit_point, axis=1)
    assert error_m.max() < 1e-4 * np.abs(hit_point).max() + 1e-5, error_m.max()
    angle = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", nrm, normal[on_curve]), -1, 1)))
    assert angle.max() < 0.1, angle.max()
    np.testing.assert_array_equal(blocked[clear], np.where(hits.triangle[clear] >= 0, 0, -1))


def _outside(a, b, r, origin):
    """Which ``origin`` points lie outside every capsule (Embree's round curves are seen from outside)."""
    outside = np.ones(len(origin), bool)
    for k in range(len(a)):
        w = (b[k] - a[k]) / np.linalg.norm(b[k] - a[k])
        along = np.clip((origin - a[k]) @ w, 0, np.linalg.norm(b[k] - a[k]))
        outside &= np.linalg.norm(origin - (a[k] + along[:, None] * w), axis=1) > r[k] * 1.01
    return outside


def test_moving_segments_are_met_where_they_stand_at_each_rays_time():
    """The capsules at 3 time steps, moving 0.7 m in a straight line over the shutter (the middle step the frame's):
    a ray at time τ meets them moved by (τ - 1/2) of the travel (the analytic capsules, with the ray moved back
    instead), and the surface rebuilt from its hit code at τ (the control points read at the ray's time) is where
    the ray met it, its normal the analytic one."""
    controls, segments, a, b, r = _capsules()
    segments32 = segments.astype(np.int32)
    travel = np.array([0.6, -0.2, 0.3])
    motion = np.stack([controls + np.r_[travel * f, 0.0] for f in (-0.5, 0.0, 0.5)]).astype(np.float32)
    scene = Scene([CurveGeometry(list(motion), segments)])
    rng = np.random.default_rng(8)
    n = 30000
    time = rng.uniform(0.0, 1.0, n)
    shift = (time - 0.5)[:, None] * travel  # where the capsules stand at each ray's time, from the frame's
    origin = rng.uniform(-2.0, 2.0, (n, 3))
    direction = (rng.uniform(-1.5, 1.5, (n, 3)) + shift - origin) * rng.uniform(0.5, 2.0, (n, 1))
    outside = _outside(a, b, r, origin - shift)
    origin, direction, time, shift = (origin[outside].astype(np.float32), direction[outside].astype(np.float32),
                                      time[outside], shift[outside])
    rows = dict(curve_geometry=0, first_curve=0, curves=motion[1], curve_segments=segments32, curve_motion=motion)
    hits, _ = _trace(scene, origin, direction, rows, time)
    best, t, normal, margin, capped = _analytic(a, b, r, origin - shift, direction)
    clear = (margin > 1e-3) & ~capped
    on_curve = clear & (best >= 0)
    assert on_curve.sum() > 2500 and (clear & (best < 0)).sum() > 1000
    np.testing.assert_array_equal(hits.triangle[clear], np.where(best[clear] >= 0, best[clear], -1))
    np.testing.assert_allclose(hits.t[on_curve], t[on_curve], rtol=1e-4, atol=1e-5)
    p, nrm, _ = _surface(motion[1], segments32, hits, on_curve, 0, motion, time)
    hit_point = origin[on_curve].astype(np.float64) + t[on_curve, None] * direction[on_curve].astype(np.float64)
    assert np.linalg.norm(p - hit_point, axis=1).max() < 1e-4 * np.abs(hit_point).max() + 1e-5
    angle = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", nrm, normal[on_curve]), -1, 1)))
    assert angle.max() < 0.1, angle.max()


def _bent_strands(count=40, seed=7):
    """Strands of 6 points along a gentle arc, radius tapering from 3 to 1.2 cm, as the export pads them."""
    rng = np.random.default_rng(seed)
    points, radii = [], []
    for _ in range(count):
        root = rng.uniform(-1, 1, 3)
        s = np.linspace(0, 1, 6)[:, None]
        bend = rng.normal(size=3) * 0.3
        up = rng.normal(size=3)
        points.append(root + s * up * 0.8 + s * s * bend)
        radii.append(np.linspace(0.03, 0.012, 6))
    offsets = np.arange(count + 1) * 6
    padded, padded_radii, segments = padded_strands(np.concatenate(points), np.concatenate(radii), offsets)
    controls = np.column_stack([padded, padded_radii]).astype(np.float32)
    return controls, segments


def test_padding_repeats_each_strands_ends():
    points = np.arange(15, dtype=float).reshape(5, 3)
    padded, radii, segments = padded_strands(points, np.arange(5.0), np.array([0, 2, 5]))
    np.testing.assert_array_equal(radii, [0, 0, 1, 1, 2, 2, 3, 4, 4])
    np.testing.assert_array_equal(segments, [0, 4, 5])
    np.testing.assert_array_equal(padded[4:8], points[[2, 2, 3, 4]])


def _bent_hits():
    """Random rays at the bent, tapering strands: (controls, segments, scene, rng, origins, directions, the
    curve rows, hits, which rays hit)."""
    controls, segments = _bent_strands()
    segments32 = segments.astype(np.int32)
    scene = Scene([CurveGeometry(controls, segments)])
    rng = np.random.default_rng(11)
    n = 20000
    origin = rng.normal(size=(n, 3)) * 0.5 + np.array([0.0, 0.0, 4.0])
    direction = rng.uniform(-1.2, 1.2, (n, 3)) - origin
    rows = dict(curve_geometry=0, first_curve=0, curves=controls, curve_segments=segments32)
    hits, _ = _trace(scene, origin.astype(np.float32), direction.astype(np.float32), rows)
    return controls, segments32, scene, rng, origin, direction, rows, hits, hits.triangle >= 0


def test_bent_tapered_strands_rebuild_the_hit_point_and_shed_their_own_rays():
    controls, segments32, scene, rng, origin, direction, rows, hits, hit = _bent_hits()
    assert hit.sum() > 2000
    p, nrm, shading = _surface(controls, segments32, hits, hit, 0)
    ray_point = origin[hit] + hits.t[hit, None].astype(np.float64) * direction[hit]
    error_m = np.linalg.norm(p - ray_point, axis=1)
    # Embree's round-curve intersection is iterative: a few hits in a thousand (grazing ones) stop up to 1 mm
    # (r/10) from where the ray meets the tube; the rest within a micrometre
    assert np.quantile(error_m, 0.99) < 2e-6 and (error_m > 1e-4).mean() < 2e-3, (np.quantile(error_m, 0.99),
                                                                                 (error_m > 1e-4).mean())
    facing = np.einsum("ij,ij->i", nrm, direction[hit]) < 0
    root = hits.triangle[hit] % 5 == 0  # 5 segments a strand
    # the tube's normals face the incoming rays, but where a ray enters the open end of a strand's thick root
    # and meets the wall inside (Embree sweeps a circle: no end cap)
    assert facing[~root].mean() > 0.995 and facing[root].mean() > 0.8
    np.testing.assert_array_equal(shading, nrm)
    across = []  # the direction from the curve's centre at u to the hit, across the tangent
    for row, u in zip(hits.triangle[hit], hits.u[hit]):
        centre, radius, _, _ = curve_at(Strands(controls, segments32), int(row), float(u), 0.5)
        across.append(np.array(centre))
    across = p - np.array(across)
    across /= np.linalg.norm(across, axis=1, keepdims=True)
    lean = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", nrm, across), -1, 1)))
    assert 0.2 < np.median(lean) < 4  # the tube's normal leans from it where the tube narrows
    # secondary rays from the offset surface (geometry.offset_origin), into the outer hemisphere
    eps = 4e-6 * np.abs(p).max(axis=1, keepdims=True) + 1e-7
    out = rng.normal(size=p.shape)
    out *= np.sign(np.einsum("ij,ij->i", out, nrm))[:, None]
    again, _ = _trace(scene, (p + eps * nrm).astype(np.float32), out.astype(np.float32), rows)
    self_hit = (again.triangle == hits.triangle[hit]) & (again.t < 1e-3)
    kept = facing & (error_m < 1e-5)  # the few hits Embree stopped short of the tube start inside it
    grazing = np.einsum("ij,ij->i", out, nrm) < 0.05 * np.linalg.norm(out, axis=1)
    assert self_hit[kept & ~grazing].mean() < 1e-3 and self_hit.mean() < 5e-3, (
        self_hit[kept & ~grazing].mean(), self_hit.mean())


def test_bad_curves_are_refused():
    with pytest.raises(EmbreeError, match="shape"):
        CurveGeometry(np.zeros((4, 3), np.float32), [0])
    with pytest.raises(EmbreeError, match="does not exist"):
        CurveGeometry(np.zeros((4, 4), np.float32), [1])
    with pytest.raises(EmbreeError, match="radii"):
        CurveGeometry(np.array([[0, 0, 0, -1.0]] * 4, np.float32), [0])


def test_an_axis_aligned_strand_rebuilds_every_hit():
    """A straight strand along x, seen from off its axis: the tangent's y and z cancel to rounding noise, which
    the hit code and the rebuilt surface (compiled apart) must not read differently (a frame hanging on that
    noise put some points on the far side of the tube)."""
    cam = np.array([0.0, -3.0, 1.0])
    points = np.linspace([-4.0, 0.0, 0.0], [4.0, 0.0, 0.0], 4) - cam
    padded, radii, segments = padded_strands(points, np.full(4, 0.3), np.array([0, 4]))
    controls = np.column_stack([padded, radii]).astype(np.float32)
    segments32 = segments.astype(np.int32)
    scene = Scene([CurveGeometry(controls, segments)])
    rng = np.random.default_rng(2)
    n = 5000
    target = np.column_stack([rng.uniform(-1.5, 1.5, n), rng.uniform(-0.4, 0.4, n), rng.uniform(-0.4, 0.4, n)]) - cam
    rows = dict(curve_geometry=0, first_curve=0, curves=controls, curve_segments=segments32)
    hits, _ = _trace(scene, np.zeros((n, 3), np.float32), target.astype(np.float32), rows)
    hit = hits.triangle >= 0
    assert hit.sum() > 2000
    p, nrm, _ = _surface(controls, segments32, hits, hit, 0)
    ray_point = hits.t[hit, None].astype(np.float64) * target[hit].astype(np.float32).astype(np.float64)
    assert np.linalg.norm(p - ray_point, axis=1).max() < 1e-5
    assert (np.einsum("ij,ij->i", nrm, target[hit]) < 0).all()


def test_rays_into_a_strand_leave_from_its_far_wall():
    """A fibre's transmitted light goes on from the far side of its tube (``curves.leave_tube``, as Cycles' rays skip
    the primitive they leave): on the bent, tapering strands, rays sent inward from a hit, started where
    ``leave_tube`` says, do not meet their own segment again within 1 mm (measured: none of ~3900; the straight
    chord alone left 41 % of them inside the wall); rays sent outward are left to ``offset_origin``."""
    from engine.tracer.curves import leave_tube

    controls, segments32, scene, rng, origin, direction, rows, hits, hit = _bent_hits()
    p, nrm, _ = _surface(controls, segments32, hits, hit, 0)
    d = -nrm + rng.normal(size=nrm.shape) * 0.7
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    inward = np.einsum("ij,ij->i", d, nrm) < 0
    left = [leave_tube(Strands(controls, segments32), int(row), float(u), tuple(a), tuple(b), 0.5)
            for row, u, a, b in zip(hits.triangle[hit], hits.u[hit], p, d)]
    start = np.array([q for q, _ in left])
    travelled = np.array([t for _, t in left])
    # leave_tube judges inward by the radial direction, the hit's normal leans a little where the tube tapers
    assert np.mean((travelled > 0) == inward) > 0.995
    inward &= travelled > 0
    eps = 4e-6 * np.abs(start).max(axis=1, keepdims=True) + 1e-7
    again, _ = _trace(scene, (start + eps * d).astype(np.float32), d.astype(np.float32), rows)
    own = inward & (again.triangle == hits.triangle[hit]) & (again.t < 1e-3)
    assert inward.sum() > 2000 and own.sum() == 0
