"""The sun's light let through, baked per voxel of the cloud grid (addon/cloud_sunlight.py): the
geometry nodes' march against its numpy twin (core.cloud_shadows.voxel_transmittance), the twin
against exp(-sigma d / sin e) through a uniform layer, and the light following a turned sun."""

import importlib
import math

import bpy
import numpy as np

from core import cloud_shadows as twin
from devtools import readback, scenes, session

clouds = importlib.import_module(f"{session.MODULE}.addon.clouds")
cloud_sunlight = importlib.import_module(f"{session.MODULE}.addon.cloud_sunlight")
sun_lamp = importlib.import_module(f"{session.MODULE}.addon.sun_lamp")

MARCH_TOLERANCE = 1e-3  # float32 sums of up to 48 steps against float64
SMALL = {"reach": 3000.0, "voxel": 150.0, "map_scale": 2000.0, "shape_scale": 600.0, "coverage": 0.6}


def _sun(elevation, azimuth):
    lamp = bpy.data.objects.new("Artist Sun", bpy.data.lights.new("Artist Sun", "SUN"))
    bpy.context.scene.collection.objects.link(lamp)
    lamp.rotation_euler = sun_lamp.sun_rotation(math.radians(elevation), math.radians(azimuth))
    return lamp


def _layer_with_sun(elevation, azimuth):
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scenes.camera("PERSP", location=(200.0, -300.0, 2.0), rotation=(math.radians(80.0), 0.0, 0.4))
    scene.camera.data.clip_end = 1e5
    lamp = _sun(elevation, azimuth)
    scene.render.engine = "BLENDER_EEVEE"
    assert bpy.ops.sandscape.add_clouds(**SMALL) == {"FINISHED"}
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    return scene, layer, lamp


def _baked_and_twin(scene, layer, lamp):
    s = clouds.scene_settings(scene)
    done = clouds.plan(scene, s)
    corner, _, counts = done["box"]
    axes = [corner[axis] + np.arange(counts[axis]) * done["voxel"] for axis in range(3)]
    centres = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    cloudiness = readback.grid_values(layer, centres).reshape(counts)
    baked = readback.grid_values(layer, centres, cloud_sunlight.GRID).reshape(counts)
    to_sun = np.array(lamp.matrix_world.to_3x3().col[2])
    steps = twin.steps_for(s["thickness"], to_sun, s["step"])
    expected = twin.voxel_transmittance(cloudiness, corner, done["voxel"], to_sun, s["thickness"], steps,
                                        clouds.parameters(scene, s)["density"], clouds.grid_wet(s))
    return baked, expected, cloudiness


def test_the_grid_bakes_the_suns_light_as_its_twin_marches_it(sandscape):
    """At every voxel centre, from the grid's own cloudiness; the sun 25 degrees up."""
    scene, layer, lamp = _layer_with_sun(25.0, 140.0)
    baked, expected, cloudiness = _baked_and_twin(scene, layer, lamp)
    cloudy = cloudiness > 0.0
    error = np.abs(baked - expected)
    print(f"{baked.size:,} voxels, {cloudy.mean():.0%} in cloud: light let through "
          f"{baked[cloudy].mean():.3f} there (twin {expected[cloudy].mean():.3f}), largest difference "
          f"{error.max():.1e}")
    assert cloudy.mean() > 0.05 and 0.05 < expected[cloudy].mean() < 0.95, "should be partly shaded"
    assert error.max() <= MARCH_TOLERANCE
    assert cloud_sunlight.baked(layer)


def test_the_baked_light_follows_a_turned_sun(sandscape):
    """The lamp's axis drives the march: turned by hand, the grid is the twin's for the new sun."""
    scene, layer, lamp = _layer_with_sun(25.0, 140.0)
    before, _, _ = _baked_and_twin(scene, layer, lamp)
    lamp.rotation_euler = sun_lamp.sun_rotation(math.radians(40.0), math.radians(300.0))
    bpy.context.view_layer.update()
    after, expected, cloudiness = _baked_and_twin(scene, layer, lamp)
    s = clouds.scene_settings(scene)
    # the step count stays the build's, for the sun at 25 degrees; the twin is given the same
    steps = twin.steps_for(s["thickness"], (math.cos(math.radians(25.0)), 0.0, math.sin(math.radians(25.0))),
                           s["step"])
    assert np.abs(after - before).max() > 0.3
    done = clouds.plan(scene, s)
    again = twin.voxel_transmittance(cloudiness, done["box"][0], done["voxel"],
                                     np.array(lamp.matrix_world.to_3x3().col[2]), s["thickness"], steps,
                                     clouds.parameters(scene, s)["density"], clouds.grid_wet(s))
    assert np.abs(after - again).max() <= MARCH_TOLERANCE


