"""The atmosphere operator: transmittance through the dust rendered against exp(-beta d), the sky's
sun where the lamp points, re-runs, a user's world kept, bad input refused."""

import math

import bpy
import mathutils
import numpy as np
import pytest

from core import atmosphere as air
from devtools import readback, scenes

DENSITY = 0.5  # 1/m at 550 nm
THICKNESS = 1.0  # m


def camera_only_emitter(size=2.0):
    """A white plane at z = 0 that glows for camera rays only, so nothing scatters light back."""
    plane = readback.uv_plane(size, "Emitter")
    material = bpy.data.materials.new("Camera Glow")
    tree = material.node_tree
    tree.nodes.clear()
    path = tree.nodes.new("ShaderNodeLightPath")
    emission = tree.nodes.new("ShaderNodeEmission")
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(path.outputs["Is Camera Ray"], emission.inputs["Strength"])
    tree.links.new(emission.outputs[0], output.inputs["Surface"])
    plane.data.materials.append(material)
    return plane


def test_rendered_transmittance_matches_the_twin(sandscape):
    camera_only_emitter()
    beta = air.rayleigh_coefficients(DENSITY)
    sandscape.addon.atmosphere.ensure_volume(bpy.context.scene, beta, (-2.0, -2.0, 0.5),
                                             (2.0, 2.0, 0.5 + THICKNESS))
    scene = readback.cycles_scene(resolution=(32, 32), samples=64)
    scenes.camera("ORTHO", location=(0.0, 0.0, 5.0), ortho_scale=1.0)
    pixels = readback.render(scene)[..., :3].reshape(-1, 3)
    expected = air.slab_transmittance(beta, THICKNESS)
    measured = pixels.mean(axis=0)
    assert np.isfinite(pixels).all()
    assert np.abs(measured / expected - 1.0).max() < 0.005, (measured, expected)  # the README's 0.5 %
    assert measured[2] < measured[1] < measured[0]  # blue is scattered out most


def mirror_ball_sun_direction():
    """Direction of the brightest sky seen in a mirror sphere from straight above."""
    material = bpy.data.materials.new("Mirror")
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Metallic"].default_value, bsdf.inputs["Roughness"].default_value = 1.0, 0.0
    scenes.analytic_sphere(material, 1.0, (0.0, 0.0, 50.0))
    scene = readback.cycles_scene(resolution=(240, 240), samples=1)
    scenes.sharp_pixels(scene)
    scene.cycles.max_bounces = 1
    scenes.camera("ORTHO", location=(0.0, 0.0, 55.0), ortho_scale=2.0)
    brightness = readback.render(scene)[..., :3].sum(-1)
    y, x = (np.indices(brightness.shape) + 0.5) / 240 * 2 - 1
    inside = x * x + y * y < 0.98
    normal = np.stack([x, y, np.sqrt(np.clip(1 - x * x - y * y, 0, 1))], -1)
    reflected = 2 * normal[..., 2:3] * normal - np.array([0.0, 0.0, 1.0])
    top = inside & (brightness >= np.percentile(brightness[inside], 99.9))
    direction = (reflected[top] * brightness[top, None]).sum(0)
    return direction / np.linalg.norm(direction)


def test_sky_sun_matches_the_lamp():
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth, settings.density = math.radians(35), math.radians(60), 0.0
    bpy.ops.sandscape.add_atmosphere()
    sky = next(n for n in bpy.context.scene.world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky")
    assert sky.sky_type == "MULTIPLE_SCATTERING"
    sky.sun_disc, sky.sun_size = True, math.radians(6)  # a visible disc to find, for this test only
    sun = next(o for o in bpy.context.scene.objects if o.type == "LIGHT")
    sun.hide_render = True
    lamp = np.array(sun.matrix_world.col[2][:3])  # a sun shines along its -Z
    seen = mirror_ball_sun_direction()
    assert math.degrees(math.acos(min(1.0, float(seen @ lamp)))) < 1.0
    # Azimuth as on a compass, from north (+Y) toward east (+X): the settings' own description.
    up, around = math.radians(35), math.radians(60)
    compass = (math.cos(up) * math.sin(around), math.cos(up) * math.cos(around), math.sin(up))
    assert lamp == pytest.approx(compass, abs=1e-6)


def test_the_camera_sees_the_sun_disc_and_the_lighting_does_not():
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth, settings.density = math.radians(20), math.radians(60), 0.0
    bpy.ops.sandscape.add_atmosphere()
    scene = readback.cycles_scene(resolution=(33, 33), samples=16)
    towards_sun = mathutils.Vector(air.sun_direction(math.radians(20), math.radians(60)))
    # 200 mm: 0.27 degrees a pixel, so the 0.545-degree disc covers about two pixels at the centre.
    scenes.camera("PERSP", location=(0.0, 0.0, 0.0), lens=200.0,
                  rotation=towards_sun.to_track_quat("-Z", "Y").to_euler())
    brightness = readback.render(scene)[..., :3].sum(-1)
    row, column = np.unravel_index(np.argmax(brightness), brightness.shape)
    assert abs(row - 16) <= 1 and abs(column - 16) <= 1, (row, column)
    assert brightness.max() > 100 * np.median(brightness)

    # Seen from above, a grey ground lit by the sky renders the same, within the noise, with the
    # disc branch cut out. Were the disc lighting it as well, the ground would be far brighter.
    bpy.data.objects.remove(scene.camera)
    readback.uv_plane(50.0, "Ground")
    scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=4.0)
    with_disc = readback.render(scene)
    tree = scene.world.node_tree
    lighting = next(n for n in tree.nodes if n.type == "BACKGROUND"
                    and not n.inputs["Color"].links[0].from_node.sun_disc)
    tree.links.new(lighting.outputs[0], next(n for n in tree.nodes if n.type == "OUTPUT_WORLD").inputs[0])
    without = readback.render(scene)
    ratio = with_disc[..., :3].mean() / without[..., :3].mean()
    assert abs(ratio - 1.0) < 0.03, ratio  # 1089 pixels at 16 spp: the noise in the mean is under 1 %


