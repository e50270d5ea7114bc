"""Sandscape on scenes it did not make: a second scene, linked and overridden terrains, a flattened
terrain, values typed out of range, Film > Transparent, a camera moved after the fact, a walk or a
terrain changed after painting, a centimetre scene."""

import math

import bpy
import numpy as np
import pytest

from devtools import operators, readback, scenes, session


def ours(collection, kind, scene=None):
    found = [b for b in collection if b.get("sandscape_object") == kind]
    return [b for b in found if scene is None or b.name in scene.objects]


def walk_scene(size=6.0, frames=(1, 31), name="Sand"):
    terrain = scenes.height_field(size, 12, name=name)
    span = frames[1] - frames[0]
    walker = scenes.keyframed_walker(lambda f: (-1.5 + 3.0 * (f - frames[0]) / span, 0.0, 0.0),
                                     range(frames[0], frames[1] + 1))
    return scenes.footprint_settings(terrain, walker, frames, resolution=256)


# ---------------------------------------------------------------- two scenes

def test_a_second_scene_gets_its_own_sun_sky_dust_and_compositor():
    first = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=4)
    scenes.camera("PERSP", location=(0, -6, 1), rotation=(math.radians(85), 0, 0))
    bpy.ops.sandscape.add_atmosphere()
    bpy.ops.sandscape.add_post_effects()
    box = ours(bpy.data.objects, "dust_volume", first)[0]
    kept = (tuple(box.location), tuple(box.scale), first.world, first.compositing_node_group)

    second = bpy.data.scenes.new("Second")
    plane = bpy.data.objects.new("Far Plane", bpy.data.meshes.new("Far Plane"))
    plane.data.from_pydata([(40, 40, 0), (60, 40, 0), (60, 60, 0), (40, 60, 0)], [], [(0, 1, 2, 3)])
    second.collection.objects.link(plane)
    camera = bpy.data.objects.new("Second Camera", bpy.data.cameras.new("Second Camera"))
    second.collection.objects.link(camera)
    camera.location = (50.0, 50.0, 5.0)  # looking straight down on its plane
    second.camera = camera
    second.sandscape_atmosphere.sun_elevation = math.radians(40)
    with bpy.context.temp_override(scene=second):
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
    assert (tuple(box.location), tuple(box.scale), first.world, first.compositing_node_group) == kept
    second_box = ours(bpy.data.objects, "dust_volume", second)
    assert len(second_box) == 1 and second_box[0] != box
    # Each box around its own camera's view.
    assert 40 < second_box[0].location.x < 60 and abs(box.location.x) < 10
    assert second.world != first.world and second.compositing_node_group != first.compositing_node_group
    sun_first, sun_second = (ours(bpy.data.objects, "sun", s)[0] for s in (first, second))
    assert sun_first != sun_second
    assert sun_first.matrix_world.col[2][2] == pytest.approx(math.sin(math.radians(25)), abs=1e-5)
    sky = next(n for n in first.world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky")
    assert sky.sun_elevation == pytest.approx(math.radians(25), abs=1e-6)  # the first sky untouched


def test_a_second_scene_gets_its_own_walker():
    first = bpy.context.scene
    bpy.ops.sandscape.add_walker()
    second = bpy.data.scenes.new("Second")
    with bpy.context.temp_override(scene=second):
        assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    assert len(ours(bpy.data.objects, "walker", first)) == len(ours(bpy.data.objects, "walker", second)) == 1
    assert first.sandscape_footprints.walker != second.sandscape_footprints.walker


# ---------------------------------------------------------------- data Sandscape must not change

@pytest.fixture
def library_terrain(tmp_path):
    """A terrain in a library .blend, linked into this file (scene and walk set up around it)."""
    terrain = scenes.height_field(6.0, 12, name="Library Dune")
    path = tmp_path / "library.blend"
    bpy.data.libraries.write(str(path), {terrain, terrain.data})
    bpy.data.objects.remove(terrain)
    with bpy.data.libraries.load(str(path), link=True) as (_, linked):
        linked.objects = ["Library Dune"]
    terrain = linked.objects[0]
    bpy.context.scene.collection.objects.link(terrain)
    walker = scenes.keyframed_walker(lambda f: (-1.5 + 0.1 * (f - 1), 0.0, 0.0), range(1, 32))
    scenes.footprint_settings(terrain, walker, (1, 31), resolution=64)
    return terrain


@pytest.mark.parametrize("how", ["linked", "library override"])
def test_linked_or_overridden_terrain_is_refused_with_nothing_half_built(library_terrain, how):
    terrain = library_terrain
    if how == "library override":
        terrain = terrain.override_create(remap_local_usages=True)
        bpy.context.scene.sandscape_footprints.terrain = terrain
    before = readback.data_snapshot()
    for operator in ("paint_footprints", "emit_footprints"):
        with pytest.raises(RuntimeError, match="linked|override"):
            getattr(bpy.ops.sandscape, operator)()
        assert readback.data_snapshot() == before
    assert not [m for m in terrain.modifiers if m.type == "NODES"]
    bpy.context.view_layer.objects.active = terrain
    with pytest.raises(RuntimeError, match="linked|override"):
        bpy.ops.sandscape.add_sand_material()
    assert readback.data_snapshot() == before
    result, reports = operators.run_execute("sandscape.paint_footprints")
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"}


def test_a_terrain_flattened_to_scale_0_is_refused():
    settings = walk_scene()
    settings.terrain.scale = (1.0, 0.0, 1.0)
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match="scale of 0"):
        bpy.ops.sandscape.paint_footprints()
    assert readback.data_snapshot() == before


