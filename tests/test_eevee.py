"""EEVEE renders, few and small (issue 27): EEVEE needs an OpenGL context, which the bpy wheel
opens through EGL, on software OpenGL here. Where none can be made these tests skip and say so.
Each check runs at one or two settings in `make test`; its other settings (marked sweep, 10-30 s
a render on software OpenGL) run in `make stress`, which CI runs after it."""

import math

import bpy
import numpy as np
import pytest
from conftest import EEVEE_SIZE as SIZE  # the eevee_scene fixture's

from devtools import readback, scenes

SKY_TOLERANCE = 0.06  # per channel: EEVEE's sky lighting of the ground against Cycles'
HAZE_TOLERANCE = 0.10  # per channel: the same with the haze's light (single scattering in EEVEE)
WALL_TOLERANCE = 0.20  # per channel: a wall in shade, lit by the sky and the sand, against Cycles
WALL_TOLERANCE_DERUNG = 0.45  # the same where EEVEE's deringing caps the sand's light (below)


@pytest.mark.sweep  # 24-42 s of software OpenGL; Cycles' own check stays in make test
def test_god_rays_shine_from_the_sun_in_eevee(eevee_scene, sandscape):
    """The driven sun place and the rays work on EEVEE's own passes: the rays' glow peaks where
    Blender projects the sun."""
    scene = eevee_scene
    bpy.ops.mesh.primitive_plane_add(size=40)
    scenes.camera("PERSP", location=(0, -6, 1.0), rotation=(math.radians(88), 0, math.radians(-8)), lens=35)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(6), 0.0, 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene.sandscape_post.use_blur = scene.sandscape_post.use_denoise = False
    scene.sandscape_post.use_sun_glow = False  # the rays alone
    assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
    assert scene.render.engine == "BLENDER_EEVEE"
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    _, u, v, intensity = sandscape.addon.sun_screen.stepped_curve(scene, sun, 0.25)[0]
    assert intensity == 1.0 and 0.2 < u < 0.8 and 0.5 < v < 0.95  # in the frame, over the horizon
    with_rays = readback.render(scene)
    scene.render.use_compositing = False
    plain = readback.render(scene)
    assert np.isfinite(with_rays).all()
    rays = (with_rays - plain)[..., :3].sum(-1)
    assert rays.max() > 0.05  # they show
    row, col = np.unravel_index(np.argmax(rays), rays.shape)
    assert abs((col + 0.5) / SIZE[0] - u) < 0.08 and abs((row + 0.5) / SIZE[1] - v) < 0.12