def test_rerun_updates_and_nothing_scattering_removes_the_volume():
    bpy.ops.mesh.primitive_plane_add(size=10)
    settings = bpy.context.scene.sandscape_atmosphere
    bpy.ops.sandscape.add_atmosphere()
    settings.sun_elevation = 0.5
    bpy.ops.sandscape.add_atmosphere()
    kinds = [o.get("sandscape_object") for o in bpy.data.objects if o.get("sandscape_object")]
    assert sorted(kinds) == ["dust_volume", "sun"] and len(bpy.data.worlds) == 1
    box = next(o for o in bpy.data.objects if o.get("sandscape_object") == "dust_volume")
    assert tuple(box.scale) == pytest.approx((14.0, 14.0, 4.0))  # the plane plus a 2 m margin
    assert not box.visible_shadow  # the sun lamp carries the sky's extinction: not dimmed twice
    settings.density = 0.0
    bpy.ops.sandscape.add_atmosphere()
    assert box.active_material.node_tree.nodes.get("Sandscape Dust Grains")  # the haze alone keeps the box
    settings.use_haze = False
    bpy.ops.sandscape.add_atmosphere()
    assert not [o for o in bpy.data.objects if o.get("sandscape_object") == "dust_volume"]
    assert not [m for m in bpy.data.meshes if m.name.startswith("Sandscape Dust")]


def test_a_users_world_and_sun_are_kept():
    theirs = bpy.data.worlds.new("Their World")
    theirs.node_tree.nodes["Background"].inputs["Strength"].default_value = 2.0  # theirs, not a new file's
    bpy.context.scene.world = theirs
    lamp = bpy.data.objects.new("Their Sun", bpy.data.lights.new("Their Sun", "SUN"))
    bpy.context.scene.collection.objects.link(lamp)
    bpy.ops.sandscape.add_atmosphere()
    assert bpy.context.scene.world == theirs and not theirs.use_fake_user
    assert not [o for o in bpy.data.objects if o.get("sandscape_object") == "sun"]  # theirs was used
    assert lamp.matrix_world.col[2][2] == pytest.approx(1.0)  # still shining straight down
    settings = bpy.context.scene.sandscape_atmosphere
    settings.replace_world = True
    bpy.ops.sandscape.add_atmosphere()
    assert bpy.context.scene.world != theirs and theirs.use_fake_user
    assert bpy.context.scene.world["replaced_world"] == "Their World"
    skies = [n for n in bpy.context.scene.world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky"]
    assert skies and all(n.sun_elevation == pytest.approx(math.pi / 2) for n in skies)  # the sky follows


@pytest.mark.parametrize("wavelengths, density", [((680, 0, 440), 0.02), ((-680, 550, 440), 0.02),
                                                  ((680, 550, 440), -1.0), ((680, 550, 440), math.nan)])
def test_bad_input_is_refused_and_changes_nothing(wavelengths, density):
    settings = bpy.context.scene.sandscape_atmosphere
    settings.wavelengths, settings.density = wavelengths, density
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match="avelengths|ensity"):
        bpy.ops.sandscape.add_atmosphere()
    assert readback.data_snapshot() == before


@pytest.mark.parametrize("visibility", [0.0, -5.0, math.nan, math.inf])
def test_a_bad_visibility_is_refused_and_changes_nothing(visibility):
    settings = bpy.context.scene.sandscape_atmosphere
    settings.visibility = visibility
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match="isibility"):
        bpy.ops.sandscape.add_atmosphere()
    assert readback.data_snapshot() == before


