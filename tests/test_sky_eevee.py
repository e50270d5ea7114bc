"""The EEVEE world's light from the ground (addon/sky_eevee.py), without rendering: the sky's
irradiance its curves hold against the sky model's table, and the sun lamp its drivers read, ours
or one the artist swaps in. The render against Cycles is in test_eevee.py."""

import math

import bpy
import numpy as np
import pytest

from core import sun as sky_sun
from devtools import scenes


def driven(node):
    bpy.context.scene.frame_set(bpy.context.scene.frame_current)
    return np.array([node.inputs[i].default_value for i in range(3)])


def test_the_sky_irradiance_curves_hold_the_sky_models_table(sandscape):
    """The RGB Curves node, read at the sine of the sun's elevation and scaled by its peaks, against
    core.sun.sky_irradiance (linear in degrees between rows; the curves are linear in the sine)."""
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    nodes = bpy.context.scene.world.node_tree.nodes
    curves = nodes[sandscape.addon.sky_eevee.SKY_LIGHT]
    peaks = np.array(curves.outputs[0].links[0].to_node.inputs[1].default_value)  # the × Peak node
    for degrees in (0.0, 0.5, 3.0, 7.0, 13.0, 27.0, 45.0, 65.0, 90.0):
        sine = math.sin(math.radians(degrees))
        held = np.array([curves.mapping.evaluate(curves.mapping.curves[c], sine) for c in range(3)]) * peaks
        assert held == pytest.approx(sky_sun.sky_irradiance(math.radians(degrees)), rel=0.03, abs=0.05)


def test_the_ground_light_follows_our_sun_and_one_you_swap_in(sandscape):
    """Its drivers read the scene's sun: our lamp's axis, strength and colour; after the artist
    adds their own sun and deletes ours, theirs, at the next scene update."""
    module = sandscape.addon.sky_eevee
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    scenes.camera("PERSP", location=(0.0, -8.0, 1.5), rotation=(math.radians(85.0), 0.0, 0.0))
    settings = scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth = math.radians(20.0), math.radians(70.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    nodes = scene.world.node_tree.nodes
    ours = sandscape.addon.atmosphere.scene_sun(scene)
    assert driven(nodes[module.SUN]) == pytest.approx(np.array(ours.matrix_world.col[2][:3]), abs=1e-5)
    assert driven(nodes[module.SUN_LIGHT]) == pytest.approx(ours.data.energy * np.array(ours.data.color),
                                                            rel=1e-5)
    bpy.data.objects.remove(ours)
    theirs = bpy.data.objects.new("Key Sun", bpy.data.lights.new("Key Sun", "SUN"))
    theirs.data.energy, theirs.data.color = 4.0, (1.0, 0.8, 0.6)
    theirs.rotation_euler = (math.radians(50.0), 0.0, math.radians(30.0))
    theirs.scale = (2.0, 2.0, 2.0)  # a scaled lamp: its axis is longer, the node normalises it
    scene.collection.objects.link(theirs)
    bpy.context.view_layer.update()  # the next scene update, as the viewport makes
    assert module.followed_sun(scene.world) == theirs
    assert driven(nodes[module.SUN_LIGHT]) == pytest.approx([4.0, 3.2, 2.4], rel=1e-5)
    assert driven(nodes[module.SUN]) == pytest.approx(np.array(theirs.matrix_world.col[2][:3]), abs=1e-5)


@pytest.mark.parametrize("sand_first", [True, False])
def test_the_ground_light_takes_the_sands_colour(sandscape, sand_first):
    """The sand's colour reaches EEVEE's ground light by a driver, whether the sand or the sky came
    first; a colour the artist edits afterwards follows at the next evaluation."""
    module = sandscape.addon.sky_eevee
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    scenes.camera("PERSP", location=(0.0, -8.0, 1.5), rotation=(math.radians(85.0), 0.0, 0.0))
    steps = [bpy.ops.sandscape.add_sand_material, bpy.ops.sandscape.add_atmosphere]
    for step in steps if sand_first else steps[::-1]:
        assert step() == {"FINISHED"}
    material = sandscape.addon.sand.find_sand_material(bpy.context.active_object)
    assert module.followed_ground(scene.world) == material
    look = sandscape.addon.sand.look_node(material)
    look.inputs["Color"].default_value = (0.8, 0.3, 0.1, 1.0)
    scene.frame_set(scene.frame_current)
    colour = [socket.default_value for socket in scene.world.node_tree.nodes[module.GROUND_COLOR].inputs[:3]]
    assert colour == pytest.approx((0.8, 0.3, 0.1), abs=1e-6)
