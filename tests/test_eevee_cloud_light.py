"""The clouds' light in EEVEE's lighting world (core/cloud_light.py, addon/sky_eevee_clouds.py):
the measured table against what light can do, and the world's nodes, rendered by Cycles (which
integrates them exactly), against the twin. The twin against Cycles' own cloud layer, on weather
maps the table was not measured on: bench/cloud_light.py."""

import math

import bpy
import numpy as np
import pytest

from core import cloud_light, cloud_light_table
from core.sand import SAND_COLOR
from devtools import readback, scenes

NODES_TOLERANCE = 0.02  # of the clear sky's light: the world's curve against the twin


def test_the_clouds_send_down_no_more_sun_than_reaches_level_ground():
    """At every measured sun and coverage, the sun's light the layer passes on, by way of the
    sand or not (D + G x the sand's mean albedo), is less than the sine of the sun's elevation:
    the sun's light on a level square metre, which clouds that absorb nothing over sand that
    keeps some can at most pass on; D and G are never below none; B lies between none and all
    of the sky."""
    ground = float(np.mean(SAND_COLOR[:3]))
    for elevation, *triples in cloud_light_table.ROWS:
        for coverage, (d, g, b) in zip(cloud_light_table.COVERAGES, triples, strict=True):
            assert d >= 0.0 and g >= 0.0 and 0.0 < d + g * ground < math.sin(math.radians(elevation)), \
                (elevation, coverage, d, g)
            assert 0.0 < b < 1.0, (elevation, coverage, b)


def test_more_cloud_hides_more_sky_and_none_changes_nothing():
    depth = cloud_light_table.OPTICAL_DEPTH
    for elevation in (math.radians(6.0), math.radians(40.0)):
        hidden = [cloud_light.shares(elevation, c, depth)[2] for c in (0.1, 0.3, 0.6, 1.0)]
        assert hidden == sorted(hidden)
        assert cloud_light.shares(elevation, 0.0, depth) == (0.0, 0.0, 0.0)
        thicker = [cloud_light.shares(elevation, 0.5, depth * k)[2] for k in (0.5, 1.0, 2.0)]
        assert thicker == sorted(thicker)
    assert cloud_light.shares(math.radians(-3.0), 0.4, depth)[:2] == (0.0, 0.0)  # the sun set
    assert np.allclose(cloud_light.level_change(0.3, 0.0, depth, (100.0,) * 3, (5.0,) * 3), 0.0)


def _white_plane_under_the_eevee_world(sandscape, elevation):
    """Add Atmosphere (no dust, no haze) over a white plane seen from above, the world's EEVEE
    output the one that renders, the lamp's direct light off: the plane shows the world's light
    from above. Returns (scene, lamp)."""
    bpy.ops.mesh.primitive_plane_add(size=10.0)
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "White", "ShaderNodeBsdfDiffuse", Color=(1.0, 1.0, 1.0, 1.0)))
    scene = bpy.context.scene
    scenes.camera("ORTHO", location=(0.0, 0.0, 2.0), rotation=(0.0, 0.0, 0.0), ortho_scale=4.0)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = elevation, 0.4
    air.density, air.dust_density, air.use_wind, air.use_haze = 0.0, 0.0, False, False
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    tree = scene.world.node_tree
    tree.nodes.remove(tree.nodes["Sandscape World Output"])
    tree.nodes["Sandscape EEVEE World Output"].target = "ALL"
    lamp = sandscape.addon.atmosphere.scene_sun(scene)
    lamp.visible_diffuse = False
    readback.cycles_scene(scene, (4, 4), 16)
    return scene, lamp


def _irradiance(scene):
    return readback.render(scene)[..., :3].astype(np.float64).mean((0, 1)) * math.pi


