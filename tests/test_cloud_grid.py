"""The cloud layer's voxel grid (geometry nodes, addon/cloud_grid.py) against the procedural
density's twin (core.clouds.density) at voxel centres; the grid drifting with the wind; the
density fading to zero inside the layer's box; a turned camera still under cloud.
"""

import importlib
import math

import bpy
import numpy as np
import pytest

from core import clouds as twin
from devtools import operators, readback, scenes, session

clouds = importlib.import_module(f"{session.MODULE}.addon.clouds")
cloud_grid = importlib.import_module(f"{session.MODULE}.addon.cloud_grid")

GRID_TOLERANCE = 1e-3  # of the densest cloud: the issue's
# The twin in float64 against Blender's float32 noise, through the sharpened edges (x 3): 99th
# percentile and largest difference, of the densest cloud (measured 2.9e-3 and 6.3e-3).
TWIN_TOLERANCE = (5e-3, 1.5e-2)
SMALL = {"reach": 3000.0, "voxel": 100.0, "map_scale": 2000.0, "shape_scale": 600.0, "coverage": 0.6}


def layer(scene):
    return next(o for o in scene.objects if o.get("sandscape_object") == "clouds")


def ground_camera(**values):
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scenes.camera("PERSP", location=(200.0, -300.0, 2.0), rotation=(math.radians(80.0), 0.0, 0.4))
    scene.camera.data.clip_end = 1e5
    scene.sandscape_atmosphere.wind = (6.0, -2.0, 0.0)
    assert bpy.ops.sandscape.add_clouds(**{**SMALL, **values}) == {"FINISHED"}
    return scene


def voxel_centres(box, voxel, rng, count):
    corner_min, _corner_max, counts = box
    index = np.column_stack([rng.integers(0, n, count) for n in counts])
    return np.asarray(corner_min) + index * voxel


@pytest.mark.parametrize("cloud_type", ["CUMULUS", "MIXED"])
def test_grid_is_the_procedural_density_at_voxel_centres(sandscape, cloud_type):
    """Against Blender's own procedural evaluation of the same groups at the same points (the
    issue's 1e-3), and against the numpy twin (float32 noise through the sharpened edges)."""
    scene = ground_camera(cloud_type=cloud_type)
    s = clouds.scene_settings(scene)
    plan = clouds.plan(scene, s)
    points = voxel_centres(plan["box"], s["voxel"], np.random.default_rng(3), 4000)
    grid = readback.grid_values(layer(scene), points)
    weather = clouds.weather_inputs(scene, s)
    helper = sandscape.node_groups.helper
    procedural = readback.field_values(
        [(helper.ensure_group(sandscape.node_groups.weather_map.GEOMETRY), weather["inputs"],
          weather["linked"]),
         (helper.ensure_group(sandscape.node_groups.cloud_density.GEOMETRY),
          clouds.density_inputs(scene, s, plan["region"], plan["fade"], True), ())],
        points, "Cloudiness")
    p = {**clouds.parameters(scene, s), "region": (*plan["region"], plan["fade"])}
    expected = twin.density(points, p)
    peak = p["density"] * (1.0 + twin.PRECIPITATION_GAIN * p["precipitation"])
    rendered = twin.density_from_cloudiness(grid, p)  # what the grid's material makes of it
    to_procedural = np.abs(rendered - twin.density_from_cloudiness(procedural, p)) / peak
    to_twin = np.abs(rendered - expected) / peak
    print(f"{cloud_type}: {np.mean(expected > 0):.0%} of the voxels hold cloud; grid vs procedural "
          f"{to_procedural.max():.1e} of the peak; vs twin 99th percentile "
          f"{np.percentile(to_twin, 99):.1e}, largest {to_twin.max():.1e}")
    assert np.mean(expected > 0.01 * peak) > 0.1, "the sample should hold cloud"
    assert to_procedural.max() <= GRID_TOLERANCE
    assert np.percentile(to_twin, 99) <= TWIN_TOLERANCE[0] and to_twin.max() <= TWIN_TOLERANCE[1]


def test_grid_drifts_with_the_wind_as_the_procedural_layer_does():
    """At frame f the layer's object stands at wind x f / fps: the grid seen there is the
    procedural density at that frame."""
    scene = ground_camera()
    cloud = layer(scene)
    fps = scene.render.fps / scene.render.fps_base
    for frame in (1, 97):
        scene.frame_set(frame)
        moved = np.array(cloud.matrix_world.translation)
        carried = np.array(scene.sandscape_atmosphere.wind[:2]) * frame / fps
        assert moved[:2] == pytest.approx(carried, abs=1e-3)
    assert cloud.matrix_world.translation.z == 0.0


