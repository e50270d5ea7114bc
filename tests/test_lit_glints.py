"""Lit glints: mirror facets on object-space grains, against their numpy twin (bakes) and as an
artist sees them (renders): which grains can glint, which way each facet leans, no glints in
shadow, and glints that stay on the sand when the camera moves.
"""

import math

import bpy
import numpy as np
import pytest

from core import sand as twin
from devtools import readback, scenes

RES = 128
PLANE = 2.0
BAKE_TOLERANCE = 1e-5
NORMAL_TOLERANCE = 2e-5  # a facet normal: float32 round-off of a normalised sum


def plane_positions(res=RES, size=PLANE):
    c = readback.pixel_centres(res, -size / 2, size / 2)
    x, y = np.meshgrid(c, c)
    return np.stack([x, y, np.zeros_like(x)], axis=-1)


@pytest.fixture
def lit_group(sandscape):
    return sandscape.node_groups.helper.ensure_group(sandscape.node_groups.lit_glints)


def bake(group, values, output):
    plane = readback.uv_plane(PLANE)
    material = scenes.group_material(group, values, output)
    plane.data.materials.append(material)
    return readback.bake_emit(plane, material, RES)


@pytest.mark.parametrize("threshold, size, seed", [(0.5, 1 / 16, 3), (0.9, 1 / 32, 11), (0.0, 1 / 8, 0)])
def test_which_grains_can_glint_is_the_twins(lit_group, threshold, size, seed):
    values = {"Threshold": threshold, "Glint Size": size, "Seed": float(seed)}
    baked = bake(lit_group, values, "Mask")[..., 0]
    noise, _ = twin.glint_cells(plane_positions(), size, seed)
    expected, _ = twin.glint_facets(noise, np.zeros(noise.shape + (3,)), (0, 0, 1), threshold, 8.0)
    assert np.abs(baked - expected).max() <= BAKE_TOLERANCE


@pytest.mark.parametrize("power", [0.0, 4.0, 64.0])
def test_facets_lean_as_the_twin_says(lit_group, power):
    values = {"Threshold": 0.0, "Glint Size": 1 / 16, "Seed": 5.0, "Facing Power": power}
    baked = bake(lit_group, values, "Facet Normal")[..., :3]
    noise, tilt = twin.glint_cells(plane_positions(), 1 / 16, 5)
    _, expected = twin.glint_facets(noise, tilt, (0.0, 0.0, 1.0), 0.0, power)
    assert np.abs(baked - expected).max() <= NORMAL_TOLERANCE
    tilt_angle = np.degrees(np.arccos(np.clip(expected[..., 2], -1, 1)))
    assert tilt_angle.max() <= np.degrees(np.arctan(twin.facet_spread(power) * np.sqrt(2))) + 1e-3


@pytest.mark.parametrize("power", [1.0, 2.0])
def test_a_facet_that_mirrors_the_view_into_the_ground_shows_the_sand(lit_group, power):
    """The baker looks along the normal (V = N): a facet's mirror is seen where it leans under 45
    degrees (R·N = 2 (F·N)² − 1 > 0), as the twin says. Wide spreads, so both kinds are many."""
    values = {"Threshold": 0.0, "Glint Size": 1 / 16, "Seed": 7.0, "Facing Power": power}
    baked = bake(lit_group, values, "Mirror")[..., 0]
    noise, tilt = twin.glint_cells(plane_positions(), 1 / 16, 7)
    _, facets = twin.glint_facets(noise, tilt, (0.0, 0.0, 1.0), 0.0, power)
    expected = twin.mirrors_view_above(facets, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0))
    print(f"facets seen: {baked.mean():.1%} (twin {expected.mean():.1%})")
    assert 0.1 < expected.mean() < 0.9
    assert np.abs(baked - expected).max() <= BAKE_TOLERANCE


def test_the_share_of_grains_that_can_glint_follows_threshold(lit_group):
    """Cells of 1 px over 128 x 128 bake points: each point its own grain."""
    for threshold in (0.5, 0.9, 0.98):
        values = {"Threshold": threshold, "Glint Size": PLANE / RES, "Seed": 2.0}
        mask = bake(lit_group, values, "Mask")[..., 0]
        p, n = 1.0 - threshold, mask.size
        sigma = math.sqrt(p * (1 - p) / n)
        assert abs(mask.mean() - p) <= 3 * sigma, (threshold, mask.mean())


# ---------------------------------------------------------------- renders

SUN_ELEVATION = math.radians(45)
# Seen face-on a quartz facet returns 4.5 % of the sun, and few clear a 4x bar. Tests of where
# sparkles go rather than how bright they are give their facets this IOR (about 67 % face-on).
MIRROR_IOR = 10.0


def glinting_ground(sandscape, glints="LIT", ior=None, **props):
    """Sand on a plane under a 45 degree sun from +Y, seen from the mirror direction (-Y, 45 degrees
    down): facets near the surface normal send the sun into the camera. ior: the facets' IOR
    (None: the group's, quartz)."""
    bpy.ops.mesh.primitive_plane_add(size=8)
    ground = bpy.context.active_object
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth, settings.density = SUN_ELEVATION, 0.0, 0.0
    settings.use_haze = False  # no volume at all: the glints alone
    settings.set_exposure = False
    bpy.ops.sandscape.add_atmosphere()
    bpy.context.view_layer.objects.active = ground
    bpy.ops.sandscape.add_sand_material(glints=glints, ripples=False, **props)
    if ior is not None:
        sandscape.addon.sand.glint_node(ground.active_material).inputs["IOR"].default_value = ior
    return ground