@pytest.mark.sweep  # 24-42 s of software OpenGL; Cycles' own check stays in make test
def test_prints_displace_in_eevee(eevee_scene, sandscape):
    """A painted trail renders in EEVEE (it never finished while the print map was one Linear
    lookup: EEVEE reads displacement in the vertex stage, where software OpenGL's linear filtering
    of a float image crawls) and its hollows change the picture: the lit and shaded walls."""
    from devtools import scenes as more_scenes

    terrain = more_scenes.height_field(8.0, 8, name="Their Sand")
    walker = more_scenes.keyframed_walker(lambda f: (-1.5 + 3.0 * (f - 1) / 30, 0.0, 0.0), range(1, 32))
    more_scenes.footprint_settings(terrain, walker, (1, 31), resolution=512, depth=0.05, rim=0.006)
    bpy.context.view_layer.objects.active = terrain
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    material = terrain.active_material
    lookups = [node for node in material.node_tree.nodes if node.bl_idname == "ShaderNodeTexImage"
               and node.image is not None and node.image.get("sandscape_image") == "print_map"]
    assert len(lookups) == 4 and all(node.interpolation == "Closest" for node in lookups)
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(75), 0.0, math.radians(90)))
    scenes.camera("PERSP", location=(0.0, -1.4, 1.0), rotation=(math.radians(50), 0, 0), lens=35)
    eevee_scene.frame_set(31)
    node = sandscape.addon.sand.footprint_node(material)
    kept = node.inputs["Depth"].default_value, node.inputs["Rim"].default_value
    changed, change = {}, {}
    for engine in ("BLENDER_EEVEE", "CYCLES"):  # issue 27: prints change the picture as in Cycles
        eevee_scene.render.engine = engine
        eevee_scene.cycles.samples = 64
        node.inputs["Depth"].default_value, node.inputs["Rim"].default_value = kept
        pressed = readback.render(eevee_scene)
        node.inputs["Depth"].default_value = node.inputs["Rim"].default_value = 0.0
        flat = readback.render(eevee_scene)
        assert np.isfinite(pressed).all()
        difference = np.abs(pressed - flat)[..., :3].max(-1)
        changed[engine], change[engine] = difference > 0.05, difference.sum()
    eevee, cycles = changed["BLENDER_EEVEE"], changed["CYCLES"]
    # A wall EEVEE draws a pixel off Cycles' (it displaces the vertices it has, Cycles dices finer)
    # is the same wall: a change counts as in both where the other engine changed a pixel within
    # one pixel of it (without that slack, the ripples' default Meander 0.35 -> 0.8 took the
    # share from 39 to 26 %: 11-24 pixels changed).
    near_eevee, near_cycles = _within_a_pixel(eevee), _within_a_pixel(cycles)
    both = ((eevee & near_cycles) | (cycles & near_eevee)).sum() / max((eevee | cycles).sum(), 1)
    ratio = change["BLENDER_EEVEE"] / change["CYCLES"]
    print(f"prints change {eevee.sum()} of {eevee.size} pixels in EEVEE, {cycles.sum()} in Cycles; "
          f"{both:.0%} of those changed in either changed in both (within a pixel); the summed "
          f"change EEVEE / Cycles {ratio:.3f}")
    # 2.2 % when written; 1.0 % once the prints' walls straddled their outline (each print one
    # wall, 7 cm, shorter and narrower): flattened prints change none.
    assert eevee.sum() >= 0.007 * eevee.size
    # As much as in Cycles: the change summed over the frame (the pixels past 0.05 were asserted
    # within 2x until Meander 0.8 put them at 23 against 11 while the sums stayed 5.10 / 4.80).
    assert 0.75 <= ratio <= 1.25 and both >= 0.3


def _within_a_pixel(mask):
    """True where `mask` or any of its 8 neighbours is."""
    padded = np.pad(mask, 1)
    rows, cols = mask.shape
    return np.any([padded[r:r + rows, c:c + cols] for r in range(3) for c in range(3)], axis=0)