def test_density_fades_to_zero_inside_the_box():
    scene = ground_camera(coverage=1.0)
    s = clouds.scene_settings(scene)
    plan = clouds.plan(scene, s)
    corner_min, corner_max, _counts = plan["box"]
    rng = np.random.default_rng(5)
    z = rng.uniform(corner_min[2], corner_max[2], 400)
    edges = []
    for axis, value in ((0, corner_min[0]), (0, corner_max[0]), (1, corner_min[1]), (1, corner_max[1])):
        points = np.column_stack([rng.uniform(corner_min[0], corner_max[0], 400),
                                  rng.uniform(corner_min[1], corner_max[1], 400), z])
        points[:, axis] = value
        edges.append(readback.grid_values(layer(scene), points))
    top = np.column_stack([rng.uniform(corner_min[0], corner_max[0], 400),
                           rng.uniform(corner_min[1], corner_max[1], 400), np.full(400, corner_max[2])])
    bottom = top.copy()
    bottom[:, 2] = corner_min[2]
    edges += [readback.grid_values(layer(scene), top), readback.grid_values(layer(scene), bottom)]
    inside = np.column_stack([rng.uniform(-500, 500, 400), rng.uniform(-500, 500, 400), z])
    assert readback.grid_values(layer(scene), inside).max() > 0.0, "full coverage holds cloud inside"
    # Cloudiness at most 0 on every side (up to float rounding: 1e-6 of the peak over a 100 km box
    # is an optical depth of 2e-6), so the material's max(cloudiness, 0) x Density is 0.
    assert max(float(edge.max()) for edge in edges) <= 1e-6


def test_a_turned_camera_and_another_frame_size_stay_inside_the_layer():
    scene = ground_camera()
    before = clouds.plan(scene, clouds.scene_settings(scene))["region"]
    scene.camera.rotation_euler.z += math.pi  # looks the other way
    scene.render.resolution_x, scene.render.resolution_y = 400, 1200  # portrait
    bpy.context.view_layer.update()
    after = clouds.plan(scene, clouds.scene_settings(scene))["region"]
    assert after == pytest.approx(before)


def test_too_many_voxels_coarsen_the_grid_with_a_warning(monkeypatch):
    """A fast wind carries the sky far over the shot: the grid keeps within its budget by larger
    voxels, and says so. (A budget of 300,000 voxels here: evaluating the real one takes 20 s.)"""
    monkeypatch.setattr(cloud_grid, "MAX_VOXELS", 300_000)
    bpy.ops.wm.read_homefile(use_empty=True)
    scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.radians(80.0), 0.0, 0.0))
    bpy.context.scene.camera.data.clip_end = 1e6
    bpy.context.scene.sandscape_atmosphere.wind = (9000.0, -9000.0, 0.0)
    result, reports = operators.run_execute("sandscape.add_clouds", voxel=5.0)
    assert result == {"FINISHED"}
    warning = [text for kinds, text in reports if kinds == {"WARNING"}]
    assert warning and "Voxel Size 5 m would make" in warning[0], reports
    plan = clouds.plan(bpy.context.scene, clouds.scene_settings(bpy.context.scene))
    assert plan["voxels"] <= cloud_grid.MAX_VOXELS and plan["voxel"] > 5.0
    # As fine as the budget lets: 1 % finer would be past it (the share of the budget used is not
    # a bound: a layer a few voxels high gains a fifth with one more, 0.86 of it here).
    settings = clouds.scene_settings(bpy.context.scene)
    low, high = settings["base"], settings["base"] + settings["thickness"]
    finer = cloud_grid.box_and_resolution(plan["carried"], low, high, plan["voxel"] / 1.01)
    assert math.prod(finer[2]) > cloud_grid.MAX_VOXELS


def test_a_camera_that_clips_short_of_the_layer_is_warned():
    bpy.ops.wm.read_homefile(use_empty=True)
    scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.radians(80.0), 0.0, 0.0))
    bpy.context.scene.camera.data.clip_end = 1000.0  # short of the layer's base at 1.5 km
    result, reports = operators.run_execute("sandscape.add_clouds", reach=3000.0)
    assert result == {"FINISHED"}
    warning = [text for kinds, text in reports if kinds == {"WARNING"}]
    assert warning and "clips at 1 km" in warning[0] and "Clip End" in warning[0], reports
    bpy.context.scene.camera.data.clip_end = 1e5
    result, reports = operators.run_execute("sandscape.add_clouds", reach=3000.0)
    assert not [text for kinds, text in reports if kinds == {"WARNING"}]
