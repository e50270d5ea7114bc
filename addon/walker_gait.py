"""The stand-in walker's legs and their stride: child objects (thighs from the hips, shins from
the knees; the arms are under walker_figure's poncho) whose swing is keyed on every frame from the
walker's own motion, phased by core.gait to the prints the path plans, so a foot is under its hip
where its print lies.

Keys, not drivers: a file opened with scripts off walks the same. Limbs are ours (OBJECT_KEY
"walker_limb", LIMB_KEY the limb's name), found among the walker's children.
"""

import bmesh
import bpy
import numpy as np
from bpy_extras import anim_utils
from mathutils import Matrix

from ..core import gait, paths
from . import ownership as own

LIMB_KEY = "sandscape_limb"
HIPS = 0.86  # metres above the soles
THIGH = SHIN = 0.44  # a leg a hair longer than the hips are high: the planted foot sinks into the sand
LEG_LENGTH = THIGH + SHIN
STANCE_LIMITS = (0.06, 0.16)  # metres either side of the path a leg hangs (from the prints' stance)
# Tapered cylinders hanging from a pivot: name: (radius at the bottom, at the top, length, side,
# the pivot's height over the soles, or its drop below the end of the limb it hangs from), metres.
# A thigh's distance from the middle follows the stance.
LIMBS = {"left_thigh": (0.05, 0.065, THIGH, paths.LEFT, HIPS),
         "right_thigh": (0.05, 0.065, THIGH, paths.RIGHT, HIPS),
         "left_shin": (0.032, 0.045, SHIN, paths.LEFT, THIGH),
         "right_shin": (0.032, 0.045, SHIN, paths.RIGHT, THIGH)}
HUNG_FROM = {"left_shin": "left_thigh", "right_shin": "right_thigh"}
# A shin ends in a foot: (heel, toe: metres behind and ahead of the ankle; width; height) centred
# on the ankle as the print is, so the foot fills the print it stands in; a flattened cone from the
# heel narrowing to TOE_SHARE of its width at the toe (a box read as a block, the eighth review).
FOOT = (0.12, 0.14, 0.09, 0.07)
TOE_SHARE = 0.55
# 7: feet tapering to the toe; 6: thin legs, no arms (under the poncho; the sixth review: thick legs
# and ball hands read as a gnome's); 5: bell sleeves half over the hands; 4: legs and hands wrapped
# in dark cloth, slimmer legs; 3: sleeves widening to the wrist from a rounded shoulder, caps shaded
# sharp; 2: shins with feet (limbs before that had none)
SHAPE_KEY, SHAPE = "sandscape_limb_shape", 7
SHARP_ANGLE = 0.9  # radians: caps and rims keep their edges; the sides shade smooth


def limbs(walker):
    """{name: object} of the walker's limbs that are ours."""
    return {child[LIMB_KEY]: child for child in walker.children_recursive
            if child.get(own.OBJECT_KEY) == own.WALKER_LIMB and child.get(LIMB_KEY) in LIMBS}


def swap_mesh(obj, mesh):
    """Give `obj` a new mesh; the old one goes if nothing else uses it."""
    old, obj.data = obj.data, mesh
    if old.users == 0:
        bpy.data.meshes.remove(old)


def shade_smooth_but_edges(bm):
    """Smooth faces, sharp edges where faces meet at over SHARP_ANGLE (a smoothed cap darkens the
    side it meets, and a limb reads as a box)."""
    for face in bm.faces:
        face.smooth = True
    for edge in bm.edges:
        edge.smooth = not (edge.is_manifold and edge.calc_face_angle(0.0) > SHARP_ANGLE)


def _limb_mesh(name, bottom, top, length, scale):
    bm = bmesh.new()
    # bmesh's cone is centred on its origin, its axis along Z: hang it from its top.
    bmesh.ops.create_cone(bm, cap_ends=True, segments=10, radius1=bottom * scale, radius2=top * scale,
                          depth=length * scale, matrix=Matrix.Translation((0.0, 0.0, -length * scale / 2)))
    if name.endswith("Shin"):
        heel, toe, width, height = (value * scale for value in FOOT)
        # A unit cone turned onto its side (its axis from -Z to +X: heel to toe), then sized.
        foot = Matrix.Translation(((toe - heel) / 2, 0.0, -length * scale + height / 2))
        foot = foot @ Matrix.Diagonal((heel + toe, width / 2, height / 2, 1.0))
        foot = foot @ Matrix.Rotation(np.pi / 2, 4, "Y")
        bmesh.ops.create_cone(bm, cap_ends=True, segments=10, radius1=1.0, radius2=TOE_SHARE, depth=1.0,
                              matrix=foot)
    shade_smooth_but_edges(bm)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def _remove_retired_limbs(walker):
    """An older walker's arms (they hung out of bell sleeves; the poncho covers them now)."""
    for child in list(walker.children_recursive):
        if child.get(own.OBJECT_KEY) == own.WALKER_LIMB and child.get(LIMB_KEY) not in LIMBS:
            mesh = child.data
            bpy.data.objects.remove(child)
            if mesh is not None and mesh.users == 0:
                bpy.data.meshes.remove(mesh)


