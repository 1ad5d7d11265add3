"""Cryptomatte as Cycles writes it: MurmurHash3 ids of names, coverage of each id per pixel (ranks sorted,
coverages of a pixel adding up to what is not background), bit for bit whatever the thread count."""

import mmh3
import numpy as np

from engine.tracer.cryptomatte import hash_to_float, layers, manifest, pass_names
from engine.tracer.murmurhash3 import murmurhash3_32
from engine.tracer.pass_table import FilmLayout, PassRequest
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, World
from engine.tracer.data_passes import DataPassInputs
from tracer.tracer_scenes import look_at, make_scene, quad, settings

PIXEL_M = 0.45  # a pixel's width on the wall: 16 pixels over 7.2 m (15 mm lens, 36 mm film, 3 m away)


def test_murmurhash3_matches_mmh3_and_published_vectors():
    assert murmurhash3_32(b"") == 0 and murmurhash3_32(b"", 1) == 0x514E28B7  # Appleby's SMHasher vectors
    assert murmurhash3_32("The quick brown fox jumps over the lazy dog") == 0x2E4FF723
    rng = np.random.default_rng(3)
    names = ["", "a", "ab", "abc", "abcd", "Cube", "Cube.001", "Suzanne", "default_surface", "Ωmega ünïcode",
             "x" * 37]
    names += [bytes(rng.integers(0, 256, n, dtype=np.uint8)) for n in range(1, 12)]
    for name in names:
        assert murmurhash3_32(name) == mmh3.hash(name, 0, signed=False), name


def test_ids_are_the_hash_bits_as_float32_never_denormal_or_nan():
    hashes = np.array([0x3F800000, 0x00000001, 0x807FFFFF, 0x7F800000, 0xFFC00001, 0x12345678], np.uint32)
    bits = hash_to_float(hashes).view(np.uint32)
    assert bits.tolist() == [0x3F800000, 0x00800001, 0x80FFFFFF, 0x7F000000, 0xFF400001, 0x12345678]
    assert np.all(np.isfinite(hash_to_float(hashes)))
    assert manifest(["Cube", "Cube", "Left"]) == '{"Cube":"%08x","Left":"%08x"}' % (mmh3.hash("Cube", signed=False),
                                                                                    mmh3.hash("Left", signed=False))
    assert layers(6) == 3 and layers(5) == 3 and layers(16) == 8 and layers(40) == 8
    assert pass_names("Object", 6) == ["CryptoObject00", "CryptoObject01", "CryptoObject02"]


def _id(name):
    return float(hash_to_float([murmurhash3_32(name)])[0])


def _two_objects():
    """Two quads side by side 3 m in front of a 16 x 16 pinhole: 'Left' (material 'red') from x = -2.025
    m (the centre of pixel column 3) to the centre of column 8, 'Right' ('blue') from there to x = 2.025
    m, the centre of column 12; rows 4-11 see the wall only, background all round."""
    camera = Camera("cam", look_at((0, 0, 0), (0, 1, 0)), (16, 16), focal_length_mm=15.0, film_width_mm=36.0,
                    film_height_mm=36.0)
    split = 0.5 * PIXEL_M
    left = quad(((split - 2.025) / 2, 3.0, 0.0), ((2.025 + split) / 2, 0, 0), (0, 0, 2.0))
    right = quad(((split + 2.025) / 2, 3.0, 0.0), ((2.025 - split) / 2, 0, 0), (0, 0, 2.0))
    materials = [Material("red", "diffuse", base_color=(0.8, 0.1, 0.1)), Material("blue", base_color=(0.1, 0.1, 0.8))]
    scene = make_scene([(*left, 0), (*right, 1)], materials, camera, world=World((0.2, 0.2, 0.2), 1.0))
    scene.triangle_object = np.array([0, 0, 1, 1], np.int32)
    scene.object_names = ["Left", "Right"]
    scene.data_passes = DataPassInputs(asset_names=("Wall", "Wall"))
    return scene


def _render(scene, **kw):
    request = PassRequest(cryptomatte=("Object", "Material", "Asset"), cryptomatte_levels=kw.pop("levels", 6))
    with Renderer(scene, settings(passes=request, film_transparent=True, pixel_filter="box", filter_width_px=1.0,
                                  **kw)) as r:
        while not r.finished:
            r.render_pass()
        return r.pass_images(), r.image_alpha()


