"""What the artist set stays as they set it: their sun, world, exposure, render engine, Cycles'
denoiser and view-layer passes change only when an option asks for it, and each operator names
every change outside Sandscape's own data in its one INFO line."""

import math

import bpy
import numpy as np
import pytest

from devtools import operators, readback, scenes


def info_line(reports):
    lines = [text for kinds, text in reports if "INFO" in kinds]
    assert len(lines) == 1, reports
    return lines[0]


def direction(obj):
    """(elevation, azimuth) in degrees of an object's world +Z: azimuth 0 along +Y, 90 along +X."""
    bpy.context.view_layer.update()
    z = np.array(obj.matrix_world.col[2][:3])
    z /= np.linalg.norm(z)
    return math.degrees(math.asin(z[2])), math.degrees(math.atan2(z[0], z[1])) % 360.0


def artists_sun():
    """A sun at 35 degrees, azimuth 120, strength 4, white, parented to a turned rig."""
    rig = bpy.data.objects.new("Light Rig", None)
    bpy.context.scene.collection.objects.link(rig)
    rig.rotation_euler.z = math.radians(30.0)  # turns the sun 30 degrees counter-clockwise
    sun = bpy.data.objects.new("Key Sun", bpy.data.lights.new("Key Sun", "SUN"))
    bpy.context.scene.collection.objects.link(sun)
    sun.parent = rig
    sun.rotation_euler = (math.radians(90.0 - 35.0), 0.0, math.radians(180.0 - 150.0))
    sun.data.energy, sun.data.color = 4.0, (1.0, 1.0, 1.0)
    return sun


def ground():
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    scenes.camera("PERSP", location=(0.0, -8.0, 1.5), rotation=(math.radians(85.0), 0.0, 0.0))
    return bpy.context.scene


