"""The god rays' sun keys are made again on save and render start only when what they depend on
changed: an unchanged long shot saves without stepping a frame, and every change that moves
the sun on screen (a camera key, the lens, the aim's target, a parent, the render size, the range,
a marker that switches cameras) still re-keys it, checked against stepping the frames."""

import math

import bpy
import numpy as np
import pytest
from mathutils import Euler

from devtools import scenes


@pytest.fixture
def shot(tmp_path):
    # 250 frames: what is keyed is checked here; what 1000 frames cost, in bench/save_cost.py.
    return scenes.long_keyed_shot(250), tmp_path / "shot.blend"


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


def saved_steps(path):
    with FrameCounter() as frames:
        bpy.ops.wm.save_as_mainfile(filepath=str(path))
    return frames.count


def keys_are_current(scene, sandscape):
    keys = sandscape.addon.sun_keys
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    keyed = np.array(keys.keyed_curve(scene.compositing_node_group))
    fresh = np.array(keys.stepped_curve(scene, sun, 0.25))  # stepping the frames, whatever moves
    return keyed.shape == fresh.shape and np.abs(keyed - fresh).max() <= 1e-6


def test_an_unchanged_shot_saves_without_stepping_a_frame(shot, sandscape):
    scene, path = shot
    assert saved_steps(path) == 0  # keyed by Add Post Effects, nothing changed since
    scene.frame_set(500)  # another current frame is no change to the keys
    assert saved_steps(path) == 0
    assert keys_are_current(scene, sandscape)


def move_camera_key(scene):
    fcurve = scene.camera.animation_data.action.layers[0].strips[0].channelbags[0].fcurves[0]
    fcurve.keyframe_points[-1].co.y += 2.0
    fcurve.keyframe_points[-1].handle_left.y += 2.0
    fcurve.keyframe_points[-1].handle_right.y += 2.0


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


def bind_marker(scene):
    kept = scene.camera
    other = scenes.camera("PERSP", location=(4.0, -6.0, 1.5), rotation=(math.radians(85), 0, 0.4), lens=50)
    scene.camera = kept  # scenes.camera made the new one the scene's
    scene.timeline_markers.new("Cut", frame=150).camera = other


CHANGES = {
    "camera key": move_camera_key,
    "lens": lambda scene: setattr(scene.camera.data, "lens", 70.0),
    "aim's target key": move_target_key,
    "parent": parent_camera,
    "render size": lambda scene: setattr(scene.render, "resolution_x", 640),
    "frame range": lambda scene: setattr(scene, "frame_end", 200),
    "marker switches camera": bind_marker,
    "static sun turned": lambda scene: setattr(
        sandscape_sun(scene).rotation_euler, "z", sandscape_sun(scene).rotation_euler.z + 0.3),
}


def sandscape_sun(scene):
    return next(o for o in scene.objects if o.type == "LIGHT" and o.data.type == "SUN")


@pytest.mark.parametrize("change", CHANGES)
def test_every_change_that_moves_the_sun_on_screen_re_keys_it(shot, sandscape, change):
    scene, path = shot
    CHANGES[change](scene)
    bpy.context.view_layer.update()
    assert not keys_are_current(scene, sandscape)  # the change moved the sun on screen
    assert saved_steps(path) > 0
    assert keys_are_current(scene, sandscape)
    assert saved_steps(path) == 0  # and once keyed, the next save is free again


def test_motion_the_digest_cannot_see_always_re_keys(shot, sandscape):
    scene, path = shot
    wrap = scene.camera.constraints.new("SHRINKWRAP")  # follows the ground's waving geometry
    wrap.target = next(o for o in scene.objects if o.type == "MESH")
    wrap.shrinkwrap_type, wrap.distance = "NEAREST_SURFACE", 1.5
    assert sandscape.addon.view_digest.digest(scene, sandscape_sun(scene), scene.camera, 0.25) is None
    assert saved_steps(path) > 0
    assert saved_steps(path) > 0
    assert keys_are_current(scene, sandscape)


