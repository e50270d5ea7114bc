"""Aerial perspective: far land fades toward the sky as exp(-beta d) (Koschmieder), measured on
marker pairs at known distances in a scene lit by Add Atmosphere (its sun, sky and dust box).

Each marker glows for camera rays only, and is rendered again black with the same seed: the
light scattered in front of it is the same in both, so the difference is the glow times the
transmittance exp(-beta d), whatever the sun and sky add; beta is the air's Rayleigh
coefficient plus the haze's 3.912 / V.
"""

import math

import bpy
import numpy as np
import pytest

from core import atmosphere as air
from devtools import readback, scenes, session

VISIBILITY = 4000.0  # m: a dusty afternoon
DENSITY = 2e-4  # 1/m at 550 nm: Rayleigh air, so the fade has a colour
DISTANCES = (100.0, 600.0, 1200.0)  # m
ANGLES = (-12.0, -4.0, 4.0)  # degrees from the view axis
SIZE = 3.0  # degrees: each marker's angular size
GLOW = 5.0
RESOLUTION = (192, 72)
TRANSMITTANCE_TOLERANCE = 0.01  # relative, on exp(-beta d) (64 samples: off by 0.33 % at most)
SKY_TOLERANCE = 0.02  # the far black marker against the horizon beside it, on 1 - exp(-beta d) (0.006)


def marker(name, glow, distance, angle):
    side = 2 * distance * math.tan(math.radians(SIZE / 2))
    centre = (distance * math.tan(math.radians(angle)), distance, 2.0)
    bpy.ops.mesh.primitive_plane_add(size=side, location=centre, rotation=(math.pi / 2, 0.0, 0.0))
    obj = bpy.context.active_object
    obj.name = name
    obj.visible_shadow = False  # the air in front of every marker is lit alike
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    path = tree.nodes.new("ShaderNodeLightPath")
    strength = tree.nodes.new("ShaderNodeMath")
    strength.operation = "MULTIPLY"
    strength.inputs[1].default_value = glow
    emission = tree.nodes.new("ShaderNodeEmission")
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(path.outputs["Is Camera Ray"], strength.inputs[0])
    tree.links.new(strength.outputs[0], emission.inputs["Strength"])
    tree.links.new(emission.outputs[0], output.inputs["Surface"])
    material.cycles.emission_sampling = "NONE"  # not a light: the air's samples stay the same
    obj.data.materials.append(material)
    return np.array([(centre[0] + dx * side / 2, distance, 2.0 + dz * side / 2)
                     for dx in (-1, 1) for dz in (-1, 1)])


def inside_pixels(camera, corners, resolution=RESOLUTION):
    """Rows and columns of the pixels well inside a marker (a pixel off its edge)."""
    columns, rows = scenes.project(camera, corners, *resolution)
    return (slice(int(math.ceil(rows.min())) + 1, int(rows.max()) - 1),
            slice(int(math.ceil(columns.min())) + 1, int(columns.max()) - 1))


@pytest.fixture(scope="module")
def rendered():
    session.reset()  # a module fixture starts before the empty file every test gets
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.pi / 2, 0.0, 0.0))
    camera.data.clip_end = 10000.0
    markers = [(distance, marker(f"Marker {distance:.0f}", GLOW, distance, angle))
               for distance, angle in zip(DISTANCES, ANGLES, strict=True)]
    scene = readback.cycles_scene(resolution=RESOLUTION, samples=64)
    settings = scene.sandscape_atmosphere
    settings.density, settings.dust_density, settings.use_wind = DENSITY, 0.0, False
    settings.use_haze, settings.visibility = True, VISIBILITY
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    glowing = readback.render(scene)[..., :3].astype(np.float64)
    for material in bpy.data.materials:
        if material.name.startswith("Marker"):
            glow = next(n for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeMath")
            glow.inputs[1].default_value = 0.0
    black = readback.render(scene)[..., :3].astype(np.float64)
    regions = [(distance, inside_pixels(camera, corners)) for distance, corners in markers]
    beta = np.asarray(air.rayleigh_coefficients(DENSITY)) + air.haze_extinction(VISIBILITY)
    _origins, directions = scenes.camera_rays(camera, *RESOLUTION)
    path = np.abs(1.0 / directions[..., 1])  # metres to a marker per metre of its distance
    return glowing, black, regions, beta, path


def test_contrast_falls_as_exp_minus_beta_d(rendered):
    glowing, black, regions, beta, path = rendered
    for distance, where in regions:
        difference = (glowing[where].mean(axis=(0, 1)) - black[where].mean(axis=(0, 1))) / GLOW
        expected = np.exp(-beta * distance * path[where][..., None]).mean(axis=(0, 1))
        print(f"{distance:.0f} m: white - black over the glow {np.round(difference, 4)}, "
              f"exp(-beta d) {np.round(expected, 4)}")
        assert np.abs(difference / expected - 1.0).max() <= TRANSMITTANCE_TOLERANCE
    # Koschmieder: at the visibility the haze alone leaves 2 % of the contrast.
    assert air.haze_extinction(VISIBILITY) * VISIBILITY == pytest.approx(-math.log(0.02))


def test_far_land_takes_the_skys_colour(rendered):
    """Against the horizon beside it, whose air is lit as the marker's (the sky higher up sees
    air nearer the dust box's top, which the sun reaches through less haze)."""
    _glowing, pixels, regions, beta, path = rendered
    distance, (rows, columns) = regions[-1]
    black = pixels[rows, columns].mean(axis=(0, 1))
    sky = pixels[rows, columns.stop + 4:columns.stop + 12].mean(axis=(0, 1))
    expected = 1.0 - np.exp(-beta * distance * path[rows, columns][..., None]).mean(axis=(0, 1))
    print(f"far black marker over the horizon beside it {np.round(black / sky, 3)}, "
          f"1 - exp(-beta d) {np.round(expected, 3)}")
    assert np.isfinite(pixels).all()
    assert np.abs(black / sky - expected).max() <= SKY_TOLERANCE