def test_coverage_of_edges_ranks_and_background():
    images, alpha = _render(_two_objects(), samples=256, samples_per_pass=64)
    assert sorted(images) == sorted(pass_names("Object", 6) + pass_names("Material", 6) + pass_names("Asset", 6))
    ob = np.concatenate([images[n] for n in pass_names("Object", 6)], -1)  # [16, 16, 12]: 6 (id, coverage)
    ids, coverage = ob[..., 0::2], ob[..., 1::2]
    rows = slice(4, 12)
    assert np.all(ids[rows, 4:8, 0] == _id("Left")) and np.all(coverage[rows, 4:8, 0] == 1.0)
    assert np.all(ids[rows, 9:12, 0] == _id("Right")) and np.all(coverage[rows, 9:12, 0] == 1.0)
    assert np.all(ob[rows, 4:8, 2:] == 0.0) and np.all(ob[:, 14:] == 0.0)  # one id inside; none on background
    edge = coverage[rows, 12, 0]  # half on 'Right', half background
    assert np.all(ids[rows, 12, 0] == _id("Right")) and np.abs(edge - 0.5).max() < 0.02, edge
    assert np.all(ob[rows, 12, 2:] == 0.0)
    seam = coverage[rows, 8]  # half 'Left', half 'Right': two ranks, the larger first
    assert set(ids[rows, 8, :2].ravel().tolist()) == {_id("Left"), _id("Right")}
    assert np.all(seam[:, 0] >= seam[:, 1]) and np.abs(seam[:, :2] - 0.5).max() < 0.02, seam[:, :2]
    assert np.all(np.diff(coverage, axis=-1) <= 0.0)  # ranks sorted everywhere
    # coverages add up to the samples that hit something: the alpha of a transparent film (exactly,
    # both are counts over the pixel's samples)
    assert np.allclose(coverage.sum(-1), alpha, atol=1e-6) and alpha[rows, 8].min() == 1.0
    material = images["CryptoMaterial00"]
    assert np.all(material[rows, 4:8, 0] == _id("red")) and np.all(material[rows, 9:12, 0] == _id("blue"))
    asset = images["CryptoAsset00"]  # both objects belong to 'Wall': one id, covering the seam pixel whole
    assert np.all(asset[rows, 8, 0] == _id("Wall")) and np.all(asset[rows, 8, 1] == 1.0)
    assert np.all(asset[rows, 8, 2:] == 0.0)


def test_levels_and_bit_identical_for_any_thread_count():
    one, _ = _render(_two_objects(), samples=32, samples_per_pass=16, threads=1, levels=2)
    two, _ = _render(_two_objects(), samples=32, samples_per_pass=16, threads=2, levels=2)
    assert sorted(one) == ["CryptoAsset00", "CryptoMaterial00", "CryptoObject00"]
    for name in one:
        assert one[name].view(np.uint32).tobytes() == two[name].view(np.uint32).tobytes(), name


def test_off_costs_nothing():
    plain = FilmLayout(PassRequest())
    assert plain.kernel.cryptomatte == -1 and plain.kernel.columns == 0 and plain.width == 0
    crypto = FilmLayout(PassRequest(cryptomatte=("Object",)))
    assert crypto.kernel.cryptomatte == 0 and crypto.kernel.columns == 3 and crypto.width == 0  # nothing summed


def test_film_counts_match_a_brute_force_count_for_any_chunking():
    """Many ids a pixel (more than Levels): the ranks are the largest counts of a plain count over all
    samples, whichever way the samples were cut into chunks."""
    from engine.tracer.cryptomatte import CryptomatteNames
    from engine.tracer.cryptomatte_film import CryptomatteFilm

    rng = np.random.default_rng(7)
    pixels, spp = 12, 200
    pixel = np.repeat(np.arange(pixels), spp)
    objects = rng.integers(0, 9, len(pixel)) * (rng.random(len(pixel)) < 0.9)  # 0: background
    indices = np.stack([objects, np.minimum(objects, 2), np.ones(len(objects))], -1)  # weight 1: opaque
    names = CryptomatteNames(tuple(f"o{i}" for i in range(8)), tuple(f"a{i}" for i in range(8)), ("m0", "m1"))
    results = []
    for cuts in ([], [spp * 3 + 17, spp * 7], list(range(0, len(pixel), 333))):
        film = CryptomatteFilm(pixels)
        for part in np.split(np.arange(len(pixel)), cuts):
            film.add(pixel[part], indices[part])
        results.append(film.images(("Object", "Material"), 4, names, np.full(pixels, spp), (3, 4)))
    for other in results[1:]:
        assert all(np.array_equal(results[0][k], other[k]) for k in results[0])
    ob = np.concatenate([results[0]["CryptoObject00"], results[0]["CryptoObject01"]], -1).reshape(pixels, 4, 2)
    for p in range(pixels):
        counts = np.bincount(objects[pixel == p], minlength=9)[1:]
        top = sorted(((-c, murmurhash3_32(f"o{i}"), i) for i, c in enumerate(counts) if c), key=lambda t: t[:2])[:4]
        assert [float(v) for v in ob[p, :, 1]] == [np.float32(-c / spp) for c, _, _ in top]
        assert ob[p, :, 0].tolist() == [_id(f"o{i}") for _, _, i in top]