def test_a_scene_not_shown_is_keyed_from_its_own_evaluation(tmp_path, sandscape):
    """Saving keys every scene's sun: one the context does not show is evaluated in its own view
    layer (its original objects are not moved by frame_set). Its camera pans 20 degrees across a
    sun on the horizon; a 35 mm lens on a 36 mm sensor puts the sun (35 / 36) tan 10 degrees off
    the centre at either end, on opposite sides."""
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
    # As a script would, without showing the scene (an operator override would make its
    # depsgraph the active one, which writes back to the objects).
    other.sandscape_post.use_blur = other.sandscape_post.use_denoise = False
    sandscape.addon.post.apply_post_effects(other, other.sandscape_post)
    for frame, yaw in ((1, 10.0), (31, -10.0)):  # keyed after the rays: the keys are stale now
        camera.rotation_euler.z = math.radians(yaw)
        camera.keyframe_insert("rotation_euler", index=2, frame=frame)
    assert bpy.context.scene == shown
    bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "two.blend"))
    keyed = sandscape.addon.sun_keys.keyed_curve(other.compositing_node_group)
    offset = 35.0 / 36.0 * math.tan(math.radians(10.0))
    u_first, u_last = keyed[0][1], keyed[-1][1]
    assert abs(u_first - 0.5) == pytest.approx(offset, abs=2e-3)
    assert abs(u_last - 0.5) == pytest.approx(offset, abs=2e-3)
    assert (u_first - 0.5) * (u_last - 0.5) < 0


def boom_camera(scene):
    """The shot's camera parented to an animated armature bone (a crane's boom)."""
    armature = bpy.data.objects.new("Crane", bpy.data.armatures.new("Crane"))
    scene.collection.objects.link(armature)
    bpy.context.view_layer.objects.active = armature
    bpy.ops.object.mode_set(mode="EDIT")
    boom = armature.data.edit_bones.new("Boom")
    boom.head, boom.tail = (0.0, -8.0, 0.0), (0.0, -8.0, 1.5)
    bpy.ops.object.mode_set(mode="OBJECT")
    pose = armature.pose.bones["Boom"]
    pose.rotation_mode = "XYZ"
    for frame, angle in ((1, -0.2), (scene.frame_end, 0.2)):
        pose.rotation_euler.z = angle
        pose.keyframe_insert("rotation_euler", index=2, frame=frame)
    camera = scene.camera
    camera.animation_data_clear()
    camera.constraints.clear()
    camera.parent, camera.parent_type, camera.parent_bone = armature, "BONE", "Boom"
    camera.matrix_parent_inverse.identity()
    camera.location, camera.rotation_euler = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    return armature


def tilt_the_boom(scene):
    armature = bpy.data.objects["Crane"]
    bpy.context.view_layer.objects.active = armature
    bpy.ops.object.mode_set(mode="EDIT")
    armature.data.edit_bones["Boom"].tail = (0.0, -6.5, 0.2)  # the rest pose leans forward
    bpy.ops.object.mode_set(mode="OBJECT")


def path_camera(scene):
    """The shot's camera following a curve, turned with it."""
    curve = bpy.data.curves.new("Track", "CURVE")
    spline = curve.splines.new("BEZIER")
    spline.bezier_points.add(1)
    for point, co in zip(spline.bezier_points, ((-3.0, -8.0, 1.5), (3.0, -8.0, 1.5)), strict=True):
        point.co, point.handle_left_type, point.handle_right_type = co, "AUTO", "AUTO"
    track = bpy.data.objects.new("Track", curve)
    scene.collection.objects.link(track)
    curve.use_path, curve.path_duration = True, scene.frame_end
    camera = scene.camera
    camera.animation_data_clear()
    camera.constraints.clear()
    camera.location = (0.0, 0.0, 0.0)
    camera.rotation_euler = (math.radians(90), 0.0, math.radians(-90))  # along the path, level
    follow = camera.constraints.new("FOLLOW_PATH")
    follow.target, follow.use_curve_follow, follow.forward_axis = track, True, "FORWARD_X"
    follow.use_fixed_location, follow.offset_factor = False, 0.0
    curve.keyframe_insert("eval_time", frame=1)
    curve.eval_time = scene.frame_end
    curve.keyframe_insert("eval_time", frame=scene.frame_end)
    return track


