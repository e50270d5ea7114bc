"""What the god rays' keyed sun depends on, as one digest: saving and rendering step through the
frames to key the sun again only when the digest changed.

The sun's place on screen over the frame range follows from the scene camera and the sun: their
transforms, parents and constraint targets (and theirs), animation (actions, NLA strips, drivers
and their targets), the camera's lens, the render size and frame range, and markers that switch
cameras. Hashing those costs milliseconds; stepping every frame costs as much as playing the
shot. Where motion can come from something not hashed here (physics, a vertex parent, a solver or
shrinkwrap constraint), there is no digest (None): the keys are always made again.
"""

import hashlib

import bpy
import numpy as np

VERSION = 1  # bump when what goes into the digest changes: older digests then never match
SIMPLE = {"BOOLEAN", "INT", "FLOAT", "ENUM", "STRING"}
UNHASHED_CONSTRAINTS = {"SHRINKWRAP", "CAMERA_SOLVER", "OBJECT_SOLVER", "FOLLOW_TRACK"}
BEZIER_FIELDS = (("co", 3), ("handle_left", 3), ("handle_right", 3), ("tilt", 1), ("radius", 1))
NURBS_FIELDS = (("co", 4), ("tilt", 1), ("radius", 1), ("weight_softbody", 1))
TRANSFORMS = ("location", "rotation_euler", "rotation_quaternion", "rotation_axis_angle", "scale",
              "delta_location", "delta_rotation_euler", "delta_rotation_quaternion", "delta_scale")


class Unhashable(Exception):
    """The motion depends on something the digest does not cover."""


def _plain(value):
    if isinstance(value, bpy.types.ID):
        return value.name_full
    if isinstance(value, (set, frozenset)):  # an enum flag: sorted, so the digest keeps across sessions
        return tuple(sorted(value))
    if hasattr(value, "__len__") and not isinstance(value, str):
        return tuple(_plain(v) for v in value)
    return value


def _values(struct, prefix, animated, out, follow):
    """Every simple setting of an RNA struct not driven by animation; ID pointers go to follow."""
    for prop in struct.bl_rna.properties:
        name = prop.identifier
        if name == "rna_type" or prop.is_readonly and prop.type != "POINTER":
            continue
        if prop.type in SIMPLE:
            if f"{prefix}{name}" not in animated:
                out.append((prefix, name, _plain(getattr(struct, name))))
        elif prop.type == "POINTER":
            value = getattr(struct, name)
            if isinstance(value, bpy.types.ID):
                out.append((prefix, name, value.name_full))
                follow.append(value)


def _action_curves(action):
    for layer in action.layers:
        for strip in layer.strips:
            for bag in strip.channelbags:
                yield from bag.fcurves


def _curve(fcurve, out):
    count = len(fcurve.keyframe_points)
    keys = np.empty(count * 6, np.float64)
    for i, attribute in enumerate(("co", "handle_left", "handle_right")):
        part = np.empty(count * 2, np.float64)
        fcurve.keyframe_points.foreach_get(attribute, part)
        keys[i * count * 2:(i + 1) * count * 2] = part
    kinds = tuple((k.interpolation, k.easing) for k in fcurve.keyframe_points)
    modifiers = []
    for modifier in fcurve.modifiers:
        _values(modifier, "", (), modifiers, [])
    out.append((fcurve.data_path, fcurve.array_index, fcurve.extrapolation, fcurve.mute,
                hashlib.sha1(keys.tobytes()).hexdigest(), kinds, tuple(modifiers)))


def _animation(block, out, follow):
    """Hash a block's animation; return the animated paths ("path" and "path[index]")."""
    data = getattr(block, "animation_data", None)
    animated = set()
    if data is None:
        return animated
    actions = [data.action] if data.action is not None else []
    out.append(("animation", data.action.name_full if data.action else None, data.action_extrapolation,
                data.action_blend_type, data.action_influence, data.use_nla, data.use_tweak_mode))
    for track in data.nla_tracks:
        out.append(("track", track.name, track.mute, track.is_solo))
        for strip in track.strips:
            strip_values = []
            _values(strip, "", (), strip_values, [])
            out.append(("strip", tuple(strip_values)))
            if strip.action is not None:
                actions.append(strip.action)
    curves = [c for action in actions for c in _action_curves(action)] + list(data.drivers)
    for fcurve in curves:
        _curve(fcurve, out)
        animated.update({fcurve.data_path, f"{fcurve.data_path}[{fcurve.array_index}]"})
    for fcurve in data.drivers:
        driver = fcurve.driver
        out.append(("driver", driver.type, driver.expression, driver.use_self))
        for variable in driver.variables:
            for target in variable.targets:
                out.append(("target", variable.name, variable.type, _plain(target.id), target.data_path,
                            target.transform_type, target.transform_space, target.rotation_mode,
                            target.bone_target))
                if target.id is not None:
                    follow.append(target.id)
    return animated


