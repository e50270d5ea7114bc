"""Feet of a rigged walker: its foot bones found by the usual rigs' names, sampled over the frames
as soles (heel and toe in world space), and their contacts with the terrain (core/contacts.py).

The sole: the foot bone's head (the ankle) and the toe bone's tail (or the foot's tail), each
lowered by its height above the lowest of them in the rest pose, where a rig stands on its feet.
"""

import numpy as np

from ..core import contacts as core_contacts
from . import evaluation, shot, walker

# (left foot, right foot, left toe, right toe) by rig; the first whose feet all exist is used.
CONVENTIONS = (
    ("Rigify", ("DEF-foot.L", "DEF-foot.R", "DEF-toe.L", "DEF-toe.R")),
    ("Rigify metarig", ("foot.L", "foot.R", "toe.L", "toe.R")),
    ("Mixamo", ("mixamorig:LeftFoot", "mixamorig:RightFoot", "mixamorig:LeftToeBase",
                "mixamorig:RightToeBase")),
    ("Auto-Rig Pro", ("foot.l", "foot.r", "toes_01.l", "toes_01.r")),
)
LEFT, RIGHT = 1, -1


def armature_of(obj):
    """The object if it is an armature, else its first armature child, else None."""
    if obj is None:
        return None
    if obj.type == "ARMATURE":
        return obj
    return next((child for child in obj.children_recursive if child.type == "ARMATURE"), None)


def foot_bones(armature, chosen=("", "")):
    """(rig name, [(side, foot bone, toe bone or None)]): the artist's chosen (left, right) foot
    bones when both are named (their first child is the toe), else those of the first convention
    the armature follows, else (None, []). Raises ContactError for a chosen bone that is not there."""
    bones = armature.data.bones
    if all(chosen):
        missing = [name for name in chosen if name not in bones]
        if missing:
            raise core_contacts.ContactError(f"'{armature.name}' has no bone '{missing[0]}'")
        return "chosen", [(side, name, bones[name].children[0].name if bones[name].children else None)
                          for side, name in ((LEFT, chosen[0]), (RIGHT, chosen[1]))]
    for rig, (left, right, left_toe, right_toe) in CONVENTIONS:
        if left in bones and right in bones:
            return rig, [(LEFT, left, left_toe if left_toe in bones else None),
                         (RIGHT, right, right_toe if right_toe in bones else None)]
    return None, []


def _rest_lift(armature, feet):
    """How far above the rest pose's lowest sole point each foot's ankle and toe tip stand."""
    points = {}
    for _, foot, toe in feet:
        bones = armature.data.bones
        points[foot] = (bones[foot].head_local.z, (bones[toe] if toe else bones[foot]).tail_local.z)
    floor = min(min(pair) for pair in points.values())
    scale = max(armature.matrix_world.to_scale())
    return {foot: ((ankle - floor) * scale, (tip - floor) * scale) for foot, (ankle, tip) in points.items()}


def sample_soles(scene, armature, feet, frames):
    """{foot bone: (heel (F, 3), toe (F, 3))} in world space over the frames."""
    lift = _rest_lift(armature, feet)
    soles = {foot: (np.empty((len(frames), 3)), np.empty((len(frames), 3))) for _, foot, _ in feet}
    for index, _ in enumerate(evaluation.stepped_frames(scene, frames)):
        evaluated = armature.evaluated_get(evaluation.scene_depsgraph(scene))
        world = np.array(evaluated.matrix_world)
        for _, foot, toe in feet:
            pose = evaluated.pose.bones
            ankle = world @ np.r_[pose[foot].head[:], 1.0]
            tip = world @ np.r_[(pose[toe] if toe else pose[foot]).tail[:], 1.0]
            heel, front = soles[foot]
            heel[index] = ankle[:3] - [0.0, 0.0, lift[foot][0]]
            front[index] = tip[:3] - [0.0, 0.0, lift[foot][1]]
    return soles


def foot_length(armature, foot, toe):
    bones = armature.data.bones
    tip = (bones[toe] if toe else bones[foot]).tail_local
    return float((tip - bones[foot].head_local).length * max(armature.matrix_world.to_scale()))


def steps(scene, armature, terrain, frames, chosen=("", "")):
    """Prints where the feet land: the dict footprints.emit takes (contact, birth, forward, side,
    strike, seconds planted, and "how": which bones), or None when the armature has no feet
    Sandscape knows."""
    rig, feet = foot_bones(armature, chosen)
    if not feet:
        return None
    soles = sample_soles(scene, armature, feet, frames)
    local, _ = evaluation.mesh_triangles(terrain.data)  # numpy, not a Python loop over vertices
    world = np.array(terrain.matrix_world)
    top = float((local @ world[2, :3] + world[2, 3]).max()) + 1.0
    fps = shot.frames_per_second(scene)
    found = {"contact": [], "birth": [], "forward": [], "side": [], "strike": [], "seconds": []}
    for side, foot, toe in feet:
        heel, front = soles[foot]
        lowest = np.where((heel[:, 2] <= front[:, 2])[:, None], heel, front)
        ground = walker.ground_heights(scene, terrain, lowest[:, :2], top)
        ground = np.where(ground >= top, np.nan, ground)  # off the terrain: no contact there
        for contact in core_contacts.foot_contacts(frames, heel, front, ground, foot_length(
                armature, foot, toe), fps):
            found["contact"].append(contact.position)
            found["birth"].append(float(frames[contact.first]))
            found["forward"].append((np.cos(contact.heading), np.sin(contact.heading), 0.0))
            found["side"].append(side)
            found["strike"].append(contact.strike)
            found["seconds"].append(contact.seconds)
    order = np.argsort(found["birth"], kind="stable")
    result = {key: np.asarray(values, np.float64 if key != "side" else np.int32)[order] if values
              else np.zeros((0, 3) if key in ("contact", "forward") else 0)
              for key, values in found.items()}
    result["how"] = f"on its feet ({rig} bones '{feet[0][1]}', '{feet[1][1]}')"
    return result