@pytest.mark.parametrize("degrees,coverage,depth_scale", [(6.0, 0.4, 1.0), (25.0, 0.7, 2.0)])
def test_eevees_lighting_world_holds_the_twins_cloud_light(sandscape, degrees, coverage, depth_scale):
    """With the clouds' light set for a layer (an empty stands in for it), less without, is the
    twin's change of the light on level ground; hiding the layer in renders takes it away."""
    elevation = math.radians(degrees)
    scene, lamp = _white_plane_under_the_eevee_world(sandscape, elevation)
    clouds = sandscape.addon.sky_eevee_clouds
    depth = cloud_light_table.OPTICAL_DEPTH * depth_scale
    clear = _irradiance(scene)
    layer = bpy.data.objects.new("Layer Stand-In", None)
    scene.collection.objects.link(layer)
    clouds.follow(scene.world, layer, coverage, depth)
    cloudy = _irradiance(scene)
    sun = lamp.data.energy * np.array(lamp.data.color)
    sine = lamp.matrix_world.col[2].normalized().z
    ground = scene.world.node_tree.nodes[sandscape.addon.sky_eevee_ground.NODE]  # the white plane's
    twin = cloud_light.level_change(math.asin(sine), coverage, depth, sun, clear,
                                    [ground.inputs[i].default_value for i in range(3)])
    print(f"clouds' light at {degrees:g}°, coverage {coverage}: world {np.round(cloudy - clear, 3)}, "
          f"twin {np.round(twin, 3)}, clear sky {np.round(clear, 3)}")
    assert np.abs(cloudy - clear - twin).max() < NODES_TOLERANCE * clear.max()
    assert np.abs(twin).max() > 0.1 * clear.max()  # a change the test can see
    layer.hide_render = True
    scene.frame_set(scene.frame_current)  # drivers evaluated
    assert np.allclose(_irradiance(scene), clear, rtol=1e-3)
    clouds.follow(scene.world)
    assert np.allclose(_irradiance(scene), clear, rtol=1e-3)


def _held_shares(sandscape, world):
    held = sandscape.addon.sky_eevee_clouds.held(world)
    return np.array([shares for _, *shares in held[:-1]])  # the last point holds the highest sun's


def test_add_clouds_and_add_atmosphere_keep_the_world_on_the_layer(sandscape):
    """Add Clouds sets the world's cloud light for its coverage and optical depth, in either order
    with Add Atmosphere, in a scene measured in centimetres; a layer of no cloud clears it."""
    scene = bpy.context.scene
    scene.unit_settings.scale_length = 0.01
    scenes.camera("PERSP", location=(0.0, 0.0, 150.0), rotation=(math.radians(80.0), 0.0, 0.0))
    small = {"reach": 100.0, "voxel": 20000.0, "base": 120000.0, "thickness": 100000.0, "density": 0.03}
    assert bpy.ops.sandscape.add_clouds(coverage=0.55, **small) == {"FINISHED"}
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    _degrees, *shares = cloud_light.curves(0.55, 0.03 * 1000.0)  # 1000 m thick
    assert np.allclose(_held_shares(sandscape, scene.world), np.stack(shares, 1), rtol=1e-4, atol=1e-6)
    assert bpy.ops.sandscape.add_clouds(coverage=0.3, **small) == {"FINISHED"}
    _degrees, *shares = cloud_light.curves(0.3, 30.0)
    assert np.allclose(_held_shares(sandscape, scene.world), np.stack(shares, 1), rtol=1e-4, atol=1e-6)
    assert bpy.ops.sandscape.add_clouds(coverage=0.0, **small) == {"FINISHED"}
    assert np.allclose(_held_shares(sandscape, scene.world), 0.0)


def test_an_overcast_layer_passes_on_what_an_eddington_slab_does():
    """Coverage 1 against a uniform slab of the layer's full optical depth and its phase's mean
    cosine (dual lobe: 0.7 x 0.8 + 0.3 x -0.3) over the table's sand (its mean albedo): the sun's
    share within 35 % from 6 degrees up (the layer is carved by its shape noise, its tops catch
    a low sun from the side), the sky's within 0.1."""
    mean_cosine = 0.7 * 0.8 + 0.3 * -0.3
    ground = float(np.mean(SAND_COLOR[:3]))
    column = cloud_light_table.COVERAGES.index(1.0)
    for elevation, *triples in cloud_light_table.ROWS:
        d, g, b = triples[column]
        sine = math.sin(math.radians(elevation))
        sun, sky = cloud_light.eddington_slab(cloud_light_table.OPTICAL_DEPTH, mean_cosine, sine, ground)
        passed = d + g * ground  # the sun's light under the layer, by way of the sand or not
        print(f"overcast at {elevation}°: D + G x sand {passed:.4f}, slab {sun:.4f}; "
              f"B {b:.3f}, slab {1 - sky:.3f}")
        if elevation >= 6:
            assert passed == pytest.approx(sun, rel=0.35)
        assert b == pytest.approx(1.0 - sky, abs=0.1)
