"""The Cryptomatte metadata of a render, as Cycles writes it on the Render Result (and Blender into a
multilayer EXR's header): per kind, under ``cryptomatte/<first 7 hex digits of the MurmurHash3_32 of
"<view layer>.Crypto<Kind>">/``, its ``name`` (that layer name), ``hash``, ``conversion`` and ``manifest``.
The compositor's Cryptomatte node finds a render's layers and the names to pick from there."""

from __future__ import annotations

from ..tracer.cryptomatte import KINDS, PASS_PREFIX, manifest
from ..tracer.murmurhash3 import murmurhash3_32

HASH = "MurmurHash3_32"
CONVERSION = "uint32_to_float32"
KEY_DIGITS = 7  # hex digits of the layer name's hash in the key (Blender's ``BKE_cryptomatte_meta_data_key``)


def layer_key(layer_name: str) -> str:
    """``cryptomatte/<7 hex digits>`` of a layer name such as "ViewLayer.CryptoObject"."""
    return f"cryptomatte/{murmurhash3_32(layer_name):08x}"[:len("cryptomatte/") + KEY_DIGITS]


def cryptomatte_metadata(view_layer: str, request, names) -> dict[str, str]:
    """Field → value for the Cryptomatte kinds ``request`` (``PassRequest``) asks for in ``view_layer``,
    with manifests of ``names`` (``tracer.cryptomatte.CryptomatteNames``): every object and material the
    render holds (Cycles also lists its lights, world and built-in shaders, which no pixel can show)."""
    out = {}
    for kind in KINDS:
        if kind in request.cryptomatte:
            layer = f"{view_layer}.{PASS_PREFIX}{kind}"
            key = layer_key(layer)
            out[f"{key}/name"] = layer
            out[f"{key}/hash"] = HASH
            out[f"{key}/conversion"] = CONVERSION
            out[f"{key}/manifest"] = manifest(names.of_kind(kind))
    return out


def stamp_cryptomatte(engine, view_layer: str, request, names) -> None:
    """Add the metadata to the render's whole Render Result (where Cycles adds it)."""
    fields = cryptomatte_metadata(view_layer, request, names)
    if not fields:
        return
    result = engine.get_result()
    for field, value in fields.items():
        result.stamp_data_add_field(field, value)