@pytest.mark.parametrize("resolution", [SIZE, (0, 0)], ids=["splat", "cells"])
def test_no_glint_facet_mirrors_the_world_under_the_horizon(eevee_scene, sandscape, resolution):
    """Every grain a sharp mirror over a black base at a low angle, under a world white below the
    horizon only. Cycles bends a reflection that would leave through the ground; EEVEE mirrors the
    world there (dark specks under a real sky). A facet that mirrors the view into the ground shows
    the base: the sand stays black (without that, 30 % of its pixels were bright with the splat and
    99 % with the cells)."""
    world = bpy.data.worlds.new("White Below the Horizon")
    eevee_scene.world = world
    tree = world.node_tree
    tree.nodes.clear()
    direction = tree.nodes.new("ShaderNodeTexCoord").outputs["Generated"]  # the ray's direction
    split = tree.nodes.new("ShaderNodeSeparateXYZ")
    helper = sandscape.node_groups.helper
    below = helper.math(tree, "LESS_THAN", split.outputs["Z"], 0.0)
    background = tree.nodes.new("ShaderNodeBackground")
    tree.links.new(direction, split.inputs[0])
    tree.links.new(below.outputs[0], background.inputs["Strength"])
    tree.links.new(background.outputs[0], tree.nodes.new("ShaderNodeOutputWorld").inputs["Surface"])
    eevee_scene.view_settings.view_transform = "Standard"
    bpy.ops.mesh.primitive_plane_add(size=80)
    ground = bpy.context.active_object
    scenes.camera("PERSP", location=(0.0, -12.0, 1.6), rotation=(math.radians(80), 0.0, 0.0))
    group = helper.ensure_group(sandscape.node_groups.lit_glints)
    values = {"Threshold": 0.0, "Glint Size": 0.01, "Facing Power": 1.0, "Roughness": 0.0,
              "Resolution X": resolution[0], "Resolution Y": resolution[1], "Pixel Angle": 0.01}
    ground.data.materials.append(scenes.group_material(group, values, "Shader"))
    sand = readback.render(eevee_scene)[: SIZE[1] // 3, :, :3]  # rows well below the horizon
    print(f"EEVEE, {resolution}: sand mean {sand.mean():.4f}, brightest {sand.max():.3f}")
    assert np.isfinite(sand).all() and sand.max() <= 0.05


@pytest.mark.parametrize("glints", ["LIT", "EMISSION"])
def test_glints_in_the_sun_and_the_shade_in_eevee(eevee_scene, sandscape, glints):
    """The Cycles test's scene in EEVEE: lit glints sparkle where the sun reaches and not in the
    roof's shadow; emission glints (the test can tell) sparkle in both."""
    from test_lit_glints import MIRROR_IOR, glinting_ground, glints_half_in_shadow

    if glints == "LIT":  # where they shine, not how bright: facets nearly mirrors
        glinting_ground(sandscape, ior=MIRROR_IOR, threshold=0.7, glint_size=0.15, facing_power=64.0)
    else:
        glinting_ground(sandscape, glints="EMISSION", threshold=0.7, glint_size=0.15, facing_power=0.0,
                        strength=600.0)
    shown = glints_half_in_shadow("BLENDER_EEVEE")
    sunlit, shaded = shown[:, 56:].mean(), shown[:, :40].mean()
    print(f"EEVEE, {glints.lower()} glints: {sunlit:.2%} of sunlit pixels, {shaded:.2%} of shaded")
    assert sunlit > 0.01
    if glints == "LIT":
        assert shaded <= 0.1 * sunlit
    else:
        assert shaded > 0.5 * sunlit


def test_dust_transmittance_per_channel_in_eevee(eevee_scene, sandscape):
    """The Cycles test's slab in EEVEE: the glow seen through 1 m of dust is exp(-beta d) per channel
    (EEVEE integrates the slab in its froxel grid)."""
    from test_atmosphere import DENSITY, THICKNESS, camera_only_emitter

    from core import atmosphere as air

    camera_only_emitter()
    beta = air.rayleigh_coefficients(DENSITY)
    box = ((-2.0, -2.0, 0.5), (2.0, 2.0, 0.5 + THICKNESS))
    sandscape.addon.atmosphere.ensure_volume(eevee_scene, beta, *box)
    eevee_scene.view_settings.view_transform = "Standard"
    eevee_scene.world = None
    scenes.camera("ORTHO", location=(0.0, 0.0, 5.0), ortho_scale=1.0)
    pixels = readback.render(eevee_scene)[..., :3].reshape(-1, 3)
    expected = air.slab_transmittance(beta, THICKNESS)
    measured = pixels.mean(axis=0)
    print(f"EEVEE transmittance {measured.round(4)}, exp(-beta d) {np.round(expected, 4)}")
    assert np.isfinite(pixels).all()
    assert np.abs(measured / expected - 1.0).max() < 0.01, (measured, expected)  # 0.7 % when written
    assert measured[2] < measured[1] < measured[0]


# 55° ahead in make stress (22 s; 5.0's make test went past its 10 minutes): make test checks the
# balances there on the measured views (test_eevee_balance.py). make test's 15° case leaves out
# EEVEE without the output (a second shader compile, 15-20 s); make stress has it.
@pytest.mark.parametrize("elevation,azimuth,without_output", [
    (15.0, 150.0, False),
    pytest.param(15.0, 150.0, True, marks=pytest.mark.sweep),
    pytest.param(55.0, 0.0, True, marks=pytest.mark.sweep),
    pytest.param(70.0, 150.0, True, marks=pytest.mark.sweep),
    pytest.param(8.0, 30.0, True, marks=pytest.mark.sweep)])
def test_sand_in_eevee_is_as_bright_as_in_cycles(eevee_scene, sandscape, elevation, azimuth, without_output):
    """Flat sand with ripples under Add Atmosphere's sun, dust and haze, at eye level: EEVEE's mean
    brightness (luminance) over the ground within the issue's 15 % of Cycles' with the sand's EEVEE
    output, each channel within 25 %, and (make stress) at most half as far off as without it (Lambert diffuse
    and a diffuse-like sheen against Cycles' rough diffuse and microfiber sheen). The sun behind the
    camera at 15° and 70°, ahead at 55° (there the one balance of 2026-12-05 left red +19 %), and
    8° high 30° off ahead (neither a measured sun nor azimuth: Balance v8, fitted on azimuths 0,
    90 and 180° alone, was +28 % there through a long lens 15° down). Luminance when written
    (v9), on 5.2: -7.2 % at 15° (-55.5 % without the output), -0.8 % at 55° ahead (+72.7 %),
    -2.5 % at 70° (+13.4 %), -1.0 % at 8° (-11.4 %); v8 on 5.0: -12.7 % (blue -19.9 %), +0.0 %
    (blue -9.1 %), -3.2 %."""
    bpy.ops.mesh.primitive_plane_add(size=400)
    ground = bpy.context.active_object
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    air = eevee_scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(elevation), math.radians(azimuth)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scenes.camera("PERSP", location=(0.0, 0.0, 1.6), rotation=(math.radians(80), 0.0, 0.0), lens=35)
    eevee_scene.frame_set(1)

    def ground_mean(engine):
        eevee_scene.render.engine = engine
        eevee_scene.cycles.samples, eevee_scene.cycles.use_denoising = 16, False
        return readback.render(eevee_scene)[: SIZE[1] // 2, :, :3].astype(np.float64).mean((0, 1))

    cycles, balanced = ground_mean("CYCLES"), ground_mean("BLENDER_EEVEE")
    luminance = np.array((0.2126, 0.7152, 0.0722))
    brightness = balanced @ luminance / (cycles @ luminance) - 1.0
    print(f"sun {elevation:g}° at {azimuth:g}°: EEVEE against Cycles {np.round(balanced / cycles - 1, 3)} "
          f"(luminance {brightness:+.3f}) balanced")
    assert abs(brightness) <= 0.15 and np.abs(balanced / cycles - 1.0).max() <= 0.25
    if without_output:
        material, addon = ground.active_material, sandscape.addon
        addon.sand_eevee.attach(material, eevee_scene, addon.sand.look_node(material), None)
        plain = ground_mean("BLENDER_EEVEE")
        without = plain @ luminance / (cycles @ luminance) - 1.0
        print(f"sun {elevation:g}° at {azimuth:g}°: without the output {np.round(plain / cycles - 1, 3)} "
              f"({without:+.3f})")
        assert abs(brightness) <= 0.5 * abs(without)


@pytest.mark.parametrize("elevation", [10, pytest.param(30, marks=pytest.mark.sweep),
                                       pytest.param(60, marks=pytest.mark.sweep)])
def test_journey_sphere_in_eevee_is_the_seeds_contrast(eevee_scene, sandscape, elevation):
    """Journey's material on a sphere in EEVEE, lit by a scene sun it was not built with: its EEVEE
    output's diffuse is the seed's saturate(4 N'.L) / 2 pi within 0.05 (intensity 0..1). EEVEE
    lights the Cycles output's Toon BSDFs as diffuse: rendered through it, the same sphere leaves
    the seed's model."""
    from test_sand_looks import DIFFUSE_TOLERANCE, sphere_normals

    from core import sand as twin

    res, scale = 96, 2.2
    scene = eevee_scene
    scene.render.resolution_x = scene.render.resolution_y = res
    scene.view_settings.view_transform = "Standard"
    scene.world = None
    light = np.array([0.0, math.cos(math.radians(elevation)), math.sin(math.radians(elevation))])
    sun = bpy.data.objects.new("Their Sun", bpy.data.lights.new("Their Sun", "SUN"))
    sun.data.energy, sun.data.angle = 1.0, 0.0
    sun.data.use_shadow = False  # the diffuse, not the shadow map: its acne left dark dots in full sun
    sun.rotation_euler = (math.radians(90.0 - elevation), 0.0, math.pi)
    scene.collection.objects.link(sun)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=1.0)
    bpy.ops.object.shade_smooth()
    assert bpy.ops.sandscape.add_sand_material(look="JOURNEY", ripples=False) == {"FINISHED"}
    material = bpy.context.object.active_material
    look = sandscape.addon.sand.look_node(material)
    for name, value in (("Grain Strength", 0.0), ("Rim Strength", 0.0), ("Ocean Strength", 0.0),
                        ("Color", (1.0, 1.0, 1.0, 1.0))):
        look.inputs[name].default_value = value
    sandscape.addon.sand.glint_node(material).inputs["Threshold"].default_value = 1.0
    scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=scale)
    scene.frame_set(scene.frame_current)  # the drivers read the sun
    rendered = readback.render(scene)[..., 0].astype(np.float64) * 2 * np.pi
    normals, inside = sphere_normals(res, scale)
    inside &= normals[..., 2] > 0.4  # 3 px in from the silhouette EEVEE's 1.5 px filter blends
    seed = twin.journey_contrast(normals, light)
    error = np.abs(rendered - seed)[inside]
    tree = material.node_tree
    tree.nodes.remove(tree.nodes["Sandscape EEVEE Output"])
    tree.nodes["Sandscape Output"].target = "ALL"
    toons = readback.render(scene)[..., 0].astype(np.float64) * 2 * np.pi
    toon_error = np.abs(toons - seed)[inside]
    print(f"EEVEE journey sphere, sun {elevation} deg: against the seed's model max {error.max():.4f} "
          f"(mean {error.mean():.4f}); through the Toons max {toon_error.max():.4f} "
          f"(mean {toon_error.mean():.4f})")
    assert np.isfinite(rendered).all()
    assert error.max() <= DIFFUSE_TOLERANCE
    assert toon_error.max() > 2 * DIFFUSE_TOLERANCE


