"""The ground's colour in EEVEE's light from below (addon/sky_eevee_ground.py), without
rendering: the world's lower hemisphere and the clouds' light at their base take the colour of
the Sandscape sand, else of the artist's ground below the camera, through drivers."""

import importlib
import math

import bpy
import pytest

from core import sand as core_sand
from devtools import scenes, session

ground = importlib.import_module(f"{session.MODULE}.addon.sky_eevee_ground")
OLIVE = (0.22, 0.2, 0.13, 1.0)
SMALL_CLOUDS = {"reach": 3000.0, "voxel": 150.0, "map_scale": 2000.0, "shape_scale": 600.0, "coverage": 0.6}


def _colour(tree):
    bpy.context.scene.frame_set(bpy.context.scene.frame_current)
    return tuple(socket.default_value for socket in tree.nodes[ground.NODE].inputs[:3])


def _material(name, colour):
    material = bpy.data.materials.new(name)
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = colour
    return material


def _their_ground(scale=1.0):
    """A rotated, scaled plane of two faces: sand-grey to the west, olive under the camera."""
    mesh = bpy.data.meshes.new("Their Ground")
    mesh.from_pydata([(-10, -10, 0), (0, -10, 0), (10, -10, 0), (-10, 10, 0), (0, 10, 0), (10, 10, 0)], [],
                     [(0, 1, 4, 3), (1, 2, 5, 4)])
    obj = bpy.data.objects.new("Their Ground", mesh)
    bpy.context.scene.collection.objects.link(obj)
    obj.data.materials.append(_material("Their Grey Rock", (0.5, 0.5, 0.5, 1.0)))
    obj.data.materials.append(_material("Their Olive Grass", OLIVE))
    mesh.polygons[1].material_index = 1
    obj.rotation_euler.z, obj.scale = math.radians(30.0), (scale * 3.0, scale * 3.0, 1.0)
    return obj


def _camera_over(obj, height=1.6):
    """A camera standing on the olive face (its middle, in world space), looking north."""
    bpy.context.view_layer.update()
    middle = obj.matrix_world @ obj.data.polygons[1].center
    scenes.camera("PERSP", location=(middle.x, middle.y, height), rotation=(math.radians(85.0), 0.0, 0.0))


def test_the_ground_takes_the_colour_of_their_ground_under_the_camera(sandscape):
    """No Sandscape sand: the world's ground colour follows the face below the camera (through our
    dust box, on a rotated, scaled and subdivided plane of two materials), and an edit to it
    follows; the sidebar says whose colour it took."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    obj = _their_ground()
    obj.modifiers.new("Subdivision", "SUBSURF").levels = 2  # faces the original mesh does not have
    _camera_over(obj)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    olive = obj.data.materials[1]
    assert sandscape.addon.sky_eevee.followed_ground(scene.world) == olive
    assert _colour(scene.world.node_tree) == pytest.approx(OLIVE[:3], abs=1e-6)
    olive.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.3, 0.25, 0.1, 1.0)
    assert _colour(scene.world.node_tree) == pytest.approx((0.3, 0.25, 0.1), abs=1e-6)
    scene.render.engine = "BLENDER_EEVEE"  # the Atmosphere section says whose colour (EEVEE's alone)
    assert sandscape.ui.panels.ground_light_text(scene).endswith("'Their Olive Grass'")


def test_the_sidebar_says_when_the_camera_moved_over_another_ground(sandscape):
    """The ground's colour is chosen when an operator runs, one for the whole shot: a camera moved
    (or animated) over another ground leaves it as it was, and the Atmosphere section says where
    the camera is and that Add Atmosphere takes the ground from the frame it runs on (helpers'
    findings of 2026-12-07); over the ground taken, it says nothing more."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    obj = _their_ground()
    _camera_over(obj)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    panels = sandscape.ui.panels
    assert panels.ground_light_text(scene).endswith("the colour of 'Their Olive Grass'")
    assert panels.ground_moved_text(scene) == ()
    olive_place = scene.camera.location.copy()
    scene.camera.location.xy = (obj.matrix_world @ obj.data.polygons[0].center).xy
    moved = panels.ground_moved_text(scene)
    assert moved and moved[0].startswith("The camera is over 'Their Grey Rock' here")
    assert panels.ground_light_text(scene).endswith("the colour of 'Their Olive Grass'")
    assert _colour(scene.world.node_tree) == pytest.approx(OLIVE[:3], abs=1e-6)  # as it was
    scene.camera.location = olive_place
    assert panels.ground_moved_text(scene) == ()
    scene.camera.location.xy = (obj.matrix_world @ obj.data.polygons[0].center).xy
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert panels.ground_light_text(scene).endswith("the colour of 'Their Grey Rock'")
    assert panels.ground_moved_text(scene) == ()