def _static_transform(obj, animated, out):
    for name in TRANSFORMS:
        value = getattr(obj, name)
        out.append((name, tuple(None if name in animated or f"{name}[{i}]" in animated else float(v)
                                for i, v in enumerate(value))))
    out.append(("parent", _plain(obj.parent), obj.parent_type, obj.parent_bone, obj.rotation_mode,
                obj.track_axis, obj.up_axis, _plain(obj.matrix_parent_inverse)))


def _object(obj, out, follow):
    if obj.rigid_body is not None or obj.parent_type in {"VERTEX", "VERTEX_3"}:
        raise Unhashable(obj.name)
    animated = _animation(obj, out, follow)
    _static_transform(obj, animated, out)
    for constraint in obj.constraints:
        if constraint.type in UNHASHED_CONSTRAINTS:
            raise Unhashable(f"{obj.name}: {constraint.type}")
        _values(constraint, f'constraints["{constraint.name}"].', animated, out, follow)
    if obj.parent is not None:
        follow.append(obj.parent)
    if obj.type == "ARMATURE" and obj.pose is not None:  # a parent bone or a constraint's subtarget
        for bone in obj.data.bones:  # the rest pose: head, tail, roll, parenting
            parent = bone.parent.name if bone.parent else None
            out.append(("rest", bone.name, _plain(bone.matrix_local), bone.length, parent, bone.use_connect,
                        bone.use_inherit_rotation, bone.inherit_scale, bone.use_local_location))
        for bone in obj.pose.bones:
            prefix = f'pose.bones["{bone.name}"].'
            out.append((prefix, tuple(_plain(getattr(bone, n)) for n in
                                      ("location", "rotation_quaternion", "rotation_euler", "scale")
                                      if f"{prefix}{n}" not in animated)))
            for constraint in bone.constraints:
                _values(constraint, f'{prefix}constraints["{constraint.name}"].', animated, out, follow)
    if obj.type == "CURVE":  # a path the camera follows: its points, tilts, handles and settings
        for spline in obj.data.splines:
            settings = []
            _values(spline, "", (), settings, [])
            bezier = spline.type == "BEZIER"
            points = spline.bezier_points if bezier else spline.points
            fields = BEZIER_FIELDS if bezier else NURBS_FIELDS
            sha = hashlib.sha1()
            for name, width in fields:
                values = np.empty(len(points) * width, np.float64)
                points.foreach_get(name, values)
                sha.update(values.tobytes())
            out.append(("spline", tuple(settings), sha.hexdigest()))
    if obj.data is not None and obj.type in {"CAMERA", "CURVE"}:  # a sun's strength moves nothing
        data_animated = _animation(obj.data, out, follow)
        _values(obj.data, "", data_animated, out, [])


def digest(scene, sun, camera, fade):
    """A hex digest of everything the keyed sun depends on, or None where that cannot be known."""
    render = scene.render
    out = [("version", VERSION, fade), ("frames", scene.frame_start, scene.frame_end),
           ("render", render.resolution_x, render.resolution_y, render.resolution_percentage,
            render.pixel_aspect_x, render.pixel_aspect_y),
           ("objects", sun.name_full, camera.name_full),
           ("markers", tuple(sorted((m.frame, _plain(m.camera)) for m in scene.timeline_markers)))]
    follow, seen = [sun, camera], set()
    try:
        _animation(scene, out, [])  # a keyed scene camera
        while follow:
            block = follow.pop()
            key = (type(block).__name__, block.name_full)
            if key in seen:
                continue
            seen.add(key)
            out.append(("block",) + key)
            if isinstance(block, bpy.types.Object):
                _object(block, out, follow)
            else:
                _animation(block, out, [])
    except Unhashable:
        return None
    return hashlib.sha1(repr(out).encode()).hexdigest()