def test_clouds_cover_their_share_of_sky_in_eevee(eevee_scene):
    """The Cycles test's straight-up view in EEVEE, with the presets' 2 px volume cells: the share
    of sky under cloud is the Coverage within the issue's 0.05 (EEVEE's default 8 px cells blur the
    edges and gave 0.566 for 0.5)."""
    from test_clouds import COVERAGE_TOLERANCE, UP_SIZE, absorbing_only, cloud_layer, white_sky

    scene = eevee_scene
    scene.render.resolution_x = scene.render.resolution_y = 96
    scene.eevee.volumetric_tile_size = "2"
    scenes.camera("ORTHO", location=(0.0, 0.0, 0.0), rotation=(math.pi, 0.0, 0.0), ortho_scale=UP_SIZE)
    scene.camera.data.clip_end = 1e6
    white_sky()
    assert bpy.ops.sandscape.add_clouds(coverage=0.5, seed=0, map_scale=2000.0, reach=1.0,
                                        voxel=200.0) == {"FINISHED"}
    absorbing_only(cloud_layer(scene))
    seen = readback.render(scene)[..., 0]
    covered = float((seen < 0.5).mean())
    print(f"EEVEE clouds: {covered:.3f} of the sky under cloud (Coverage 0.5)")
    assert np.isfinite(seen).all()
    assert covered == pytest.approx(0.5, abs=COVERAGE_TOLERANCE)


