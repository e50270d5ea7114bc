"""World matrices over a frame range read from the keyframes alone, without stepping the frames.

For objects that plain F-curves move (location, rotation and scale in the active action, their
own and their object parents'): the usual keyed camera, dolly rig or sun. Stepping the frames
instead costs as much as playing the shot and runs every frame handler in the file. Anything
else returns None and the caller steps the frames: constraints, drivers, NLA strips, a blended
or partial action, delta transforms, bone or vertex parents, a path parent, rigid body physics,
an animated transform mode, time remapping. A frame-change handler that moves the camera is
not seen either; nor is it by the view digest. The matrices are in double precision.
"""

import numpy as np
from bpy_extras import anim_utils

CHANNELS = {"location": 3, "rotation_euler": 3, "rotation_quaternion": 4, "rotation_axis_angle": 4,
            "scale": 3}


def _fcurves(obj):
    """{(path, index): fcurve} of the object's active action, or None when more than plain keys
    on its transform channels move it."""
    animation = obj.animation_data
    if animation is None:
        return {}
    if len(animation.drivers) or len(animation.nla_tracks) or animation.use_tweak_mode:
        return None
    if animation.action is None:
        return {}
    if getattr(animation, "action_influence", 1.0) != 1.0 or getattr(
            animation, "action_blend_type", "REPLACE") != "REPLACE":
        return None
    bag = anim_utils.action_get_channelbag_for_slot(animation.action, animation.action_slot)
    if bag is None:
        return {}
    curves = {}
    for fcurve in bag.fcurves:
        if fcurve.data_path not in CHANNELS or fcurve.mute:
            return None  # an animated transform mode, or a property we do not follow
        curves[(fcurve.data_path, fcurve.array_index)] = fcurve
    return curves


def _plain(obj):
    no_delta = (tuple(obj.delta_location) == (0.0, 0.0, 0.0) and tuple(obj.delta_scale) == (1.0, 1.0, 1.0)
                and tuple(obj.delta_rotation_euler) == (0.0, 0.0, 0.0)
                and tuple(obj.delta_rotation_quaternion) == (1.0, 0.0, 0.0, 0.0))
    parent_ok = obj.parent is None or obj.parent_type == "OBJECT"
    # A path parent moves its children along the curve (its eval_time is the curve's own key);
    # physics moves an object with no key at all.
    on_path = obj.type == "CURVE" and getattr(obj.data, "use_path", False)
    data_keyed = obj.data is not None and getattr(obj.data, "animation_data", None) is not None
    physics = obj.rigid_body is not None or obj.rigid_body_constraint is not None
    return no_delta and parent_ok and not len(obj.constraints) and not on_path and not physics and (
        obj.type in ("CAMERA", "LIGHT") or not data_keyed)


def _chain(obj):
    """[(object, fcurves)] from the object up through its parents, or None."""
    chain = []
    while obj is not None:
        curves = _fcurves(obj)
        if curves is None or not _plain(obj):
            return None
        chain.append((obj, curves))
        obj = obj.parent
    return chain


def _values(obj, curves, path, frame):
    return [curves[(path, i)].evaluate(frame) if (path, i) in curves else getattr(obj, path)[i]
            for i in range(CHANNELS[path])]


def _axis_rotation(axis, angle):
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    rotation = np.eye(3)
    rotation[i, i], rotation[i, j], rotation[j, i], rotation[j, j] = c, -s, s, c
    return rotation


def _quaternion_matrix(w, x, y, z):
    length = np.sqrt(w * w + x * x + y * y + z * z)
    if length == 0.0:
        return np.eye(3)
    w, x, y, z = w / length, x / length, y / length, z / length
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _basis(obj, curves, frame):
    """The object's local matrix on a frame, in double precision (mathutils works in single)."""
    location = np.array(_values(obj, curves, "location", frame), np.float64)
    scale = np.array(_values(obj, curves, "scale", frame), np.float64)
    mode = obj.rotation_mode
    if mode == "QUATERNION":
        rotation = _quaternion_matrix(*_values(obj, curves, "rotation_quaternion", frame))
    elif mode == "AXIS_ANGLE":
        angle, *axis = _values(obj, curves, "rotation_axis_angle", frame)
        length = float(np.linalg.norm(axis))
        rotation = np.eye(3) if length == 0.0 else _quaternion_matrix(
            np.cos(angle / 2), *(np.sin(angle / 2) * np.asarray(axis) / length))
    else:  # an euler order "XYZ" turns about X first, then Y, then Z
        angles = _values(obj, curves, "rotation_euler", frame)
        rotation = np.eye(3)
        for letter in mode:
            axis = "XYZ".index(letter)
            rotation = _axis_rotation(axis, angles[axis]) @ rotation
    basis = np.eye(4)
    basis[:3, :3] = rotation * scale
    basis[:3, 3] = location
    return basis


def world_matrices(scene, obj, frames):
    """The object's world matrix on each frame, from its keys and its parents' keys; None when
    anything else moves it (or the scene remaps time)."""
    if scene.render.frame_map_old != scene.render.frame_map_new:
        return None
    chain = _chain(obj)
    if chain is None:
        return None
    matrices = []
    for frame in frames:
        world = np.eye(4)
        for link, curves in reversed(chain):  # from the top parent down
            local = _basis(link, curves, frame)
            world = world @ np.array(link.matrix_parent_inverse) @ local if link.parent is not None else local
        matrices.append(world)
    return matrices


def still_camera_data(camera):
    """True when the camera is a camera and nothing animates its lens, sensor or shift: one
    projection serves every frame."""
    if camera.type != "CAMERA":
        return False
    animation = camera.data.animation_data
    return animation is None or (animation.action is None and not len(animation.drivers)
                                 and not len(animation.nla_tracks))
