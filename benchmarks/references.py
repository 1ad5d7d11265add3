"""High-sample reference images, cached with their variance in benchmarks/cache/.

A cache entry is keyed by the renderer (Prism, Mitsuba, Cycles), the scene, the
resolution, the reference settings and requested spp, and - for Prism - a hash of
the tracer's source and the benchmark scene code, so a change to either renders
the reference anew (a stale reference would turn a renderer change into "error").
Each entry holds ``image`` and ``variance`` (variance of the mean, [H, W, 3]),
the spp reached and the seconds it took.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np

BENCH_DIR = Path(__file__).resolve().parent
CACHE_DIR = BENCH_DIR / "cache"
REPO_ROOT = BENCH_DIR.parent


_FINGERPRINT: list[str] = []


def code_fingerprint() -> str:
    """Hash of engine/tracer/**.py, lenses/ and the scene builders, taken once per
    process (the code a run imported), so one run's references share one key."""
    if _FINGERPRINT:
        return _FINGERPRINT[0]
    digest = hashlib.sha256()
    files = sorted((REPO_ROOT / "engine" / "tracer").rglob("*.py"))
    files += sorted((REPO_ROOT / "lenses").glob("*"))
    files += [BENCH_DIR / "scenes.py", BENCH_DIR / "geometry.py"]
    for path in files:
        if path.is_file():
            digest.update(str(path.relative_to(REPO_ROOT)).encode())
            digest.update(path.read_bytes())
    _FINGERPRINT.append(digest.hexdigest()[:16])
    return _FINGERPRINT[0]


def scene_fingerprint() -> str:
    """Hash of the scene builders only (what a peer's reference depends on)."""
    digest = hashlib.sha256()
    for path in (BENCH_DIR / "scenes.py", BENCH_DIR / "geometry.py"):
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _path(key: dict) -> Path:
    text = json.dumps(key, sort_keys=True)
    name = f"{key['renderer']}_{key['scene']}_{hashlib.sha256(text.encode()).hexdigest()[:12]}.npz"
    return CACHE_DIR / name


def load(key: dict):
    """The cached reference for ``key`` as a dict, or None."""
    path = _path(key)
    if not path.exists():
        return None
    with np.load(path, allow_pickle=False) as f:
        out = {k: f[k] for k in f.files}
    out["spp"] = int(out["spp"])
    out["seconds"] = float(out["seconds"])
    out["cached"] = True
    return out


def store(key: dict, image, variance, spp: int, seconds: float) -> dict:
    CACHE_DIR.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(_path(key), image=np.asarray(image, np.float32), variance=np.asarray(variance, np.float32),
                        spp=spp, seconds=seconds, key=json.dumps(key, sort_keys=True))
    return dict(image=image, variance=variance, spp=spp, seconds=seconds, cached=False)


def prism_reference(scene_name, scene, overrides: dict, spp: int, max_seconds: float, threads: int, log=print):
    """Prism's reference for ``scene`` rendered with ``overrides`` (cached)."""
    from .prism_runs import converge, settings_for

    key = dict(renderer="prism", scene=scene_name, resolution=list(scene.camera.resolution),
               overrides=overrides, spp=spp, code=code_fingerprint())
    cached = load(key)
    if cached is not None:
        log(f"  reference {scene_name} {overrides}: cached ({cached['spp']} spp)")
        return cached
    settings = settings_for(overrides, samples=spp, seed=424242, threads=threads)
    image, variance, reached, seconds, _ = converge(scene, settings, spp, max_seconds)
    log(f"  reference {scene_name} {overrides}: {reached} spp in {seconds:.1f} s")
    return store(key, image, variance, reached, seconds)


def peer_reference_key(peer: str, scene_name: str, resolution: int, spp: int, version: str) -> dict:
    return dict(renderer=peer, scene=scene_name, resolution=[resolution, resolution], spp=spp,
                version=version, scenes=scene_fingerprint())