def glint_pixels(pixels):
    """Glints are far brighter than the sand around them: above 4x the frame's median."""
    brightness = pixels[..., :3].mean(-1)
    return brightness > 4.0 * np.median(brightness)


def glints_half_in_shadow(engine="CYCLES"):
    """Glint pixels of the ground seen from the sun's mirror direction, with a roof high above the
    left half (hidden from the camera) casting its shadow over x < 0."""
    bpy.ops.mesh.primitive_plane_add(size=1, location=(-10.0, 0.0, 6.0))
    roof = bpy.context.active_object
    roof.scale = (20.0, 40.0, 1.0)
    roof.visible_camera = False
    readback.cycles_scene(resolution=(96, 96), samples=4).render.engine = engine
    scenes.camera("ORTHO", location=(0.0, -10.0, 10.0), rotation=(math.radians(45), 0.0, 0.0),
                  ortho_scale=5.0)
    return glint_pixels(readback.render())


def test_lit_glints_only_where_the_sun_reaches(sandscape):
    glinting_ground(sandscape, threshold=0.7, glint_size=0.15, facing_power=64.0)
    glints = glints_half_in_shadow()
    sunlit, shaded = glints[:, 56:].mean(), glints[:, :40].mean()
    print(f"lit glints: {sunlit:.3%} of sunlit pixels, {shaded:.3%} of shaded")
    assert sunlit > 0.01
    assert shaded <= 0.1 * sunlit


def test_emission_glints_shine_in_the_shade_too(sandscape):
    """The same measure on emission glints: they sparkle in shadow, so the test can tell."""
    glinting_ground(sandscape, glints="EMISSION", threshold=0.7, glint_size=0.15, facing_power=0.0,
                    strength=600.0)
    glints = glints_half_in_shadow()
    assert glints[:, :40].mean() > 0.5 * glints[:, 56:].mean()


def test_lit_glints_stay_on_the_sand_when_the_camera_moves(sandscape):
    """Each sparkle pixel of A traced to the ground and projected into B (camera moved 5 cm and
    turned 1 degree): a sparkle of B lies within a pixel of it (sparkles are single pixels, and a
    sub-pixel sparkle may fall in either neighbour), far more often than chance."""
    glinting_ground(sandscape, ior=MIRROR_IOR, threshold=0.9, glint_size=0.1, facing_power=64.0)
    width, height = 128, 96
    readback.cycles_scene(resolution=(width, height), samples=16)
    cam = scenes.camera("PERSP", location=(0.0, -5.0, 5.0), rotation=(math.radians(45), 0.0, 0.0))
    kept, chance = scenes.sparkles_kept_after_camera_move(cam, lambda: glint_pixels(readback.render()),
                                                          width, height, enough=100)
    print(f"lit glints kept after the camera move: {kept:.1%} (chance {chance:.1%})")
    assert kept >= 0.85 and kept >= 4 * chance


@pytest.fixture
def facet_group(sandscape):
    return sandscape.node_groups.helper.ensure_group(sandscape.node_groups.glint_facet)


@pytest.mark.parametrize("ior", [twin.QUARTZ_IOR, 2.4])
def test_a_facet_reflects_the_fresnel_share_of_the_sky(facet_group, ior):
    """Every grain a flat, sharp facet (no sand under it) on a plane under a uniform white sky,
    seen by an orthographic camera at several angles: each pixel is the facet's colour times
    the dielectric's Fresnel reflectance at the view's angle (Fresnel's equations through
    Snell's law, core.sand.facet_fresnel), within 0.2 % of it (one sample of a sharp mirror of a
    uniform sky is exact but for float round-off)."""
    world = bpy.data.worlds.new("Uniform Sky")
    world.color = (1.0, 1.0, 1.0)
    if world.node_tree is not None:  # a new world's Background node starts grey
        background = next(n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeBackground")
        background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bpy.context.scene.world = world
    bpy.ops.mesh.primitive_plane_add(size=40)
    plane = bpy.context.active_object
    colour = (1.0, 0.8, 0.5, 1.0)
    plane.data.materials.append(scenes.group_material(
        facet_group, {"Noise": 1.0, "Threshold": 0.0, "Roughness": 0.0, "Color": colour, "IOR": ior},
        output="Shader"))
    readback.cycles_scene(resolution=(4, 4), samples=1)
    angles = (0.0, 40.0, 70.0, 85.0)  # the view's angle from the normal
    cam = scenes.camera("ORTHO", ortho_scale=0.5)
    measured = []
    for angle in angles:
        t = math.radians(angle)
        cam.location = (0.0, -10.0 * math.sin(t), 10.0 * math.cos(t))
        cam.rotation_euler = (t, 0.0, 0.0)
        measured.append(readback.render()[..., :3].mean(axis=(0, 1)))
    expected = twin.facet_fresnel(np.cos(np.radians(angles)), ior)[:, None] * np.array(colour[:3])
    print("facet reflectance", np.round(np.array(measured)[:, 0], 5), "expected", np.round(expected[:, 0], 5))
    assert 0.04 < expected[0, 0] < 0.2 and expected[-1, 0] > 0.4  # face-on dim, grazing bright
    np.testing.assert_allclose(measured, expected, rtol=2e-3, atol=1e-5)