@pytest.mark.parametrize("density, wind", [(1e6, False), (1e6, True), (1e-9, True)])
def test_extreme_densities_render_finite(density, wind):
    bpy.ops.mesh.primitive_plane_add(size=4)
    settings = bpy.context.scene.sandscape_atmosphere
    settings.density, settings.use_wind, settings.dust_density = density, wind, density
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene = readback.cycles_scene(resolution=(24, 16), samples=4)
    scene.cycles.volume_biased = True
    scenes.camera("PERSP", location=(0.0, -5.0, 1.0), rotation=(math.radians(80), 0.0, 0.0))
    pixels = readback.render(scene)
    assert np.isfinite(pixels).all() and pixels.min() >= 0.0


def dust_material():
    box = next(o for o in bpy.data.objects if o.get("sandscape_object") == "dust_volume")
    return box.active_material


def test_wind_dust_is_frame_driven_and_absent_when_off():
    bpy.ops.mesh.primitive_plane_add(size=4)
    settings = bpy.context.scene.sandscape_atmosphere
    settings.use_wind, settings.dust_density = True, 0.0
    bpy.ops.sandscape.add_atmosphere()
    tree = dust_material().node_tree
    field = next(n for n in tree.nodes if n.label == "Dust Field")
    driver = tree.animation_data.drivers[0].driver
    assert driver.expression == "frame" and driver.is_simple_expression
    bpy.context.scene.frame_set(42)
    assert field.inputs["Frame"].default_value == pytest.approx(42.0, abs=1e-6)
    assert not bpy.context.scene.cycles.volume_biased  # the artist's: the quality presets set it
    haze = tree.nodes["Sandscape Dust Grains"]  # no dust: the haze alone, everywhere alike
    assert not haze.inputs["Density"].is_linked and haze.inputs["Density"].default_value == pytest.approx(
        3.912 / 20000.0, rel=1e-3)
    settings.use_wind, settings.dust_density = False, 0.01
    bpy.ops.sandscape.add_atmosphere()
    tree = dust_material().node_tree
    assert not [n for n in tree.nodes if n.label == "Dust Field"]  # homogeneous: no field at all
    assert tree.animation_data is None or not tree.animation_data.drivers
    phases = [n.phase for n in tree.nodes if n.bl_idname == "ShaderNodeVolumeScatter"]
    assert phases == ["HENYEY_GREENSTEIN"]  # dust and haze in one node: two closures at most
    grains = tree.nodes["Sandscape Dust Grains"].inputs["Density"]
    assert grains.default_value == pytest.approx(0.01 + 3.912 / 20000.0, rel=1e-3)


def lone_cube_dust_box(unit_scale):
    """A 1 m cube, a camera 8.5 m off looking at it, windless air: the dust box, in metres."""
    scene = bpy.context.scene
    scene.unit_settings.scale_length = unit_scale
    per_metre = 1.0 / unit_scale
    bpy.ops.mesh.primitive_cube_add(size=per_metre, location=(0.0, 0.0, 0.5 * per_metre))
    camera = scenes.camera("PERSP", location=(8.5 * per_metre, -1.0 * per_metre, 1.6 * per_metre),
                           rotation=(math.radians(85.0), 0.0, math.radians(83.0)))
    camera.data.clip_end = 1e6
    settings = scene.sandscape_atmosphere
    settings.use_wind, settings.dust_density = False, 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    box = next(o for o in scene.objects if o.get("sandscape_object") == "dust_volume")
    centre, size = np.array(box.location) / per_metre, np.array(box.scale) / per_metre
    return centre - size / 2, centre + size / 2, camera, per_metre


