"""What the data passes read from Blender (``tracer.data_passes.DataPassInputs``): View Layer ▸ Passes ▸
Data switches and Alpha Threshold, World ▸ Mist Pass and World ▸ Ambient Occlusion ▸ Distance (Cycles reads the
same)."""

from __future__ import annotations

from collections import namedtuple

from ..tracer.data_passes import ALPHA_THRESHOLD_DEFAULT, AO_DISTANCE_DEFAULT, DataPassInputs

#: Which data passes the rendered view layer asks for (the per-triangle data is read only for those).
DataPassSwitches = namedtuple("DataPassSwitches", "uv object_index material_index")


def data_pass_switches(view_layer) -> DataPassSwitches:
    if view_layer is None:
        return DataPassSwitches(False, False, False)
    return DataPassSwitches(bool(getattr(view_layer, "use_pass_uv", False)),
                            bool(getattr(view_layer, "use_pass_object_index", False)),
                            bool(getattr(view_layer, "use_pass_material_index", False)))


def export_data_passes(scene, geometry, view_layer=None) -> DataPassInputs:
    """The data passes' inputs of ``scene`` whose meshes are ``geometry`` (``meshes.ExportedGeometry``), rendered
    as ``view_layer``."""
    inputs = DataPassInputs(object_pass_index=geometry.triangle_pass_index, uv=geometry.pass_uv,
                            material_pass_index=tuple(geometry.material_pass_index),
                            asset_names=tuple(geometry.object_asset_names),
                            material_names=tuple(geometry.material_names),
                            alpha_threshold=float(getattr(view_layer, "pass_alpha_threshold", ALPHA_THRESHOLD_DEFAULT)))
    world = scene.world
    if world is not None:
        mist = world.mist_settings
        inputs.mist_start_m = float(mist.start)
        inputs.mist_depth_m = float(mist.depth)
        inputs.mist_falloff = str(mist.falloff)
        inputs.ao_distance_m = world_ao_distance(scene)
    return inputs


def world_ao_distance(scene) -> float:
    """World ▸ Ambient Occlusion ▸ Distance (m): the AO pass's rays' length, and an Ambient Occlusion node's
    where its own Distance is 0 (Cycles' ``ao_bounces_distance``); Blender's default without a world."""
    world = getattr(scene, "world", None)
    if world is None:
        return AO_DISTANCE_DEFAULT
    return float(world.light_settings.distance)
