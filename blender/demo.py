"""The desert demo scene, built from an empty file with Sandscape's own bpy layer."""

import math

import bpy
import numpy as np

from ..core import dunes
from . import atmosphere, clouds, footprints, post, presets, sand, walker

TERRAIN_SIZE = (120.0, 60.0)  # wide enough that the camera never sees past the dunes
TERRAIN_SPACING = 0.25
FRAMES = (1, 240)
SUN = (math.radians(6.0), 0.85)  # low, ahead-left of the walker, in view: slopes lit from the side
CAMERA_OFFSET = (-4.5, -1.5, 0.9)  # behind, beside and low, metres: the prints read in raking sun
CAMERA_SHIFT = (0.05, 0.05)  # lens shift, not a tilt: the walker low in frame, the low sun in it
AIR = {"density": 0.003, "dust_density": 0.002, "margin": 20.0}
CLOUDS = {"coverage": 0.4, "seed": 2, "base": 700.0, "thickness": 1200.0, "step": 400.0,
          "reach": 8000.0}  # low cumulus above the haze; seed 2 leaves the sun clear of them all walk
PRINTS = {"depth": 0.05, "rim": 0.015}  # metres: soft sand
SAND = {"Threshold": 0.985, "Glint Size": 0.012, "Facing Power": 4.0, "Strength": 60.0, "Seed": 1.0}


def dune_terrain(collection):
    vertices, quads = dunes.grid(*TERRAIN_SIZE, TERRAIN_SPACING)
    mesh = bpy.data.meshes.new("Dunes")
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", vertices.astype(np.float32).ravel())
    mesh.loops.add(quads.size)
    mesh.loops.foreach_set("vertex_index", quads.ravel().astype(np.int32))
    mesh.polygons.add(len(quads))
    mesh.polygons.foreach_set("loop_start", (np.arange(len(quads)) * 4).astype(np.int32))
    mesh.update(calc_edges=True)
    uv = vertices[quads.ravel(), :2] / np.array(TERRAIN_SIZE) + 0.5
    mesh.uv_layers.new(name="UVMap").uv.foreach_set("vector", uv.astype(np.float32).ravel())
    mesh.shade_smooth()
    terrain = bpy.data.objects.new("Dunes", mesh)
    collection.objects.link(terrain)
    return terrain


def follow_camera(scene, walker):
    """A camera that keeps its offset from the walker and looks at it (constraints, no scripts)."""
    camera = bpy.data.objects.new("Demo Camera", bpy.data.cameras.new("Demo Camera"))
    camera.data.lens = 24.0
    camera.data.clip_end = 40000.0  # the clouds are kilometres away
    camera.data.shift_x, camera.data.shift_y = CAMERA_SHIFT
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.location = CAMERA_OFFSET
    follow = camera.constraints.new("COPY_LOCATION")
    follow.target = walker
    follow.use_offset = True
    aim = camera.constraints.new("TRACK_TO")
    aim.target = walker
    aim.track_axis, aim.up_axis = "TRACK_NEGATIVE_Z", "UP_Y"
    return camera


def build(context):
    """Dunes, glinting sand, a walker with footprints, dusty air with a low sun, clouds, post effects,
    camera.

    Calls the bpy layer directly with known-good values (operators validate artists' input).
    """
    scene = context.scene
    scene.frame_start, scene.frame_end = FRAMES
    # Its denoising comes with the post effects below, once there is a camera and a sun.
    presets.apply(scene, {k: v for k, v in presets.PRESETS["PREVIEW"].items() if k != presets.DENOISE})
    terrain = dune_terrain(scene.collection)
    context.view_layer.objects.active = terrain
    sand.apply(terrain, {**sand.default_glint_values(), **SAND}, ripple_values=sand.default_ripples(scene))
    steps = scene.sandscape_footprints
    steps.terrain = terrain
    steps.walker, path = walker.ensure_walker(scene, terrain, *FRAMES)  # 14 m in 10 s, on the dunes
    steps.source = "WALKER"
    steps.resolution = 2048
    for name, value in PRINTS.items():
        setattr(steps, name, value)
    footprints.paint(scene, steps)
    camera = follow_camera(scene, steps.walker)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = SUN
    for name, value in AIR.items():
        setattr(air, name, value)
    # The sun lamp gets the sky's own sun (reddened 6 degrees up) and the scene the exposure
    # that shows level ground under it at its own grey; the dust box spans what the camera
    # sees over the frames, out to where the haze lets 1 % through.
    atmosphere.apply(scene, air)
    scene.view_settings.view_transform = "AgX"
    scene.view_settings.look = "AgX - Punchy"  # the haze greys the sand; AgX's base look more so
    for name, value in CLOUDS.items():
        setattr(scene.sandscape_clouds, name, value)
    clouds.apply(scene, clouds.scene_settings(scene))  # spans the camera's views over the frames
    post.apply_post_effects(scene, scene.sandscape_post)
    return {"terrain": terrain, "camera": camera, "walker": steps.walker}
