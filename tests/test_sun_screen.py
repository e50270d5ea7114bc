"""The god rays' sun place is driven, not keyed: whatever moves the camera or the sun (a camera
key, the lens, an aim's target, a stretched parent, the render size, a shrinkwrap, a scaled rig,
sensor fits, shift and pixel aspect) moves it on the very
next frame, with no save and no handler, checked against Blender's own projection of the
evaluated camera (sun_screen.stepped_curve, calc_matrix_camera). Saving and rendering step no
frame at all."""

import math

import bpy
import numpy as np
import pytest
from mathutils import Euler

from core import post
from devtools import readback, scenes

TOLERANCE = 2e-5  # of a screen width: single-precision matrices and socket values


@pytest.fixture
def shot():
    return scenes.long_keyed_shot(60)


class FrameCounter:
    def __init__(self):
        self.count = 0

    def __call__(self, *_):
        self.count += 1

    def __enter__(self):
        bpy.app.handlers.frame_change_pre.append(self)
        return self

    def __exit__(self, *_):
        bpy.app.handlers.frame_change_pre.remove(self)


def scene_sun(scene):
    return next(o for o in scene.objects if o.type == "LIGHT" and o.data.type == "SUN")


def driven_matches_blender(scene, sandscape, sun=None):
    """The driven (u, v, intensity) on every frame against Blender's projection; the largest
    difference, and the reference curve."""
    screen = sandscape.addon.sun_screen
    sun = sun or scene_sun(scene)
    driven = np.array(screen.driven_curve(scene.compositing_node_group, scene))
    reference = np.array(screen.stepped_curve(scene, sun, 0.25))
    assert driven.shape == reference.shape
    return np.abs(driven - reference).max(), reference


def test_saving_and_rendering_step_no_frame(shot, sandscape, tmp_path):
    shot.render.engine = "CYCLES"  # the tree is rebuilt for it on the next update, not at render
    shot.render.resolution_x, shot.render.resolution_y = 32, 18
    shot.cycles.samples = 1
    with FrameCounter() as frames:
        bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "shot.blend"))
    assert frames.count == 0
    assert shot.compositing_node_group["built_for"] == "CYCLES"
    with FrameCounter() as frames:
        bpy.ops.render.render()
    handlers = sandscape.addon.post_handlers
    handlers.unregister()
    try:
        with FrameCounter() as blenders_own:  # a render sets its frame itself
            bpy.ops.render.render()
    finally:
        handlers.register()
    assert frames.count == blenders_own.count <= 2


def move_camera_key(scene):
    fcurve = scene.camera.animation_data.action.layers[0].strips[0].channelbags[0].fcurves[0]
    for point in (fcurve.keyframe_points[-1],):
        point.co.y += 2.0
        point.handle_left.y += 2.0
        point.handle_right.y += 2.0


def move_target_key(scene):
    target = bpy.data.objects["Target"]
    fcurve = target.animation_data.action.layers[0].strips[0].channelbags[0].fcurves[0]
    for point in fcurve.keyframe_points:
        point.co.y += 1.0
        point.handle_left.y += 1.0
        point.handle_right.y += 1.0


def parent_camera(scene):
    rig = bpy.data.objects.new("Rig", None)
    scene.collection.objects.link(rig)
    scene.camera.parent = rig
    rig.rotation_euler.z = math.radians(15)
    rig.scale = (1.0, 2.0, 0.5)  # a stretched rig: each axis over its own length


def shrinkwrap(scene):
    wrap = scene.camera.constraints.new("SHRINKWRAP")  # follows the ground's waving geometry
    wrap.target = bpy.data.objects["Plane"]
    wrap.shrinkwrap_type, wrap.distance = "NEAREST_SURFACE", 2.0
    scene.camera.constraints.move(1, 0)  # lifted first, then aimed: the sun at infinity moves


def lens_of_every_kind(scene):
    data = scene.camera.data
    data.lens, data.sensor_fit, data.shift_x, data.shift_y = 25.0, "VERTICAL", 0.1, -0.05
    scene.render.pixel_aspect_x = 1.5