def sky_sun_degrees(scene):
    skies = [n for n in scene.world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky"]
    assert skies
    return {(round(math.degrees(n.sun_elevation), 3), round(math.degrees(n.sun_rotation), 3)) for n in skies}


def test_your_sun_stays_where_you_put_it_and_the_sky_follows_it(sandscape):
    scene = ground()
    sun = artists_sun()
    scene.view_settings.exposure = 0.5
    assert direction(sun) == pytest.approx((35.0, 120.0), abs=1e-4)
    before = (sun.matrix_world.copy(), sun.data.energy, tuple(sun.data.color))

    result, reports = operators.run_execute("sandscape.add_atmosphere")
    line = info_line(reports)
    assert result == {"FINISHED"}
    assert (sun.matrix_world, sun.data.energy, tuple(sun.data.color)) == before
    assert scene.view_settings.exposure == 0.5
    assert sky_sun_degrees(scene) == {(35.0, 120.0)}  # the sky's sun is where theirs shines from
    settings = scene.sandscape_atmosphere
    assert math.degrees(settings.sun_elevation) == pytest.approx(25.0)  # still what Aim Your Sun would do
    assert "Your sun 'Key Sun' kept at 35.0° up, azimuth 120.0°; the sky follows it" in line
    assert "changed:" not in line
    assert "exposure kept at +0.50" in line  # what Set Exposure would do, said, not done

    # Asked for: their sun turned (in world space, through its parent) and lit as the sky's sun.
    settings.aim_sun, settings.sun_elevation, settings.sun_azimuth = True, math.radians(20), math.radians(200)
    result, reports = operators.run_execute("sandscape.add_atmosphere")
    line = info_line(reports)
    assert direction(sun) == pytest.approx((20.0, 200.0), abs=1e-3)
    assert sun.parent.name == "Light Rig"
    strength, colour = sandscape.core.sun.lamp(math.radians(20))
    assert sun.data.energy == pytest.approx(strength, rel=1e-5) and strength > 40.0
    assert tuple(sun.data.color) == pytest.approx(colour, abs=1e-5)
    assert "changed: your sun 'Key Sun' turned to 20.0° up, azimuth 200.0°" in line
    assert "its strength 4 →" in line and "its colour (1.00, 1.00, 1.00) →" in line
    assert "its angle 0.53° → 0.54°" in line
    assert sky_sun_degrees(scene) == {(20.0, 200.0)}


def test_the_sky_follows_a_sun_your_keys_move_and_aiming_leaves_it_alone():
    scene = ground()
    sun = artists_sun()
    for frame, elevation in ((1, 35.0), (100, 15.0)):
        sun.rotation_euler.x = math.radians(90.0 - elevation)
        sun.keyframe_insert("rotation_euler", frame=frame)
    scene.frame_set(1)
    scene.sandscape_atmosphere.replace_world = True
    operators.run_execute("sandscape.add_atmosphere")
    for frame in (1, 50, 100):  # drivers (simple expressions): no Python needed on a farm
        scene.frame_set(frame)
        elevation, azimuth = direction(sun)
        assert sky_sun_degrees(scene) == {(round(elevation, 3), round(azimuth, 3))}, frame
        eevee_sun = scene.world.node_tree.nodes["Sandscape EEVEE Ground Sun"]  # EEVEE's light from below
        assert eevee_sun.inputs[2].default_value == pytest.approx(math.sin(math.radians(elevation)), abs=1e-5)
    scene.frame_set(1)
    scene.sandscape_atmosphere.aim_sun = True
    before = sun.matrix_world.copy()
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    assert sun.matrix_world == before and "so Aim Your Sun leaves it" in info_line(reports)
    drivers = scene.world.node_tree.animation_data.drivers
    assert all(d.driver.is_simple_expression for d in drivers)
    assert len([d for d in drivers if "Sandscape EEVEE" not in d.data_path]) == 4  # the sky's sun


def test_the_sky_and_the_rays_follow_a_sun_you_swap_in(sandscape):
    """Found by an artist-eye check: the artist's sun deleted and another added after Add
    Atmosphere and Add Post Effects; the god rays moved to the new one, the sky's sun stayed."""
    scene = ground()
    first = artists_sun()
    operators.run_execute("sandscape.add_atmosphere")
    scene.sandscape_post.use_blur = scene.sandscape_post.use_denoise = False
    operators.run_execute("sandscape.add_post_effects")
    bpy.data.objects.remove(first)
    second = bpy.data.objects.new("New Sun", bpy.data.lights.new("New Sun", "SUN"))
    second.rotation_euler = (math.radians(90.0 - 8.0), 0.0, math.radians(180.0 + 12.0))
    scene.collection.objects.link(second)
    bpy.context.view_layer.update()  # the next scene update, as the viewport makes
    scene.frame_set(scene.frame_current)  # drivers evaluated on their new target
    elevation, azimuth = direction(second)
    assert sky_sun_degrees(scene) == {(round(elevation, 3), round(azimuth, 3))}
    assert sandscape.addon.sun_screen.driven_sun(scene.compositing_node_group) == second
    drivers = [d for d in scene.world.node_tree.animation_data.drivers
               if "Sandscape EEVEE Clamp" not in d.data_path]  # that one reads the scene's clamp
    assert len(drivers) == 12  # the sky's sun (4), EEVEE's ground light (3 axes, 3 channels), its disc (2)
    assert all(d.driver.is_valid and d.driver.variables[0].targets[0].id == second for d in drivers)


def test_set_exposure_measures_your_own_lamp():
    """An artist's sun at strength 4 under their own world: the exposure is for that lamp (their
    world's light is not known and left out), not for the sky model's sun, forty times brighter."""
    scene = ground()
    sun = artists_sun()
    sun.data.color = (1.0, 0.9, 0.8)
    scene.sandscape_atmosphere.set_exposure = True
    studio = bpy.data.worlds.new("Studio")
    studio.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.5
    scene.world = studio
    operators.run_execute("sandscape.add_atmosphere")
    luminance = 0.2126 * 1.0 + 0.7152 * 0.9 + 0.0722 * 0.8
    wanted = math.log2(math.pi / (4.0 * luminance * math.sin(math.radians(35.0))))
    assert scene.view_settings.exposure == pytest.approx(wanted, abs=0.006)
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    assert "exposure" not in info_line(reports)  # already so: no change to report


def test_exposure_changes_only_when_asked_and_the_report_says_so(sandscape):
    scene = ground()
    scene.view_settings.exposure = 0.5
    settings = scene.sandscape_atmosphere
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    assert scene.view_settings.exposure == 0.5
    settings.set_exposure = True
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    wanted = round(sandscape.core.sun.exposure(settings.sun_elevation), 2)
    assert scene.view_settings.exposure == pytest.approx(wanted)
    assert f"changed: exposure +0.50 → {wanted:+.2f}" in info_line(reports)


def test_your_world_is_kept_unless_asked_and_a_new_files_grey_world_is_replaced():
    scene = ground()
    factory = bpy.data.worlds.new("World")  # as a new file's: grey background, strength 1
    scene.world = factory
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    assert scene.world != factory and scene.world.get("sandscape_world")
    assert factory.use_fake_user and "world 'World' replaced" in info_line(reports)

    studio = bpy.data.worlds.new("Studio")
    studio.node_tree.nodes["Background"].inputs["Color"].default_value = (0.2, 0.3, 0.5, 1.0)
    scene.world = studio
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    line = info_line(reports)
    assert scene.world == studio and not studio.use_fake_user
    assert "your world 'Studio' kept" in line and "changed:" not in line
    assert scene.sandscape_atmosphere.replace_world is False
    scene.sandscape_atmosphere.replace_world = True
    _, reports = operators.run_execute("sandscape.add_atmosphere")
    assert scene.world.get("sandscape_world") and studio.use_fake_user
    assert "world 'Studio' replaced" in info_line(reports)


def links_from(tree, node):
    return [link.from_socket for link in tree.links if link.from_node == node]


def test_post_effects_work_in_eevee_without_switching_the_engine():
    scene = ground()
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene.render.engine = "BLENDER_EEVEE"
    result, reports = operators.run_execute("sandscape.add_post_effects")
    line = info_line(reports)
    assert result == {"FINISHED"} and scene.render.engine == "BLENDER_EEVEE"
    tree = scene.compositing_node_group
    layers = next(n for n in tree.nodes if n.bl_idname == "CompositorNodeRLayers")
    read = links_from(tree, layers)
    assert read and all(socket.enabled for socket in read), [s.name for s in read if not s.enabled]
    assert {s.name for s in read} >= {"Image", "Volume Direct", "Environment"}
    assert "not done: denoising all but the glints (Cycles only; left out in EEVEE)" in line
    layer = scene.view_layers[0]
    assert layer.eevee.use_pass_volume_direct and layer.use_pass_environment
    assert not layer.cycles.use_pass_volume_direct and len(layer.aovs) == 0


def test_workbench_is_refused_with_nothing_changed():
    scene = ground()
    bpy.ops.sandscape.add_atmosphere()
    scene.render.engine = "BLENDER_WORKBENCH"
    before = readback.data_snapshot()
    result, reports = operators.run_execute("sandscape.add_post_effects")
    assert result == {"CANCELLED"} and "Workbench" in reports[0][1] and "ERROR" in reports[0][0]
    assert readback.data_snapshot() == before


def test_cycles_denoiser_and_other_view_layers_are_left_as_the_artist_set_them():
    scene = ground()
    bpy.ops.sandscape.add_atmosphere()
    readback.cycles_scene(scene)
    scene.cycles.use_denoising = True
    main = scene.view_layers[0]
    main.name = "Main"
    mattes = scene.view_layers.new("Mattes")
    main.use_pass_environment = True  # theirs before Sandscape came
    scene.render.use_compositing = False
    result, reports = operators.run_execute("sandscape.add_post_effects")
    line = info_line(reports)
    assert result == {"FINISHED"} and scene.cycles.use_denoising
    assert "Cycles' own denoising kept" in line
    assert ("passes on in view layer 'Main': Volume Direct, Volume Indirect, Denoising Data, Glossy Direct, "
            "Glossy Indirect, Glossy Color, Emission, AOV 'sandscape_glint'") in line
    assert "compositing turned on" in line and scene.render.use_compositing
    untouched = ("use_pass_environment", "use_pass_glossy_direct", "use_pass_emit")
    assert not any(getattr(mattes, name) for name in untouched) and len(mattes.aovs) == 0
    assert not mattes.cycles.use_pass_volume_direct and not mattes.cycles.denoising_store_passes
    tree = scene.compositing_node_group
    layers = next(n for n in tree.nodes if n.bl_idname == "CompositorNodeRLayers")
    assert layers.layer == "Main" and "Noisy Image" in {s.name for s in links_from(tree, layers)}

    # Fewer effects: the passes Sandscape turned on and no longer reads go off; the artist's stay.
    settings = scene.sandscape_post
    settings.use_denoise = settings.use_blur = False
    _, reports = operators.run_execute("sandscape.add_post_effects")
    line = info_line(reports)
    assert all(name in line.split("off again: ")[1] for name in ("Volume Direct", "Volume Indirect", "AOV"))
    assert not main.cycles.use_pass_volume_direct and not main.cycles.denoising_store_passes
    assert len(main.aovs) == 0 and main.use_pass_environment
    actions = {a.name for a in bpy.data.actions}
    operators.run_execute("sandscape.add_post_effects")  # again: the keys' action is reused
    assert {a.name for a in bpy.data.actions} == actions
    settings.use_god_rays = settings.use_sun_glow = False  # nothing left: the tree goes
    # (the artist's pass stays)
    operators.run_execute("sandscape.add_post_effects")
    assert scene.compositing_node_group is None and main.use_pass_environment


def test_a_view_layer_that_does_not_render_is_not_the_one_read():
    scene = ground()
    bpy.ops.sandscape.add_atmosphere()
    readback.cycles_scene(scene)
    first = scene.view_layers[0]
    second = scene.view_layers.new("Beauty")
    first.use = False  # shown, but not rendered
    operators.run_execute("sandscape.add_post_effects")
    layers = next(n for n in scene.compositing_node_group.nodes if n.bl_idname == "CompositorNodeRLayers")
    assert layers.layer == "Beauty" and second.use_pass_environment and not first.use_pass_environment


def test_add_clouds_leaves_volume_sampling_and_names_the_steps_it_raises():
    scene = ground()
    bpy.ops.sandscape.add_atmosphere()
    scene.cycles.volume_biased, scene.cycles.volume_max_steps = False, 64
    result, reports = operators.run_execute("sandscape.add_clouds", evaluation="PROCEDURAL")
    line = next(text for kinds, text in reports if "INFO" in kinds)
    assert result == {"FINISHED"} and not scene.cycles.volume_biased
    assert scene.cycles.volume_max_steps > 64
    assert f"changed: volume max steps 64 → {scene.cycles.volume_max_steps}" in line


def test_add_sand_material_keeps_your_material_and_says_the_faces_moved():
    ground()
    plane = bpy.data.objects["Plane"]
    bpy.context.view_layer.objects.active = plane
    clay = bpy.data.materials.new("Clay")
    plane.data.materials.append(clay)
    result, reports = operators.run_execute("sandscape.add_sand_material")
    line = info_line(reports)
    assert result == {"FINISHED"} and plane.material_slots[0].material == clay
    assert "changed: every face of 'Plane' uses it (your 'Clay' keeps its slot)" in line
    _, reports = operators.run_execute("sandscape.add_sand_material")  # an update moves nothing
    assert "changed:" not in info_line(reports)


def test_the_sky_follows_a_scaled_sun_and_a_squashed_parent():
    """Found by an artist-eye check: a lamp scaled to 2 broke the driver (asin of more than 1) and
    a parent scaled (1, 1, 0.5) tilted the sky's sun by 8 degrees."""
    scene = ground()
    sun = artists_sun()
    sun.scale = (2.0, 2.0, 2.0)
    sun.parent.scale = (1.0, 1.0, 0.5)
    scene.sandscape_atmosphere.replace_world = True
    operators.run_execute("sandscape.add_atmosphere")
    scene.frame_set(1)
    elevation, azimuth = direction(sun)
    assert sky_sun_degrees(scene) == {(round(elevation, 3), round(azimuth, 3))}
    assert all(d.is_valid for d in scene.world.node_tree.animation_data.drivers)
