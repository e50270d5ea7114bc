"""The sun's place on screen, keyed on every frame of the god rays' tree: a render farm without
Sandscape renders the keys. Made again only when the digest of what they depend on
(view_digest.py) changed since they were made: stepping every frame costs as much as playing the
shot.
"""

import bpy
import numpy as np

from ..core import post
from . import evaluation, keyed_motion, shot, view_digest
from . import ownership as own

SUN_KEY, RAYS = "Sandscape Sun Key", "Sandscape God Rays"  # node names in the post tree
DIGEST_KEY = "sandscape_sun_digest"  # on the tree: the view digest its sun keys were made for


def rays_node(tree):
    return own.node(tree, RAYS)


def sun_key_node(tree):
    return own.node(tree, SUN_KEY)


def view_projection(scene, camera, depsgraph=None):
    """World to clip space of the camera as the scene renders it; camera as evaluated in depsgraph
    (default: the scene's own)."""
    depsgraph = depsgraph or evaluation.scene_depsgraph(scene)
    camera = camera.evaluated_get(depsgraph)
    render = scene.render
    width = max(render.resolution_x * render.resolution_percentage // 100, 1)
    height = max(render.resolution_y * render.resolution_percentage // 100, 1)
    projection = np.array(camera.calc_matrix_camera(
        depsgraph, x=width, y=height, scale_x=render.pixel_aspect_x, scale_y=render.pixel_aspect_y))
    return projection @ np.array(camera.matrix_world.inverted())


def _place(projection, direction, fade, frame):
    (u, v), in_front = post.screen_position(projection, direction)
    intensity = post.sun_intensity((u, v), in_front, fade)
    if not in_front or not np.isfinite((u, v)).all():
        u, v = 0.5, 0.5  # any finite place: the intensity is 0
    return (frame, float(u), float(v), float(intensity))


def curve_from_keys(scene, sun, fade):
    """The sun curve read from the keyframes, without stepping a frame; None where more than
    plain keys move the camera or the sun (keyed_motion.py), or markers switch cameras."""
    camera = scene.camera
    if camera is None or any(marker.camera is not None for marker in scene.timeline_markers):
        return None
    if not keyed_motion.still_camera_data(camera):
        return None
    frames = range(scene.frame_start, scene.frame_end + 1)
    cameras = keyed_motion.world_matrices(scene, camera, frames)
    suns = keyed_motion.world_matrices(scene, sun, frames) if cameras is not None else None
    if suns is None:
        return None
    projection = view_projection(scene, camera) @ np.array(camera.matrix_world)  # the lens alone
    return [_place(projection @ np.linalg.inv(view), lamp[:3, 2], fade, frame)
            for frame, view, lamp in zip(frames, cameras, suns, strict=True)]


def sun_curve(scene, sun, fade):
    """[(frame, u, v, intensity)] of the sun seen by the scene camera on every frame of the range:
    from the keys where they are all that move the camera and the sun, else by stepping the
    frames."""
    from_keys = curve_from_keys(scene, sun, fade)
    return from_keys if from_keys is not None else stepped_curve(scene, sun, fade)


def stepped_curve(scene, sun, fade):
    """The sun curve by stepping every frame: whatever moves the camera and the sun."""
    curve = []
    for frame in evaluation.stepped_frames(scene, range(scene.frame_start, scene.frame_end + 1)):
        depsgraph = evaluation.scene_depsgraph(scene)  # a scene not shown: its own evaluation
        direction = np.array(sun.evaluated_get(depsgraph).matrix_world.col[2][:3])
        curve.append(_place(view_projection(scene, scene.camera, depsgraph), direction, fade, frame))
    return curve


def key_sun(tree, curve):
    """Keyframes, not a driver: a render farm needs no scripts."""
    sun_node, rays = sun_key_node(tree), rays_node(tree)
    old = tree.animation_data.action if tree.animation_data is not None else None
    if tree.animation_data is not None:
        tree.animation_data_clear()
    if old is not None and old.users == 0:  # else every run leaves one more action behind
        name = old.name
        bpy.data.actions.remove(old)
    else:
        name = None
    sockets = (sun_node.inputs["X"], sun_node.inputs["Y"], rays.inputs["Intensity"])
    for frame, *values in curve:
        for socket, value in zip(sockets, values, strict=True):
            socket.default_value = value
            socket.keyframe_insert("default_value", frame=frame)
    if name is not None and tree.animation_data is not None and tree.animation_data.action is not None:
        tree.animation_data.action.name = name


def keyed_curve(tree):
    """The (frame, u, v, intensity) keys the tree holds now, or None."""
    action = tree.animation_data.action if tree.animation_data else None
    if action is None:
        return None
    from bpy_extras import anim_utils

    bag = anim_utils.action_get_channelbag_for_slot(action, tree.animation_data.action_slot)
    sun_node, rays = sun_key_node(tree), rays_node(tree)
    paths = [socket.path_from_id("default_value")
             for socket in (sun_node.inputs["X"], sun_node.inputs["Y"], rays.inputs["Intensity"])]
    columns = []
    for path in paths:
        fcurve = next((c for c in bag.fcurves if c.data_path == path), None)
        if fcurve is None:
            return None
        values = np.empty(len(fcurve.keyframe_points) * 2, np.float64)
        fcurve.keyframe_points.foreach_get("co", values)
        columns.append(values.reshape(-1, 2))
    if len({len(c) for c in columns}) != 1:
        return None
    return [(int(round(f)), u, v, i) for (f, u), (_, v), (_, i) in zip(*columns, strict=True)]


def scene_digest(scene, sun, fade):
    """The view digest of the scene's camera and this sun, or None (no camera, or motion the
    digest cannot see)."""
    camera = shot.scene_camera(scene)
    return view_digest.digest(scene, sun, camera, fade) if sun is not None and camera is not None else None


def key_scene(tree, scene, sun, fade):
    """Key the sun on every frame now and remember the digest the keys were made for; the curve."""
    curve = sun_curve(scene, sun, fade)
    key_sun(tree, curve)
    tree[DIGEST_KEY] = scene_digest(scene, sun, fade) or ""
    return curve


def refresh(tree, scene, sun, fade):
    """Key the sun again where the keys may be stale; True when they were rewritten. Nothing is
    stepped when the digest is the one the keys were made for."""
    fingerprint = scene_digest(scene, sun, fade)
    keyed = keyed_curve(tree)
    if fingerprint is not None and tree.get(DIGEST_KEY) == fingerprint and keyed is not None:
        return False
    curve = sun_curve(scene, sun, fade)
    tree[DIGEST_KEY] = fingerprint or ""
    if keyed is not None and len(keyed) == len(curve) and np.allclose(
            np.array(keyed), np.array(curve), atol=1e-6, rtol=0.0):
        return False
    key_sun(tree, curve)
    return True