CHANGES = {
    "camera key": move_camera_key,
    "lens": lambda scene: setattr(scene.camera.data, "lens", 20.0),
    "fit, shift, pixel aspect": lens_of_every_kind,
    "aim's target key": move_target_key,
    "stretched parent": parent_camera,
    "render size": lambda scene: setattr(scene.render, "resolution_x", 640),
    "shrinkwrap": shrinkwrap,
    "sun turned": lambda scene: setattr(scene_sun(scene).rotation_euler, "z",
                                        scene_sun(scene).rotation_euler.z + 0.3),
}


@pytest.mark.parametrize("change", CHANGES)
def test_every_change_moves_the_driven_sun_with_it(shot, sandscape, change):
    before, _ = driven_matches_blender(shot, sandscape)
    assert before <= TOLERANCE
    old = np.array(sandscape.addon.sun_screen.stepped_curve(shot, scene_sun(shot), 0.25))
    CHANGES[change](shot)
    error, reference = driven_matches_blender(shot, sandscape)
    assert np.abs(reference - old).max() > 0.01  # the change moved the sun on screen
    assert error <= TOLERANCE
    assert reference[:, 3].max() > 0  # and it is seen


def test_the_sun_behind_the_camera_and_orthographic_cameras_give_no_rays(shot, sandscape):
    scene_sun(shot).rotation_euler.z += math.pi  # the sun behind the camera now
    error, reference = driven_matches_blender(shot, sandscape)
    assert error <= TOLERANCE and reference[:, 3].max() == 0.0
    scene_sun(shot).rotation_euler.z -= math.pi
    shot.camera.data.type = "ORTHO"
    error, reference = driven_matches_blender(shot, sandscape)
    assert error <= TOLERANCE and reference[:, 3].max() == 0.0


def test_the_sun_place_group_matches_its_twin(sandscape):
    """Directions all round the camera (behind it, beside it, on its plane), scales and shifts
    of any lens, perspective or not, and three fades."""
    group = sandscape.node_groups.helper.ensure_group(sandscape.node_groups.sun_place)
    width, height = 40, 30
    rng = np.random.default_rng(3)
    direction = np.zeros((height, width, 4))
    direction[..., :3] = rng.normal(size=(height, width, 3))
    direction[..., 2] -= 1.5  # most in front
    direction[0, :8, 2] = 0.0  # on the camera's plane
    direction[1, :8, 2] = -1e-12
    lens = np.ones((height, width, 4))
    lens[..., :2] = rng.uniform(0.3, 2.5, (height, width, 2))
    shift = np.zeros((height, width, 4))
    shift[..., :2] = rng.uniform(-0.3, 0.3, (height, width, 2))
    perspective = np.ones((height, width, 4))
    perspective[-3:, :, :3] = 0.0  # orthographic
    for fade in (0.25, 0.6, 0.0):
        values = {"Direction": direction, "Scale": lens, "Shift": shift, "Perspective": perspective,
                  "Fade": fade}
        place = readback.composite_group(group, values, "Sun", (width, height))
        intensity = readback.composite_group(group, values, "Intensity", (width, height))[..., 0]
        expected = np.array([[post.sun_on_screen(direction[r, c, :3], lens[r, c, :2], shift[r, c, :2],
                                                 perspective[r, c, 0], fade)
                              for c in range(width)] for r in range(height)])
        assert np.isfinite(place).all() and np.isfinite(intensity).all()
        assert np.abs(intensity - expected[..., 2]).max() < 1e-5, fade
        uv_error = np.abs(place[..., :2] - expected[..., :2]) / np.maximum(1.0, np.abs(expected[..., :2]))
        assert uv_error.max() < 1e-5, fade
        assert 0.05 < expected[..., 2].mean() < 0.95  # in, near and far out of the frame