# ---------------------------------------------------------------- values typed out of range

@pytest.fixture
def lit_scene():
    bpy.ops.mesh.primitive_plane_add(size=20)
    scenes.camera("PERSP", location=(0, -6, 1.0), rotation=(math.radians(85), 0, 0), lens=35)
    air = bpy.context.scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(10), 0.0, 0.0
    bpy.ops.sandscape.add_atmosphere()
    return bpy.context.scene


@pytest.mark.parametrize("group, operator, values, message", [
    ("sandscape_post", "add_post_effects", {"fade": math.nan}, "Edge Fade"),
    ("sandscape_post", "add_post_effects", {"ray_weight": math.inf}, "Weight"),
    ("sandscape_post", "add_post_effects", {"ray_exposure": -1.0}, "Exposure"),
    ("sandscape_post", "add_post_effects", {"blur_threshold": math.nan}, "Threshold"),
    ("sandscape_atmosphere", "add_atmosphere", {"sun_elevation": 3.4e38}, "Sun Elevation"),
    ("sandscape_atmosphere", "add_atmosphere", {"sun_azimuth": 3.4e38}, "Sun Azimuth"),
    ("sandscape_atmosphere", "add_atmosphere", {"coverage": math.nan}, "Coverage"),
    ("sandscape_atmosphere", "add_atmosphere", {"wind": (math.inf, 0.0, 0.0)}, "Wind"),
    ("sandscape_atmosphere", "add_atmosphere", {"margin": -1.0}, "Margin"),
])
def test_nan_inf_and_out_of_range_values_are_refused(lit_scene, group, operator, values, message):
    for key, value in values.items():
        setattr(getattr(lit_scene, group), key, value)
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match=message):
        getattr(bpy.ops.sandscape, operator)()
    assert readback.data_snapshot() == before
    result, reports = operators.run_execute(f"sandscape.{operator}")
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"} and message in reports[0][1]


# ---------------------------------------------------------------- compositing

def test_post_effects_keep_the_renders_alpha(lit_scene):
    bpy.ops.mesh.primitive_cube_add(size=1, location=(0, 2, 0.5))
    lit_scene.objects["Plane"].hide_render = True  # sky behind a lone cube: transparent around it
    readback.cycles_scene(lit_scene, resolution=(48, 27), samples=2)
    lit_scene.render.film_transparent = True
    bpy.ops.sandscape.add_post_effects()
    composited = readback.render(lit_scene)
    lit_scene.render.use_compositing = False
    plain = readback.render(lit_scene)
    assert 0.01 < (plain[..., 3] > 0.5).mean() < 0.99  # the frame has both
    assert np.abs(composited[..., 3] - plain[..., 3]).max() <= 1e-6
    assert np.isfinite(composited).all()


