"""World matrices over a frame range read from the keyframes alone, without stepping the frames.

For objects that plain F-curves move (location, rotation and scale in the active action, their
own and their object parents'): the usual keyed camera, dolly rig or sun. Stepping the frames
instead costs as much as playing the shot and runs every frame handler in the file. Anything
else returns None and the caller steps the frames: constraints, drivers, NLA strips, a blended
or partial action, delta transforms, bone or vertex parents, an animated transform mode, time
remapping.
"""

from bpy_extras import anim_utils
from mathutils import Euler, Matrix, Quaternion, Vector

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
    return no_delta and parent_ok and not len(obj.constraints)


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


def _basis(obj, curves, frame):
    location = Vector(_values(obj, curves, "location", frame))
    scale = Vector(_values(obj, curves, "scale", frame))
    mode = obj.rotation_mode
    if mode == "QUATERNION":
        rotation = Quaternion(_values(obj, curves, "rotation_quaternion", frame)).normalized()
    elif mode == "AXIS_ANGLE":
        angle, *axis = _values(obj, curves, "rotation_axis_angle", frame)
        rotation = Quaternion(Vector(axis).normalized(), angle) if Vector(axis).length else Quaternion()
    else:
        rotation = Euler(_values(obj, curves, "rotation_euler", frame), mode).to_quaternion()
    return Matrix.LocRotScale(location, rotation, scale)


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
        world = Matrix.Identity(4)
        for link, curves in reversed(chain):  # from the top parent down
            local = _basis(link, curves, frame)
            world = world @ link.matrix_parent_inverse @ local if link.parent is not None else local
        matrices.append(world)
    return matrices


def still_camera_data(camera):
    """True when nothing animates the camera's lens, sensor or shift: one projection serves every
    frame."""
    animation = camera.data.animation_data
    return animation is None or (animation.action is None and not len(animation.drivers)
                                 and not len(animation.nla_tracks))