def ensure_limbs(walker, cloth, scale, stance):
    """The walker's legs, made where missing, hung at their pivots (`stance` in scene units,
    `scale` scene units per metre): thighs from the body, shins from the knees; they wear the
    wraps (`cloth`: {kind: material}). Returns {name: object}."""
    _remove_retired_limbs(walker)
    found = limbs(walker)
    collections = walker.users_collection
    for name, (bottom, top, length, side, pivot) in LIMBS.items():
        limb = found.get(name)
        title = "Sandscape Walker " + name.replace("_", " ").title()
        if limb is None or limb.get(SHAPE_KEY) != SHAPE:  # missing, or an older walker's shape
            mesh = _limb_mesh(title, bottom, top, length, scale)
            mesh.materials.append(cloth[own.WRAPS])
        if limb is None:
            limb = bpy.data.objects.new(title, mesh)
            own.mark(limb, own.OBJECT_KEY, own.WALKER_LIMB, **{LIMB_KEY: name})
            for collection in collections:
                collection.objects.link(limb)
            found[name] = limb
        elif limb.get(SHAPE_KEY) != SHAPE:
            swap_mesh(limb, mesh)
        limb[SHAPE_KEY] = SHAPE
        limb.parent = found[HUNG_FROM[name]] if name in HUNG_FROM else walker
        limb.rotation_mode = "XYZ"
        if name in HUNG_FROM:
            limb.location = (0.0, 0.0, -pivot * scale)
            continue
        across = float(np.clip(stance / 2, STANCE_LIMITS[0] * scale, STANCE_LIMITS[1] * scale))
        limb.location = (0.0, side * across, pivot * scale)
        limb.rotation_euler[0] = 0.0
    return found


def key_stride(walker, positions, frames, stride, scale):
    """Key each limb's swing on every frame from the walker's world `positions` at `frames`
    (as footprints samples them), for prints `stride` scene units apart."""
    arc = paths.arc_length(positions)
    amplitude = gait.leg_amplitude(LEG_LENGTH * scale, stride)
    for name, limb in limbs(walker).items():
        side = LIMBS[name][3]
        if name.endswith("shin"):  # bends back at the knee as its leg swings through
            swing = -gait.knee_bend(arc, stride, side)
        else:
            swing = gait.leg_swing(arc, stride, amplitude, side)
        # A turn about local Y by -theta swings the limb's lower end forward (+X) by theta.
        _key_every_frame(limb, "rotation_euler", 1, frames, -swing)


def _key_every_frame(obj, path, index, frames, values):
    curve = _curve(obj, path, index)
    if curve is None:  # the first time: Blender makes the action, its slot and the curve
        obj.keyframe_insert(path, index=index, frame=float(frames[0]))
        curve = _curve(obj, path, index)
    curve.keyframe_points.clear()
    curve.keyframe_points.add(len(frames))
    co = np.empty(2 * len(frames), np.float32)
    co[0::2], co[1::2] = np.asarray(frames, np.float32), np.asarray(values, np.float32)
    curve.keyframe_points.foreach_set("co", co)
    curve.keyframe_points.foreach_set("interpolation", np.full(len(frames), _linear(), np.int32))
    curve.update()


def _curve(obj, path, index):
    animation = obj.animation_data
    if animation is None or animation.action is None:
        return None
    bag = anim_utils.action_get_channelbag_for_slot(animation.action, animation.action_slot)
    curves = bag.fcurves if bag is not None else ()
    return next((c for c in curves if c.data_path == path and c.array_index == index), None)


def _linear():
    return bpy.types.Keyframe.bl_rna.properties["interpolation"].enum_items["LINEAR"].value