def test_god_rays_follow_a_camera_turned_after_add_post_effects(lit_scene, sandscape):
    """No save, no handler: the render's own drivers place the rays where the sun now is."""
    screen = sandscape.addon.sun_screen
    lit_scene.sandscape_post.use_blur = lit_scene.sandscape_post.use_denoise = False
    lit_scene.sandscape_post.use_sun_glow = False  # the rays alone (the glow takes the sun's glare too)
    lit_scene.frame_start = lit_scene.frame_end = 1
    bpy.ops.sandscape.add_post_effects()
    before = screen.driven_place(lit_scene.compositing_node_group, lit_scene)
    lit_scene.camera.rotation_euler[2] += math.radians(20)  # the sun moves across the frame
    bpy.context.view_layer.update()
    sun = sandscape.addon.atmosphere.scene_sun(lit_scene)
    _, u, v, _ = screen.stepped_curve(lit_scene, sun, 0.25)[0]
    assert abs(before[0] - u) > 0.1
    readback.cycles_scene(lit_scene, resolution=(64, 36), samples=1)
    with_rays = readback.render(lit_scene)
    lit_scene.render.use_compositing = False
    rays = (with_rays - readback.render(lit_scene))[..., :3].sum(-1)
    # The glow is brightest at the sun's new place on screen (column, row from the bottom).
    row, col = np.unravel_index(np.argmax(rays), rays.shape)
    assert abs((col + 0.5) / 64 - u) < 0.1 and abs((row + 0.5) / 36 - v) < 0.1


def test_a_saved_file_places_the_sun_where_it_is(lit_scene, sandscape, tmp_path):
    """A longer lens and another frame size after Add Post Effects, the file saved and opened
    again with Sandscape off: its drivers give Blender's own projection."""
    screen = sandscape.addon.sun_screen
    lit_scene.sandscape_post.use_blur = False
    lit_scene.frame_start, lit_scene.frame_end = 1, 5
    bpy.ops.sandscape.add_post_effects()
    lit_scene.camera.data.lens = 80  # a longer lens moves the sun away from the centre
    lit_scene.camera.rotation_euler[0] = math.radians(95)  # looking 5 degrees up: the sun at the top
    lit_scene.render.resolution_x, lit_scene.render.resolution_y = 300, 100
    path = tmp_path / "drivers.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    sun = sandscape.addon.atmosphere.scene_sun(lit_scene)
    expected = np.array(screen.stepped_curve(lit_scene, sun, 0.25))
    with session.extension_off():
        bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=False)
        scene = bpy.context.scene
        driven = np.array(screen.driven_curve(scene.compositing_node_group, scene))
    assert np.abs(driven - expected).max() <= 2e-5
    assert 0 < expected[:, 3].max() and np.ptp(expected[:, 1]) == 0.0


# ---------------------------------------------------------------- painting after changes

def painted_points():
    points = ours(bpy.data.objects, "footprints")[0]
    return np.array([points.matrix_world @ v.co for v in points.data.vertices])


def test_paint_follows_a_walk_that_changed(sandscape):
    settings = walk_scene()
    bpy.ops.sandscape.paint_footprints()
    before = painted_points()
    walker = settings.walker
    for frame in range(1, 32):  # the same walk, half a metre to the side
        bpy.context.scene.frame_set(frame)
        walker.location.y = 0.5
        walker.keyframe_insert("location", index=1, frame=frame)
    bpy.ops.sandscape.paint_footprints()
    after = painted_points()
    assert len(after) == len(before)
    assert after[:, 1] - before[:, 1] == pytest.approx(0.5, abs=1e-4)


def test_paint_follows_a_terrain_that_moved(sandscape):
    settings = walk_scene()
    bpy.ops.sandscape.paint_footprints()
    before = painted_points()
    settings.terrain.location.z += 0.3
    settings.terrain.rotation_euler.z = math.radians(40)  # the walk now crosses it elsewhere
    bpy.context.view_layer.update()
    bpy.ops.sandscape.paint_footprints()
    after = painted_points()
    assert after[:, :2] == pytest.approx(before[:, :2], abs=1e-4)  # under the same feet
    assert after[:, 2] - before[:, 2] == pytest.approx(0.3, abs=1e-4)  # on the raised ground


def test_edited_prints_survive_a_repaint_when_nothing_changed(sandscape):
    walk_scene()
    bpy.ops.sandscape.paint_footprints()
    points = ours(bpy.data.objects, "footprints")[0]
    points.data.vertices[0].co.x += 0.2
    bpy.ops.sandscape.paint_footprints()
    assert ours(bpy.data.objects, "footprints")[0].data.vertices[0].co.x == pytest.approx(
        painted_points()[0, 0] - points.matrix_world.translation.x, abs=1e-6)