@pytest.mark.parametrize("elevation", [6.0, pytest.param(30.0, marks=pytest.mark.sweep)])
def test_the_sky_lights_the_ground_in_eevee_as_in_cycles(eevee_scene, sandscape, elevation):
    """A grey plane lit by Add Atmosphere's sky alone (the lamp hidden), from above: EEVEE's mean
    colour against Cycles' exact integral of the sky, per channel. Through the world's EEVEE output
    (two hemispheres, addon/sky_eevee.py) and through the plain sky, which EEVEE's spherical
    harmonics let light the ground with the bright low sky near the sun. When written: within
    2.9 % at 6° and 1.7 % at 30° on 5.2; the plain sky +75 % and +38 % in red on 5.2."""
    bpy.ops.mesh.primitive_plane_add(size=100)
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Grey", "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5, 1.0)))
    air = eevee_scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(elevation), 0.3, 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    sandscape.addon.atmosphere.scene_sun(eevee_scene).hide_render = True
    scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=1.0)
    eevee_scene.cycles.samples, eevee_scene.cycles.max_bounces = 256, 1
    eevee_scene.render.resolution_x = eevee_scene.render.resolution_y = 16  # the wall's mean

    def mean(engine):
        eevee_scene.render.engine = engine
        return readback.render(eevee_scene)[..., :3].astype(np.float64).mean((0, 1))

    cycles, eevee = mean("CYCLES"), mean("BLENDER_EEVEE")
    tree = eevee_scene.world.node_tree
    tree.nodes.remove(tree.nodes["Sandscape EEVEE World Output"])
    tree.nodes["Sandscape World Output"].target = "ALL"
    plain = mean("BLENDER_EEVEE")
    print(f"sky at {elevation:g}°: Cycles {cycles.round(4)}, EEVEE {eevee.round(4)} "
          f"({(eevee / cycles - 1).round(3)}), plain sky {plain.round(4)} ({(plain / cycles - 1).round(3)})")
    assert np.abs(eevee / cycles - 1.0).max() <= SKY_TOLERANCE
    assert np.abs(plain / cycles - 1.0).max() > 2 * SKY_TOLERANCE


