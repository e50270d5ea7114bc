"""How the layer takes the light, rendered in Cycles: in a side light the cloud tops are bright and
the bases, which the sun reaches only through the cloud above them, darker."""

import math

import bpy
import numpy as np

from devtools import readback, scenes

BASE, THICKNESS = 1500.0, 2000.0
SUN_ELEVATION = math.radians(30.0)


def sand_ground(albedo=0.4):
    """A diffuse plane at z = 0 under the whole layer, of a desert's albedo."""
    bpy.ops.mesh.primitive_plane_add(size=100000.0)
    material = bpy.data.materials.new("Sand")
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (albedo,) * 3 + (1.0,)
    material.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
    bpy.context.active_object.data.materials.append(material)


def side_lit_layer(ground=False):
    """Add Clouds around an ortho camera at mid-layer, then the camera backed out of the layer's
    side (its density fades to zero there) to look at the clouds edge-on, 8 km across; a black
    sky and a point-like sun from the frame's right at 30 degrees. Returns the render, rows
    bottom-up, and the altitude of each row."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    readback.cycles_scene(scene, (160, 100), samples=16)
    scene.cycles.volume_biased = True  # ray marching, as the quality presets set it
    scene.cycles.volume_bounces, scene.cycles.max_bounces = 8, 8
    scene.render.film_transparent = True
    middle = BASE + THICKNESS / 2
    camera = scenes.camera("ORTHO", location=(0.0, 0.0, middle), rotation=(math.pi / 2, 0.0, 0.0),
                           ortho_scale=8000.0)
    camera.data.clip_end = 1e6
    world = bpy.data.worlds.new("Black")
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    lamp = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    lamp.data.angle, lamp.data.energy = 0.0, 5.0
    lamp.rotation_euler = (0.0, math.pi / 2 - SUN_ELEVATION, 0.0)  # light travels to -x and down
    scene.collection.objects.link(lamp)
    assert bpy.ops.sandscape.add_clouds(base=BASE, thickness=THICKNESS, coverage=0.5, seed=3,
                                        map_scale=3000.0, reach=2500.0, voxel=100.0) == {"FINISHED"}
    camera.location.y = -6000.0
    if ground:
        sand_ground()
    image = readback.render(scene)
    rows = image.shape[0]
    altitude = middle + (np.arange(rows) + 0.5 - rows / 2) / rows * 8000.0 * rows / image.shape[1]
    return image, altitude


def test_tops_are_brighter_than_bases_in_a_side_light():
    """Among the pixels the clouds cover (alpha above 0.9), those above 35 % of the layer's height
    (cumulus domes rise from 20 % to 70 %) are at least 1.5 times as bright as those of its
    lowest 15 %: sunlight reaches a base only through the cloud above it (exp(-tau) on the sun's
    path), a top directly."""
    image, altitude = side_lit_layer()
    assert np.isfinite(image).all()
    opaque = image[..., 3] > 0.9
    top = opaque & (altitude > BASE + 0.35 * THICKNESS)[:, None]
    base = opaque & (altitude < BASE + 0.15 * THICKNESS)[:, None]
    luminance = image[..., :3].mean(axis=-1)
    print(f"cloud pixels: top {top.sum()}, base {base.sum()}; mean radiance top "
          f"{luminance[top].mean():.4f}, base {luminance[base].mean():.4f}")
    assert top.sum() > 200 and base.sum() > 200
    assert luminance[top].mean() >= 1.5 * luminance[base].mean()


def test_the_ground_lights_the_bases_a_little():
    """Sand under the layer (albedo 0.4) sends light up into the bases: brighter than over no
    ground, still darker than the tops. Cycles does it with the paths' bounces."""
    image, altitude = side_lit_layer()
    grounded, _ = side_lit_layer(ground=True)
    base = (altitude < BASE + 0.15 * THICKNESS)[:, None] & (image[..., 3] > 0.9) & (grounded[..., 3] > 0.9)
    top = (altitude > BASE + 0.35 * THICKNESS)[:, None] & (grounded[..., 3] > 0.9)
    without, with_ground = (frame[..., :3].mean(axis=-1)[base].mean() for frame in (image, grounded))
    lit_top = grounded[..., :3].mean(axis=-1)[top].mean()
    print(f"bases: {without:.4f} over no ground, {with_ground:.4f} over sand; tops {lit_top:.4f}")
    assert 1.1 * without <= with_ground <= 0.8 * lit_top