def test_the_twin_lets_through_exp_of_the_optical_depth_of_a_uniform_layer():
    """Cloudiness 1 everywhere in a layer 1 km thick: exp(-sigma (top - z) / sin e), within one
    step's midpoint error at the top (the sun along +x, so a narrow strip of grid holds the rays)."""
    corner, voxel, density = (-1000.0, -100.0, 1000.0), 100.0, 2e-3
    cloudiness = np.ones((71, 3, 11))
    heights = corner[2] + np.arange(11) * voxel
    for elevation in (10.0, 45.0, 80.0):
        to_sun = (math.cos(math.radians(elevation)), 0.0, math.sin(math.radians(elevation)))
        light = twin.voxel_transmittance(cloudiness, corner, voxel, to_sun, 1000.0, 48, density, 1.0)
        exact = np.exp(-density * (2000.0 - heights) / math.sin(math.radians(elevation)))
        step = 1000.0 / 48 / math.sin(math.radians(elevation))
        assert np.allclose(light[10, 1], exact, rtol=0, atol=density * step)


def test_a_grid_built_without_a_sun_carries_no_light_and_no_stale_drivers(sandscape):
    """The sun deleted and Add Clouds run again: one output for both engines, no driver left
    reading a lamp that is gone."""
    scene, layer, lamp = _layer_with_sun(25.0, 140.0)
    bpy.data.objects.remove(lamp)
    assert bpy.ops.sandscape.add_clouds(**SMALL) == {"FINISHED"}
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    tree = layer.modifiers[0].node_group
    assert not cloud_sunlight.baked(layer)
    assert tree.animation_data is None or not tree.animation_data.drivers
    nodes = layer.active_material.node_tree.nodes
    assert cloud_sunlight.OUTPUT not in nodes and nodes["Sandscape Output"].target == "ALL"
    scene.render.engine = "BLENDER_EEVEE"
    assert not sandscape.addon.cloud_shadows.unshaded(scene)  # no sun: nothing to shade


def test_a_scene_that_renders_with_cycles_gets_no_march(sandscape):
    """Cycles shades the clouds through the volume itself: the march would be evaluated for nothing.
    Switched to EEVEE, the Clouds section says so until Add Clouds runs again."""
    scene, layer, lamp = _layer_with_sun(25.0, 140.0)
    scene.render.engine = "CYCLES"
    assert bpy.ops.sandscape.add_clouds(**SMALL) == {"FINISHED"}
    assert not cloud_sunlight.baked(layer)
    assert cloud_sunlight.OUTPUT not in layer.active_material.node_tree.nodes
    scene.render.engine = "BLENDER_EEVEE"
    assert sandscape.addon.cloud_shadows.unshaded(scene)
    assert bpy.ops.sandscape.add_clouds(**SMALL) == {"FINISHED"}
    assert cloud_sunlight.baked(layer) and not sandscape.addon.cloud_shadows.unshaded(scene)


def test_the_sunlights_drivers_run_without_python(sandscape):
    """A farm renders with Python auto-run off: every driver the light adds is a simple expression."""
    _scene, layer, _lamp = _layer_with_sun(25.0, 140.0)
    trees = (layer.modifiers[0].node_group, layer.active_material.node_tree)
    found = [curve.driver for tree in trees for curve in tree.animation_data.drivers]
    assert len(found) >= 7  # the sun's axis in both trees, its light, the shadows' switch
    assert all(driver.is_simple_expression for driver in found)


def test_a_centimetre_scene_bakes_the_same_light(sandscape):
    """Unit scale 0.01, every length in scene units a hundred times the metre scene's: the same
    light let through at the same voxels."""
    scene, layer, lamp = _layer_with_sun(25.0, 140.0)
    metres, _, _ = _baked_and_twin(scene, layer, lamp)
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.scale_length = 0.01
    scenes.camera("PERSP", location=(2e4, -3e4, 200.0), rotation=(math.radians(80.0), 0.0, 0.4))
    scene.camera.data.clip_end = 1e7
    lamp = _sun(25.0, 140.0)
    scene.render.engine = "BLENDER_EEVEE"
    lengths = ("reach", "voxel", "map_scale", "shape_scale")
    assert bpy.ops.sandscape.add_clouds(**{k: v * 100.0 if k in lengths else v for k, v in SMALL.items()}) \
        == {"FINISHED"}
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    centimetres, _, _ = _baked_and_twin(scene, layer, lamp)
    assert centimetres.shape == metres.shape
    print(f"centimetres against metres: largest difference {np.abs(centimetres - metres).max():.1e}")
    assert np.abs(centimetres - metres).max() <= MARCH_TOLERANCE


def test_the_higher_orders_bring_less_than_the_sun_and_most_where_it_does_not_reach():
    """core.cloud_shadows.many_scatterings, the EEVEE clouds' higher orders: under the lamp's own
    light at a cloud's sunlit edge (7/8 of it at T = 1), none where no light gets in at all, and
    deep in a cloud (optical depth 20 towards the sun) far more than the single order's T."""
    assert twin.many_scatterings(1.0) == 0.875
    assert twin.many_scatterings(0.0) == 0.0
    deep = math.exp(-20.0)
    assert twin.many_scatterings(deep) > 1e3 * deep
    values = twin.many_scatterings(np.linspace(0.0, 1.0, 101))
    assert np.all(np.diff(values) > 0)