@pytest.mark.parametrize("above,below,clamp", [pytest.param(1.0, 0.0, 0.0, marks=pytest.mark.sweep),
                                               pytest.param(9.0, 1.0, 0.0, marks=pytest.mark.sweep),
                                               (2.5, 23.0, 0.0),
                                               pytest.param(2.5, 23.0, 10.0, marks=pytest.mark.sweep)])
def test_eevee_lights_from_two_hemispheres_as_its_twin_says(eevee_scene, sandscape, above, below, clamp):
    """A white plane facing up, then down, under a world of two uniform hemispheres (radiance
    `above` and `below`) with Clamp Surface Indirect `clamp`: EEVEE's light against the twin of
    its derung, clamped two bands (core.atmosphere.eevee_world_irradiance, the limit this
    Blender's). When written on 5.2: (1, 0) 0.930 and 0.066 of the exact up and 0, (9, 1) and
    (2.5, 23) exact within 1.9 %, clamped at 10 0.891 and 8.08 (twin 0.889 and 8.18); on 5.0
    (1, 0) 0.828 and 0.166, (9, 1) 8.25 and 1.66 (derung), clamped 1.656 and 8.25 (twin 1.667
    and 8.33)."""
    from core import atmosphere as air

    bpy.ops.mesh.primitive_plane_add(size=2)
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "White", "ShaderNodeBsdfDiffuse", Color=(1.0, 1.0, 1.0, 1.0)))
    world = bpy.data.worlds.new("Two Hemispheres")
    eevee_scene.world, world.sun_threshold = world, 0.0
    eevee_scene.eevee.clamp_surface_indirect = clamp
    tree = world.node_tree
    direction, axes = tree.nodes.new("ShaderNodeTexCoord"), tree.nodes.new("ShaderNodeSeparateXYZ")
    upper = tree.nodes.new("ShaderNodeMath")
    upper.operation, upper.inputs[1].default_value = "GREATER_THAN", 0.0
    level = tree.nodes.new("ShaderNodeMapRange")
    level.inputs["To Min"].default_value, level.inputs["To Max"].default_value = below, above
    tree.links.new(direction.outputs["Generated"], axes.inputs[0])
    tree.links.new(axes.outputs["Z"], upper.inputs[0])
    tree.links.new(upper.outputs[0], level.inputs["Value"])
    tree.links.new(level.outputs[0], tree.nodes["Background"].inputs["Strength"])
    tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    limit = sandscape.addon.compat.eevee_dering_limit()
    for facing, location, rotation in ((1.0, (0.0, 0.0, 5.0), (0.0, 0.0, 0.0)),
                                       (-1.0, (0.0, 0.0, -5.0), (math.pi, 0.0, 0.0))):
        camera = scenes.camera("ORTHO", location=location, rotation=rotation, ortho_scale=1.0)
        seen = readback.render(eevee_scene)[..., :3].astype(np.float64).mean()
        twin = air.eevee_world_irradiance([above * math.pi] * 3, [below * math.pi] * 3, facing, limit,
                                          clamp)[0] / math.pi
        print(f"hemispheres {above:g} / {below:g}, clamp {clamp:g}, facing {facing:+g}: EEVEE {seen:.3f}, "
              f"twin {twin:.3f}")
        assert seen == pytest.approx(twin, rel=0.02, abs=0.01)
        bpy.data.objects.remove(camera)


