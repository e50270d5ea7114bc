"""Sand that reads as sand on an artist's own scene: the hue and saturation of the lit sand in
display values (as the eye sees the PNG), across sun elevations, under Add Atmosphere's sky and
default haze. A user's low sun once gave bluish-white sand (hue 202 degrees) or grey (saturation
0.13); real quartz sand is orange-yellow, hue about 25-45 degrees (look references)."""

import math

import bpy
import numpy as np
import pytest

from devtools import look, readback, scenes

HUE_RANGE = (20.0, 50.0)  # the look references' 25-45 degrees, with 5 degrees for the renderer
MIN_SATURATION = 0.2


@pytest.mark.parametrize("elevation", (5, pytest.param(20, marks=pytest.mark.sweep), 50))
def test_lit_sand_reads_as_sand(sandscape, elevation, tmp_path):
    terrain = scenes.height_field(400.0, 40, lambda x, y: 1.5 * np.sin(x / 23.0) * np.cos(y / 31.0),
                                  name="Their Ground")
    terrain.rotation_euler.z = 0.4  # their own placement, not ours
    camera = scenes.camera("PERSP", location=(0.0, -60.0, 4.0), rotation=(math.radians(82), 0.0, 0.0),
                           lens=35.0)
    camera.data.clip_end = 1e4
    scene = bpy.context.scene
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(elevation), math.radians(120.0)
    air.set_exposure = True  # as the report suggests for this sky
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}  # default dust and 20 km haze
    bpy.context.view_layer.objects.active = terrain
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    readback.cycles_scene(scene, (96, 54), 16)
    scene.cycles.use_denoising = True
    pixels = readback.render_display(scene, tmp_path / "sand.png")
    hue, saturation = look.lit_lower_half(pixels)
    print(f"sun {elevation} deg: lit sand hue {hue:.1f} deg, saturation {saturation:.3f}")
    assert HUE_RANGE[0] <= hue <= HUE_RANGE[1]
    assert saturation >= MIN_SATURATION