# ---------------------------------------------------------------- a centimetre scene

def test_a_centimetre_scene_gets_metre_defaults_and_reports_its_units(sandscape):
    scene = bpy.context.scene
    scene.unit_settings.scale_length = 0.01  # one unit is a centimetre
    settings = scene.sandscape_footprints
    assert settings.stride == pytest.approx(70.0, rel=1e-6)  # 0.7 m, not 0.7 cm
    assert settings.foot_length == pytest.approx(27.0, rel=1e-6)
    terrain = scenes.height_field(600.0, 24, name="Sand")  # 6 m
    walker = scenes.keyframed_walker(lambda f: (-150.0 + 10.0 * (f - 1), 0.0, 0.0), range(1, 32))
    scenes.footprint_settings(terrain, walker, (1, 31), resolution=256)
    reports = []
    result, reports = operators.run_execute("sandscape.paint_footprints")
    assert result == {"FINISHED"}
    co = painted_points()
    assert np.diff(co[:, 0]) == pytest.approx(70.0, abs=1e-3)
    texel_units = bpy.data.images[0]["texel"] if bpy.data.images[0].get("texel") else next(
        i for i in bpy.data.images if i.get("texel"))["texel"]
    shown = reports[-1][1]
    expected = sandscape.addon.units.length_text(scene, texel_units)
    assert expected in shown and ("mm" in expected or "cm" in expected), shown
    bpy.ops.sandscape.add_walker()
    box = ours(bpy.data.objects, "walker")[0]
    # A 1.7 m figure in centimetres, its hood's peak 10 cm over its head.
    assert max(v.co.z for v in box.data.vertices) == pytest.approx(180.0, rel=1e-6)


@pytest.mark.parametrize("look", ["PHYSICAL", "JOURNEY"])
def test_a_centimetre_scene_gets_grains_of_two_millimetres(look):
    bpy.context.scene.unit_settings.scale_length = 0.01
    bpy.ops.mesh.primitive_plane_add(size=600.0)
    assert bpy.ops.sandscape.add_sand_material(look=look) == {"FINISHED"}
    material = bpy.context.active_object.active_material
    look_node = next(n for n in material.node_tree.nodes if n.name == "Sandscape Look")
    assert look_node.inputs["Grain Size"].default_value == pytest.approx(0.2, rel=1e-6)  # 2 mm in cm
    look_node.inputs["Grain Size"].default_value = 0.5  # the artist's own
    assert bpy.ops.sandscape.add_sand_material(look=look) == {"FINISHED"}
    assert look_node.inputs["Grain Size"].default_value == pytest.approx(0.5)


def test_prints_in_a_scene_not_shown_land_on_its_evaluated_ground(sandscape):
    """A script paints a scene other than the one the context shows: its terrain is evaluated in
    its own view layer (raised 1 m by a modifier there), not looked up in the shown scene's."""
    shown = bpy.context.scene
    terrain = scenes.height_field(6.0, 12, name="Their Sand")
    terrain.location.x = 20.0  # placed away from the origin: its world matrix is the scene's to evaluate
    raise_up = terrain.modifiers.new("Raise", "DISPLACE")
    raise_up.strength, raise_up.mid_level = 1.0, 0.0  # no texture: 1 m along the normal
    walker = scenes.keyframed_walker(lambda f: (18.5 + 0.1 * (f - 1), 0.0, 2.0), range(1, 32))
    other = bpy.data.scenes.new("Other Shot")
    for obj in (terrain, walker):
        other.collection.objects.link(obj)
        shown.collection.objects.unlink(obj)
    other.frame_start, other.frame_end = 1, 31
    settings = other.sandscape_footprints
    settings.terrain, settings.walker, settings.resolution = terrain, walker, 256
    assert bpy.context.scene == shown
    sandscape.addon.footprints.paint(other, settings)
    points = next(o for o in other.objects if o.get("sandscape_object") == "footprints")
    frame = points.parent  # the print frame, on the terrain: points are in its space
    origin = sandscape.addon.footprints.frame_world(other, frame)
    placed = [origin @ v.co for v in points.data.vertices]
    assert len(placed) >= 3 and [p.z for p in placed] == pytest.approx([1.0] * len(placed), abs=1e-4)
    assert all(18.0 < p.x < 22.0 for p in placed)