@pytest.mark.parametrize("elevation", [12.0, pytest.param(45.0, marks=pytest.mark.sweep)])
def test_the_lit_sand_lights_a_wall_in_eevee_as_in_cycles(eevee_scene, sandscape, elevation):
    """A grey wall standing on sand, its face edge-on to the sun so only the sky and the lit sand
    light it (as they light a walker's shaded side): EEVEE, which bounces no light, gets the sand's
    from its lighting world's lower hemisphere (addon/sky_eevee.py), Clamp Surface Indirect off.
    Against Cycles' one bounce, per channel; without the ground's light EEVEE's wall must be off
    by over twice the tolerance. When written on 5.2: 12° sun −10/−16/−18 % (R/G/B; two bands
    cannot give a wall more than the mean of the sky's light on level ground and the sand's, and
    a low sun's bright horizon gives it more), 45° +4/−2/−8 %; without the ground's light −74 %
    and −86 % in red. On 5.0: 12° −10/−16/−18 %, 45° −41/−2/−8 % (the red capped, below)."""
    from core import sand as core_sand

    bpy.ops.mesh.primitive_plane_add(size=400)
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Sand", "ShaderNodeBsdfDiffuse", Color=core_sand.SAND_COLOR))
    bpy.ops.mesh.primitive_plane_add(size=2, location=(0.0, 0.0, 1.5), rotation=(math.pi / 2, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Grey", "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5, 1.0)))
    air = eevee_scene.sandscape_atmosphere
    # The wall faces -Y; a sun due east (+X) grazes it and casts no shadow in front of it.
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(elevation), math.pi / 2, 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scenes.camera("ORTHO", location=(0.0, -5.0, 1.5), rotation=(math.pi / 2, 0.0, 0.0), ortho_scale=0.8)
    eevee_scene.cycles.samples, eevee_scene.cycles.max_bounces = 256, 1
    eevee_scene.render.resolution_x = eevee_scene.render.resolution_y = 16  # the wall's mean
    eevee_scene.eevee.clamp_surface_indirect = 0.0  # as the EEVEE presets set it
    eevee_scene.frame_set(eevee_scene.frame_current)  # the ground's light reads the sun

    def mean(engine):
        eevee_scene.render.engine = engine
        return readback.render(eevee_scene)[..., :3].astype(np.float64).mean((0, 1))

    cycles, eevee = mean("CYCLES"), mean("BLENDER_EEVEE")
    ground = sandscape.addon.sky_eevee_ground
    ground.set_colour(eevee_scene.world.node_tree.nodes[ground.NODE], (0.0, 0.0, 0.0))
    bare = mean("BLENDER_EEVEE")
    print(f"wall under a {elevation:g}° sun: Cycles {cycles.round(4)}, EEVEE {eevee.round(4)} "
          f"({(eevee / cycles - 1).round(3)}), without the ground's light {bare.round(4)} "
          f"({(bare / cycles - 1).round(3)})")
    assert np.isfinite(eevee).all()
    # 5.0 derings contrasts above 2/3 (5.2: 0.86): lit sand under a high sun may light a wall from
    # below with at most 4.8 times the sky's light on level ground (5.2: 13 times).
    derung = sandscape.addon.compat.eevee_dering_limit() < 0.8 and elevation > 30
    assert np.abs(eevee / cycles - 1.0).max() <= (WALL_TOLERANCE_DERUNG if derung else WALL_TOLERANCE)
    assert np.abs(bare / cycles - 1.0).max() > 0.5


