"""EEVEE draws the sun's disc the Sky Texture leaves out there (its Sun Disc is Cycles only):
the sky world's EEVEE output puts an even disc, as wide as the lamp's, as bright as gives the
lamp's irradiance, in the camera's sky. Reference: the lamp's strength and colour over the
disc's solid angle (core.sun), and nothing of it off the disc.

An artist's lamp at strength 4: the sky model's own sun (about 10^6) passes the 65504 of
EEVEE's half-float film, which then holds it there."""

import math

import bpy
import numpy as np
import pytest
from mathutils import Vector

from core import sun as sky_sun
from devtools import readback, scenes

LENS = 500.0  # mm on a 36 mm sensor, 64 px across
ANGLE = 0.02  # radians: the artist's sun, about 18 pixels across here
RADIANCE_TOLERANCE = 0.01  # relative, per channel, on the pixels well inside the disc (the sky adds 0.2 %)


def _aim_at_the_artists_sun(scene, lens, angle, offset=(0.0, 0.0)):
    """The artist's lamp 30 degrees up, Add Atmosphere with no dust, a camera turned toward the sun
    (turned further by `offset`, radians about X and Z). Returns the sun, the camera and the
    direction toward the sun."""
    lamp = bpy.data.lights.new("Their Sun", "SUN")
    lamp.energy, lamp.color, lamp.angle = 4.0, (1.0, 0.9, 0.7), angle
    sun = bpy.data.objects.new("Their Sun", lamp)
    sun.rotation_euler = (math.radians(60.0), 0.0, math.radians(20.0))
    scene.collection.objects.link(sun)
    air = scene.sandscape_atmosphere
    air.density, air.dust_density, air.use_haze, air.use_wind = 0.0, 0.0, False, False
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 2.0), lens=lens)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    bpy.context.view_layer.update()
    toward = (sun.matrix_world.to_3x3() @ Vector((0.0, 0.0, 1.0))).normalized()
    turn = toward.to_track_quat("-Z", "Y").to_euler()
    turn.x, turn.z = turn.x + offset[0], turn.z + offset[1]
    camera.rotation_euler = turn
    bpy.context.view_layer.update()
    return sun, camera, toward


def test_eevee_draws_the_sun_disc_as_bright_as_the_lamp(eevee_scene, sandscape):
    scene = eevee_scene
    sun, camera, toward = _aim_at_the_artists_sun(scene, LENS, ANGLE)
    lamp = sun.data
    assert sandscape.addon.atmosphere.scene_sun(scene) == sun
    scene.eevee.taa_render_samples = 16
    pixels = readback.render(scene)[..., :3].astype(np.float64)
    assert np.isfinite(pixels).all()
    expected = sky_sun.disc_radiance(np.array(lamp.color) * lamp.energy, ANGLE)
    place = np.array([camera.location + toward * 100.0])
    columns, rows = scenes.project(camera, place, scene.render.resolution_x, scene.render.resolution_y)
    grid = np.stack(np.mgrid[0:pixels.shape[0], 0:pixels.shape[1]], -1) + 0.5
    distance = np.linalg.norm(grid - np.array([rows[0], columns[0]]), axis=-1)  # pixels from the sun
    radius = 0.5 * ANGLE / (camera.data.sensor_width / LENS / pixels.shape[1])
    inside, outside = pixels[distance < radius - 1.5], pixels[distance > radius + 2.5]
    print(f"disc radius {radius:.1f} px, {len(inside)} pixels inside: {inside.mean(0)} against {expected}; "
          f"off the disc at most {outside.max():.3g}")
    assert len(inside) >= 20
    assert np.allclose(inside.mean(0), expected, rtol=RADIANCE_TOLERANCE)
    assert outside.max() < 0.01 * expected.max()  # the sky beside it (about 0.2 %), no disc


@pytest.mark.sweep
@pytest.mark.parametrize("lens, samples, tolerance", [(35.0, 64, 0.1), (12.0, 256, 0.4)])
def test_eevee_draws_a_disc_smaller_than_a_pixel_in_place(eevee_scene, sandscape, lens, samples, tolerance):
    """The sky's own sun size (0.0095 rad) through a 35 mm and a 12 mm lens, 96x64: the disc 0.9
    and 0.3 pixel across, off the pixel grid. EEVEE's jittered samples find it: the light over the
    sky's level, summed round its brightest pixel, is the lamp's irradiance within 10 % for the
    larger disc at 64 samples; the smaller one's stays 1.0-1.36 times it from 16 to 1024 samples
    (EEVEE's film does not converge there: 40 %); its centroid lies within a quarter pixel of where
    Blender projects the sun. (The demo's EEVEE sun had not read as a dot; a disc missed between
    pixel centres was the guess this refutes from 16 samples on: at 1 and 4 it is missed.)"""
    scene = eevee_scene
    size = sandscape.addon.sun_lamp.SKY_SUN_SIZE
    width, height = 96, 64
    scene.render.resolution_x, scene.render.resolution_y = width, height
    # the sun off the frame's centre and its pixel's
    sun, camera, toward = _aim_at_the_artists_sun(scene, lens, size, offset=(0.021, 0.013))
    lamp = sun.data
    scene.view_settings.view_transform = "Standard"
    scene.eevee.taa_render_samples = samples
    pixels = readback.render(scene)[..., :3].astype(np.float64)
    assert np.isfinite(pixels).all()
    excess = np.clip(pixels - np.median(pixels, axis=(0, 1)), 0.0, None).sum(-1)
    row, col = np.unravel_index(np.argmax(excess), excess.shape)
    rows, cols = np.mgrid[row - 4:row + 5, col - 4:col + 5]
    window = excess[rows, cols]
    pixel_angle = camera.data.sensor_width / lens / width
    energy = window.sum() * pixel_angle ** 2 / (np.array(lamp.color) * lamp.energy).sum()
    centroid = np.array([(window * (rows + 0.5)).sum(), (window * (cols + 0.5)).sum()]) / window.sum()
    columns, heights = scenes.project(camera, np.array([camera.location + toward * 100.0]), width, height)
    miss = np.hypot(*(centroid - [heights[0], columns[0]]))
    print(f"lens {lens:g}: disc {size / pixel_angle:.2f} px across, {energy:.3f} of the lamp's "
          f"irradiance, centroid {miss:.2f} px from the sun's place")
    assert energy == pytest.approx(1.0, abs=tolerance) and miss < 0.25