@pytest.mark.parametrize("unit_scale", [1.0, 0.01])
def test_the_dust_box_spans_the_shot_not_the_cube(unit_scale):
    """Out to where the haze lets 1 % through, in every corner of the frame; not the cube's 1 m box
    (once a glowing square round it). Reference: the Rayleigh law, Koschmieder's haze and the
    camera's frame."""
    low, high, camera, per_metre = lone_cube_dust_box(unit_scale)
    settings = bpy.context.scene.sandscape_atmosphere
    extinction = np.asarray(air.rayleigh_coefficients(settings.density, tuple(settings.wavelengths)))
    extinction += air.haze_extinction(settings.visibility / per_metre)  # per metre, as the Rayleigh law
    reach = math.log(100.0) / float(np.min(extinction))  # metres, the clearest channel
    assert 100.0 < reach < 1000.0
    matrix = np.array(camera.matrix_world)
    corners = np.array([tuple(c) for c in camera.data.view_frame(scene=bpy.context.scene)], np.float64)
    directions = corners / np.linalg.norm(corners, axis=1, keepdims=True) @ matrix[:3, :3].T
    origin = matrix[:3, 3] / per_metre
    far = origin + directions * reach
    margin = settings.margin / per_metre  # stored in scene units
    inside = far[far[:, 2] > 0.0]  # the ground ends the rays below it
    assert (inside >= low - 1e-3).all() and (inside <= high + 1e-3).all()
    assert (origin >= low).all() and (origin <= high).all()
    # Reach in every horizontal direction from the camera, and no more; no higher than the views.
    assert low[:2] == pytest.approx(origin[:2] - reach - margin, abs=1e-3)
    assert high[:2] == pytest.approx(origin[:2] + reach + margin, abs=1e-3)
    assert high[2] == pytest.approx(max(far[:, 2].max(), origin[2]) + margin, abs=1e-3)
    assert low[2] == pytest.approx(-margin, abs=1e-3)  # from under the ground, which ends the rays


def test_a_turned_camera_and_another_frame_size_see_no_edge_of_the_dust_box():
    """The camera turned round and the frame made wide after Add Atmosphere: every ray of the new
    frame still runs out to the haze's 1 % reach (or to the ground, or up out of the layer
    through its top, a plane and not an edge) before it leaves the box."""
    low, high, camera, per_metre = lone_cube_dust_box(1.0)
    scene = bpy.context.scene
    settings = scene.sandscape_atmosphere
    reach = math.log(100.0) / float(np.min(air.rayleigh_coefficients(settings.density,
                                                                      tuple(settings.wavelengths))))
    camera.rotation_euler.z += math.radians(180.0)
    scene.render.resolution_x, scene.render.resolution_y = 2400, 400
    bpy.context.view_layer.update()
    matrix = np.array(camera.matrix_world)
    corners = np.array([tuple(c) for c in camera.data.view_frame(scene=scene)], np.float64)
    directions = corners / np.linalg.norm(corners, axis=1, keepdims=True) @ matrix[:3, :3].T
    origin = matrix[:3, 3]
    for direction in directions:
        # Where the ray leaves through a side: every side at least reach away along the ray.
        with np.errstate(divide="ignore"):
            exits = np.where(direction[:2] > 0, (high[:2] - origin[:2]) / direction[:2],
                             (low[:2] - origin[:2]) / direction[:2])
        assert exits.min() >= reach - 1e-3


def test_a_camera_that_clips_short_of_the_haze_is_warned():
    """Blender's new camera ends its rays at 100 m, where Add Atmosphere's haze reaches kilometres:
    past that the frame shows the bare sky. The report says so and what to raise Clip End to."""
    from devtools import operators

    bpy.ops.mesh.primitive_plane_add(size=200.0)
    scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.radians(88.0), 0.0, 0.0))
    bpy.context.scene.sandscape_atmosphere.use_haze = True
    bpy.context.scene.sandscape_atmosphere.visibility = 10000.0
    bpy.context.scene.camera.data.clip_end = 100.0
    result, reports = operators.run_execute("sandscape.add_atmosphere")
    warnings = [text for kinds, text in reports if kinds == {"WARNING"}]
    assert result == {"FINISHED"} and len(warnings) == 1, reports
    assert "clips at 100 m, short of the haze" in warnings[0] and "Raise its Clip End" in warnings[0]

    def metres(text):
        number, unit = text.split()[:2]
        return float(number) * (1000.0 if unit.startswith("km") else 1.0)

    reach = metres(warnings[0].split("which reaches ")[1])
    assert metres(warnings[0].rsplit("to at least ", 1)[1]) >= reach > 100.0  # rounded up, never down
    bpy.context.scene.camera.data.clip_end = 50000.0
    result, reports = operators.run_execute("sandscape.add_atmosphere")
    assert result == {"FINISHED"} and not [text for kinds, text in reports if kinds == {"WARNING"}], reports


def test_lengths_that_differ_read_differently_and_a_limit_is_rounded_up(sandscape):
    """A helper's report read "clips at 1 km, short of the haze, which reaches 1 km": lengths that
    differ get the digits to show it, and the Clip End to raise to is rounded up, past the haze."""
    units = sandscape.addon.units
    scene = bpy.context.scene
    first, second = units.distinct_length_texts(scene, [1000.0, 1004.0])
    assert first != second and first == "1 km"
    assert units.distinct_length_texts(scene, [1000.0, 1000.0]) == ["1 km", "1 km"]
    assert units.round_up(1004.0) == pytest.approx(1100.0) and units.round_up(4600.0) == pytest.approx(4600.0)
    assert units.round_up(0.0123) == pytest.approx(0.013) and units.round_up(math.inf) == math.inf