def test_the_haze_lights_eevees_ground_as_cycles_haze_does(eevee_scene, sandscape):
    """A grey plane under Add Atmosphere's sky and haze (20 km, sun at 6 degrees), the lamp's own
    light on the plane off in both engines, seen by a camera looking at the horizon (the box
    rises hundreds of metres): the light the plane gets from the sky and the haze, EEVEE's mean
    colour per channel against Cycles'. Without the haze's light in EEVEE's world (as before it)
    EEVEE's red falls far short. When written on 5.2: +5.7, +3.4 and +0.1 % in red, green and
    blue with it; without, -34.8, -16.8 and -4.6 %."""
    bpy.ops.mesh.primitive_plane_add(size=100)
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Grey", "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5, 1.0)))
    air = eevee_scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(6.0), 0.3
    air.density, air.dust_density, air.use_wind, air.use_haze = 0.0, 0.0, False, True
    scenes.camera("PERSP", location=(0.0, 0.0, 1.5), rotation=(math.radians(90.0), 0.0, 0.0), lens=35.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    lamp = sandscape.addon.atmosphere.scene_sun(eevee_scene)
    lamp.visible_diffuse = False  # Cycles: the haze still scatters the lamp's light
    lamp.data.diffuse_factor = lamp.data.specular_factor = 0.0  # EEVEE's own switch
    eevee_scene.cycles.samples = 256

    def mean(engine):
        eevee_scene.render.engine = engine
        return readback.render(eevee_scene)[: SIZE[1] // 4, :, :3].astype(np.float64).mean((0, 1))

    cycles, eevee = mean("CYCLES"), mean("BLENDER_EEVEE")
    held = sandscape.addon.sky_eevee_haze.held(eevee_scene.world)
    sandscape.addon.sky_eevee_haze.follow(eevee_scene.world)
    without = mean("BLENDER_EEVEE")
    sandscape.addon.sky_eevee_haze.follow(eevee_scene.world, *held)
    print(f"sky and haze at 6°: Cycles {cycles.round(4)}, EEVEE {eevee.round(4)} "
          f"({(eevee / cycles - 1).round(3)}), without the haze's light {(without / cycles - 1).round(3)}")
    assert np.abs(eevee / cycles - 1.0).max() <= HAZE_TOLERANCE
    assert without[0] / cycles[0] - 1.0 < -2 * HAZE_TOLERANCE