def test_a_camera_just_off_the_grounds_edge_takes_the_ground_low_in_its_frame(sandscape):
    """A camera standing just past the ground's edge, nearly level, the ground low in its frame (a
    helper's shot): nothing below it, nothing along its view, the ground through the middle of
    the frame's lower edge (perspective and orthographic)."""
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.mesh.primitive_plane_add(size=40.0)  # its near edge at y = -20
    olive = _material("Their Olive Grass", OLIVE)
    bpy.context.active_object.data.materials.append(olive)
    for kind, settings in (("PERSP", {}), ("ORTHO", {"ortho_scale": 8.0})):
        # 3 m up, 1.5 m off the edge, pitched 2 degrees down: its view meets the ground 86 m out,
        # past the plane's far edge; the frame's lower edge, 2.25 m lower (orthographic) or 11
        # degrees lower (perspective), meets the plane.
        camera = scenes.camera(kind, location=(0.0, -21.5, 3.0), rotation=(math.radians(88.0), 0.0, 0.0),
                               **settings)
        assert sandscape.addon.sky_eevee_ground.below_camera(bpy.context.scene) == olive, kind
        bpy.data.objects.remove(camera)


def test_a_camera_past_the_grounds_edge_takes_the_ground_it_looks_at(sandscape):
    """Nothing below the camera (it stands off the plane's edge, looking down onto it): the
    surface along its view."""
    bpy.ops.wm.read_homefile(use_empty=True)
    obj = _their_ground()
    bpy.context.view_layer.update()
    middle = obj.matrix_world @ obj.data.polygons[1].center
    scenes.camera("PERSP", location=(middle.x, middle.y - 60.0, 20.0),
                  rotation=(math.radians(70.0), 0.0, 0.0))
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert sandscape.addon.sky_eevee.followed_ground(bpy.context.scene.world) == obj.data.materials[1]


def test_a_textured_ground_leaves_the_sands_colour_and_says_so(sandscape):
    """A Base Color from a procedural texture can be neither driven nor averaged (an image's mean:
    test_sky_eevee_ground_image.py): the sand's colour stands in, and the report names the
    material."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    obj = _their_ground()
    olive = obj.data.materials[1]
    texture = olive.node_tree.nodes.new("ShaderNodeTexNoise")
    shader = olive.node_tree.nodes["Principled BSDF"]
    olive.node_tree.links.new(texture.outputs["Color"], shader.inputs["Base Color"])
    _camera_over(obj)
    settings = scene.sandscape_atmosphere
    done = sandscape.addon.atmosphere.apply(scene, settings)
    assert done["ground"] == olive and not done["ground_read"]
    assert "Their Olive Grass" in sandscape.operators.atmosphere.report_line(scene, settings, done)
    assert _colour(scene.world.node_tree) == pytest.approx(core_sand.SAND_COLOR[:3], abs=1e-6)


def test_the_clouds_light_from_below_follows_the_same_ground_and_then_the_sand(sandscape):
    """The clouds' ambient takes their ground's colour as the world does; sand added afterwards
    takes over both."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"  # the clouds' light from below is EEVEE's
    obj = _their_ground()
    _camera_over(obj)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert bpy.ops.sandscape.add_clouds(**SMALL_CLOUDS) == {"FINISHED"}
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    cloud_tree = layer.active_material.node_tree
    assert _colour(cloud_tree) == pytest.approx(OLIVE[:3], abs=1e-6)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    sand = sandscape.addon.sand.find_sand_material(obj)
    assert ground.followed(cloud_tree) == sand
    assert sandscape.addon.sky_eevee.followed_ground(scene.world) == sand
    assert _colour(cloud_tree) == pytest.approx(_colour(scene.world.node_tree), abs=1e-6)


