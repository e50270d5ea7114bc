"""A rig that walks: an armature with the usual rigs' foot names, its feet keyed through a walk
with a turn and a stop (each foot planted, then swinging in a 10 cm arc to its next plant). For
the rig footprint tests and the rig contact bench."""

import math

import bpy
import numpy as np
from mathutils import Matrix, Vector

ANKLE, BALL, TIP = Vector((-0.06, 0.0, 0.08)), Vector((0.12, 0.0, 0.02)), Vector((0.2, 0.0, 0.0))
STANCE = 0.12  # each foot this far from the middle
# Each foot's plants: (x, y, heading, first frame, last frame); the last ones stand side by side.
PLANTS = {
    1: [(0.0, 0.0, 0.0, 1, 14), (1.3, 0.1, 0.15, 27, 40), (2.6, 0.45, 0.4, 53, 90)],
    -1: [(0.65, 0.0, 0.0, 1, 27), (1.95, 0.25, 0.3, 40, 53), (2.55, 0.15, 0.4, 66, 90)],
}
# A jog at 24 fps (3.2 m/s): each foot down 5 frames (0.21 s), 1.2 m steps, both feet off between;
# the right foot is in the air as the scene starts (its plant before frame 1 is never sampled).
RUN_PLANTS = {
    1: [(0.0, 0.0, 0.0, 1, 5), (2.4, 0.0, 0.0, 19, 23), (4.8, 0.0, 0.0, 37, 41)],
    -1: [(-1.2, 0.0, 0.0, -8, -4), (1.2, 0.0, 0.0, 10, 14), (3.6, 0.0, 0.0, 28, 32), (6.0, 0.0, 0.0, 46, 50)],
}
NAMES = {
    "metarig": {1: ("foot.L", "toe.L"), -1: ("foot.R", "toe.R")},
    "rigify": {1: ("DEF-foot.L", "DEF-toe.L"), -1: ("DEF-foot.R", "DEF-toe.R")},
    "auto-rig pro": {1: ("foot.l", "toes_01.l"), -1: ("foot.r", "toes_01.r")},
    "mixamo": {1: ("mixamorig:LeftFoot", "mixamorig:LeftToeBase"),
               -1: ("mixamorig:RightFoot", "mixamorig:RightToeBase")},
}


def foot_place(plants, frame):
    """(x, y, heading, lift) of a foot at a frame: planted, or swinging in a 10 cm arc."""
    for k, (x, y, heading, first, last) in enumerate(plants):
        if frame <= last and (k == 0 or frame >= first):
            if frame >= first:
                return x, y, heading, 0.0
        following = plants[k + 1] if k + 1 < len(plants) else None
        if following is not None and last < frame < following[3]:
            t = (frame - last) / (following[3] - last)
            here = np.array([x, y, heading]) + (np.array(following[:3]) - [x, y, heading]) * t
            return (*here, 0.1 * math.sin(math.pi * t))
    x, y, heading, *_ = plants[-1] if frame > plants[-1][4] else plants[0]
    return x, y, heading, 0.0


def placement(side, x, y, heading, lift):
    """The foot's rest-to-pose transform in armature space: turned about its ankle, moved."""
    ankle = ANKLE + Vector((0.0, side * STANCE, 0.0))
    return (Matrix.Translation(Vector((x, y, lift)) + ankle) @ Matrix.Rotation(heading, 4, "Z")
            @ Matrix.Translation(-ankle))


def walking_rig(convention, frames=90, extra_bones=0, plants=PLANTS):
    """The rig, keyed on frames 1..frames (the walk is over by 90); extra_bones keyed bones more,
    a chain standing in for a body, cost a real rig evaluates on every frame."""
    armature = bpy.data.objects.new("Rig", bpy.data.armatures.new("Rig"))
    bpy.context.scene.collection.objects.link(armature)
    bpy.context.view_layer.objects.active = armature
    bpy.ops.object.mode_set(mode="EDIT")
    for side, (foot, toe) in NAMES[convention].items():
        offset = Vector((0.0, side * STANCE, 0.0))
        bone = armature.data.edit_bones.new(foot)
        bone.head, bone.tail = ANKLE + offset, BALL + offset
        tip = armature.data.edit_bones.new(toe)
        tip.head, tip.tail, tip.parent, tip.use_connect = BALL + offset, TIP + offset, bone, True
    parent = None
    for index in range(extra_bones):
        body = armature.data.edit_bones.new(f"Body {index}")
        body.head, body.tail = (0.0, 0.0, 1.0 + 0.01 * index), (0.0, 0.0, 1.01 + 0.01 * index)
        body.parent = parent
        parent = body
    bpy.ops.object.mode_set(mode="OBJECT")
    for frame in range(1, frames + 1):
        for index in range(extra_bones):
            body = armature.pose.bones[f"Body {index}"]
            body.rotation_mode = "XYZ"
            body.rotation_euler.z = 0.01 * math.sin(frame / 7 + index)
            body.keyframe_insert("rotation_euler", frame=frame)
        for side, (foot, _) in NAMES[convention].items():
            bone = armature.pose.bones[foot]
            bone.rotation_mode = "QUATERNION"
            bone.matrix = placement(side, *foot_place(plants[side], frame)) @ bone.bone.matrix_local
            bpy.context.view_layer.update()
            bone.keyframe_insert("location", frame=frame)
            bone.keyframe_insert("rotation_quaternion", frame=frame)
    return armature


def expected_prints(gait=PLANTS):
    """Each plant's sole middle (world x, y), heading and first frame."""
    rows = []
    for side, plants in gait.items():
        for x, y, heading, first, _ in plants:
            middle = placement(side, x, y, heading, 0.0) @ ((ANKLE + TIP) / 2 + Vector((0, side * STANCE, 0)))
            rows.append((middle.x, middle.y, heading, first, side))
    return sorted(rows, key=lambda row: (row[3], -row[4]))