def close_the_track(scene):
    bpy.data.curves["Track"].splines[0].use_cyclic_u = True


@pytest.mark.parametrize("rig, change", [(boom_camera, tilt_the_boom), (path_camera, close_the_track)],
                         ids=["bone rest pose", "curve closed"])
def test_rigs_the_camera_rides_re_key_when_they_change(shot, sandscape, rig, change):
    """Found by an artist-eye check: a bone's rest pose and a path's settings (closed, tilt,
    resolution) were not in the digest, so the keys stayed stale after a save."""
    scene, path = shot
    rig(scene)
    saved_steps(path)  # keyed for the rig
    assert keys_are_current(scene, sandscape)
    change(scene)
    bpy.context.view_layer.update()
    assert not keys_are_current(scene, sandscape)  # the change moved the sun on screen
    assert saved_steps(path) > 0
    assert keys_are_current(scene, sandscape)


def test_keyed_cameras_and_suns_are_read_from_their_keys_without_stepping(sandscape):
    """A camera keyed in quaternions on a keyed, turned and scaled rig, and a keyed sun: the sun's
    place read from the keys matches stepping the frames within 1e-6, and nothing steps; a
    constraint on the camera sends it back to stepping."""
    keys = sandscape.addon.sun_keys
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
    with FrameCounter() as frames:
        from_keys = keys.curve_from_keys(scene, sun, 0.25)
    assert from_keys is not None and frames.count == 0
    stepped = np.array(keys.stepped_curve(scene, sun, 0.25))
    assert np.abs(np.array(from_keys) - stepped).max() <= 1e-5  # Blender steps in single precision
    assert np.ptp(stepped[:, 1]) > 0.05 and stepped[:, 3].max() > 0  # the sun moves on screen, in view
    camera.constraints.new("LIMIT_LOCATION")
    assert keys.curve_from_keys(scene, sun, 0.25) is None


@pytest.mark.parametrize("mover", ["path parent", "rigid body"])
def test_motion_without_the_cameras_own_keys_is_stepped(sandscape, mover):
    """Found by an artist-eye check: a camera parented to a curve whose path animation moves it,
    and one riding a rigid body, had been read from (absent) keys as standing still."""
    keys = sandscape.addon.sun_keys
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 20
    camera = scenes.camera("PERSP", location=(0.0, -10.0, 2.0), rotation=(math.radians(90), 0.0, 0.0))
    if mover == "path parent":
        curve = bpy.data.curves.new("Track", "CURVE")
        curve.splines.new("POLY").points.add(1)
        curve.splines[0].points[1].co = (10.0, 0.0, 0.0, 1.0)
        curve.use_path, curve.path_duration = True, 20
        curve.eval_time = 0.0
        curve.keyframe_insert("eval_time", frame=1)
        curve.eval_time = 20.0
        curve.keyframe_insert("eval_time", frame=20)
        rig = bpy.data.objects.new("Track", curve)
    else:
        bpy.ops.mesh.primitive_cube_add(location=(0.0, 0.0, 3.0))
        rig = bpy.context.active_object
        bpy.ops.rigidbody.object_add()
    scene.collection.objects.link(rig) if rig.name not in scene.objects else None
    camera.parent = rig
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    scene.collection.objects.link(sun)
    assert keys.curve_from_keys(scene, sun, 0.25) is None