def test_a_centimetre_scene_finds_the_same_ground(sandscape):
    """Unit scale 0.01: the ray and its step past our boxes work in scene units."""
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.context.scene.unit_settings.scale_length = 0.01
    obj = _their_ground(scale=100.0)
    _camera_over(obj, height=160.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert sandscape.addon.sky_eevee.followed_ground(bpy.context.scene.world) == obj.data.materials[1]


def test_the_clouds_bases_get_the_sun_the_layer_lets_through_on_the_whole(sandscape):
    """EEVEE's cloud-shadow map's mean (core.cloud_shadows.transmittance over the layer) is the
    lamp's share on the ground in the clouds' light from below (the world keeps the whole light);
    a sun too low to cast the map: all of it."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    obj = _their_ground()
    _camera_over(obj)
    air = scene.sandscape_atmosphere
    air.sun_elevation = math.radians(25.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert bpy.ops.sandscape.add_clouds(**SMALL_CLOUDS) == {"FINISHED"}
    clouds = sandscape.addon.clouds
    s = clouds.scene_settings(scene)
    done = clouds.plan(scene, s)
    to_sun = sandscape.addon.cloud_shadows.to_sun(scene)
    light = sandscape.core.cloud_shadows.transmittance(
        clouds.twin_density(scene, s, None, done), done["carried"], s["base"], s["thickness"], to_sun,
        sandscape.core.cloud_shadows.steps_for(s["thickness"], to_sun, s["step"]))
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    held = layer.active_material.node_tree.nodes[ground.SUN_LET_THROUGH].outputs[0]
    assert 0.2 < light.mean() < 0.95  # a share the test can see
    assert held.default_value == pytest.approx(light.mean(), abs=1e-6)
    assert ground.SUN_LET_THROUGH not in scene.world.node_tree.nodes
    air.sun_elevation = math.radians(0.3)  # under cloud_shadows.LOWEST_SUN: no map
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert held.default_value == 1.0


def test_each_scene_takes_its_own_ground(sandscape):
    """A second scene, not the one shown, run through temp_override: its world follows the
    ground below its own camera, and the first scene's world keeps its own."""
    bpy.ops.wm.read_homefile(use_empty=True)
    first = bpy.context.scene
    obj = _their_ground()
    _camera_over(obj)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    second = bpy.data.scenes.new("Second")
    mesh = bpy.data.meshes.new("Basalt")
    mesh.from_pydata([(40, 40, 0), (60, 40, 0), (60, 60, 0), (40, 60, 0)], [], [(0, 1, 2, 3)])
    basalt = bpy.data.objects.new("Basalt", mesh)
    basalt.data.materials.append(_material("Their Basalt", (0.05, 0.05, 0.06, 1.0)))
    second.collection.objects.link(basalt)
    camera = bpy.data.objects.new("Second Camera", bpy.data.cameras.new("Second Camera"))
    second.collection.objects.link(camera)
    camera.location = (50.0, 50.0, 2.0)
    second.camera = camera
    with bpy.context.temp_override(scene=second):
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    followed = sandscape.addon.sky_eevee.followed_ground
    assert followed(second.world) == basalt.data.materials[0]
    assert followed(first.world) == obj.data.materials[1]


@pytest.mark.parametrize("pane", ["ShaderNodeBsdfGlass", "Principled Transmission", "Hidden"])
def test_the_ground_is_found_through_glass_round_the_camera_and_past_a_sand_rock(sandscape, pane):
    """A glass box round the camera (or a box hidden from renders) is passed through; a small
    rock of Sandscape sand elsewhere does not take over from the ground below the camera."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    obj = _their_ground()
    _camera_over(obj)
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=scene.camera.location)
    box = bpy.context.active_object
    if pane == "ShaderNodeBsdfGlass":
        box.data.materials.append(scenes.single_node_material("Their Glass", pane))
    else:
        glass = _material("Their Glass", (1.0, 1.0, 1.0, 1.0))
        glass.node_tree.nodes["Principled BSDF"].inputs["Transmission Weight"].default_value = 1.0
        box.data.materials.append(glass)
        box.hide_render = pane == "Hidden"
        if box.hide_render:
            glass.node_tree.nodes["Principled BSDF"].inputs["Transmission Weight"].default_value = 0.0
    bpy.ops.mesh.primitive_ico_sphere_add(radius=0.5, location=(-500.0, 300.0, 0.0))
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}  # on the rock
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert sandscape.addon.sky_eevee.followed_ground(scene.world) == obj.data.materials[1]