def test_a_scene_not_shown_drives_from_its_own_evaluation(sandscape):
    """Its camera pans 20 degrees across a sun on the horizon; a 35 mm lens on a 36 mm sensor
    puts the sun (35 / 36) tan 10 degrees off the centre at either end, on opposite sides."""
    shown = bpy.context.scene
    other = bpy.data.scenes.new("Other Shot")
    other.frame_start, other.frame_end = 1, 31
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 1.0), rotation=(math.pi / 2, 0.0, 0.0), lens=35)
    other.collection.objects.link(camera)
    shown.collection.objects.unlink(camera)
    other.camera = camera
    sun = bpy.data.objects.new("Their Sun", bpy.data.lights.new("Their Sun", "SUN"))
    sun.rotation_euler = (math.radians(-89.5), 0.0, 0.0)  # shining along -Y, 0.5 degrees up
    other.collection.objects.link(sun)
    other.sandscape_post.use_blur = other.sandscape_post.use_denoise = False
    sandscape.addon.post.apply_post_effects(other, other.sandscape_post)
    for frame, yaw in ((1, 10.0), (31, -10.0)):  # keyed after the rays
        camera.rotation_euler.z = math.radians(yaw)
        camera.keyframe_insert("rotation_euler", index=2, frame=frame)
    assert bpy.context.scene == shown
    screen = sandscape.addon.sun_screen
    offset = 35.0 / 36.0 * math.tan(math.radians(10.0))
    places = []
    for frame in (1, 31):
        other.frame_set(frame)
        places.append(screen.driven_place(other.compositing_node_group, other)[0] - 0.5)
    assert abs(places[0]) == pytest.approx(offset, abs=2e-4)
    assert abs(places[1]) == pytest.approx(offset, abs=2e-4)
    assert places[0] * places[1] < 0


def test_a_quaternion_camera_on_a_keyed_scaled_rig_and_a_keyed_sun(sandscape):
    """And its curve from the keys (the optimizer's, no frame stepped) agrees with both."""
    screen = sandscape.addon.sun_screen
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 60
    rig = bpy.data.objects.new("Rig", None)
    scene.collection.objects.link(rig)
    rig.scale = (1.0, 2.0, 1.0)
    camera = scenes.camera("PERSP", location=(0.0, -10.0, 2.0), rotation=(math.radians(90), 0.0, 0.0))
    camera.parent = rig
    camera.matrix_parent_inverse = rig.matrix_world.inverted()
    camera.rotation_mode = "QUATERNION"
    for frame, yaw, x in ((1, 0.0, 0.0), (30, 25.0, 3.0), (60, -10.0, -2.0)):
        rig.rotation_euler.z = math.radians(yaw)
        rig.location.x = x
        rig.keyframe_insert("rotation_euler", frame=frame)
        rig.keyframe_insert("location", frame=frame)
        camera.rotation_quaternion = Euler((math.radians(90 + frame / 10), 0.0, math.radians(frame / 5))
                                           ).to_quaternion()
        camera.keyframe_insert("rotation_quaternion", frame=frame)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    scene.collection.objects.link(sun)
    for frame, tilt in ((1, 85.0), (60, 83.0)):  # 5 and 7 degrees up, ahead of the camera
        sun.rotation_euler = (math.radians(tilt), 0.0, math.radians(180.0))
        sun.keyframe_insert("rotation_euler", frame=frame)
    scene.sandscape_post.use_blur = scene.sandscape_post.use_denoise = False
    assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
    error, reference = driven_matches_blender(scene, sandscape, sun)
    assert error <= TOLERANCE
    assert np.ptp(reference[:, 1]) > 0.05 and reference[:, 3].max() > 0  # it moves on screen, in view
    with FrameCounter() as frames:
        from_keys = screen.curve_from_keys(scene, sun, 0.25)
    assert frames.count == 0 and np.abs(np.array(from_keys) - reference).max() <= 1e-5


def test_another_sun_and_a_lost_camera_are_followed(shot, sandscape):
    """The artist's new sun takes over the drivers on the next update; a camera deleted and
    brought back re-arms them."""
    ours = scene_sun(shot)
    theirs = bpy.data.objects.new("Their Sun", bpy.data.lights.new("Their Sun", "SUN"))
    theirs.rotation_euler = (math.radians(82.0), 0.0, math.radians(200.0))
    bpy.data.objects.remove(ours)
    shot.collection.objects.link(theirs)
    bpy.context.view_layer.update()
    screen = sandscape.addon.sun_screen
    assert screen.driven_sun(shot.compositing_node_group) == theirs
    error, _ = driven_matches_blender(shot, sandscape, theirs)
    assert error <= TOLERANCE
    camera = shot.camera
    shot.camera = None
    bpy.context.view_layer.update()
    shot.frame_set(5)
    shot.camera = camera
    bpy.context.view_layer.update()
    error, reference = driven_matches_blender(shot, sandscape, theirs)
    assert error <= TOLERANCE and reference[:, 3].max() > 0
