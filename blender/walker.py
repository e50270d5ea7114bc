"""The stand-in walker: a box on a Follow Path constraint along a gentle S-shaped curve, for
artists without a rig. Any animated object works as a walker; this one is only a start.

Both objects are ours (OBJECT_KEY "walker" and "walk_path") and found in the scene the
operator runs in, so running it again updates them and another scene gets its own.
"""

import math

import bpy
import numpy as np
from bpy_extras import anim_utils
from mathutils import Vector

from . import ownership as own
from . import units

WALK_SPEED = 1.4  # metres per second, a walking pace, for the stand-in when there is no terrain
BOX = (0.4, 0.3, 1.7)  # metres: a person-sized stand-in


def frame_range_problem(start, end):
    if end <= start:
        return f"The frame range {start}..{end} is too short to walk"
    return None


def ensure_walker(scene, terrain, start, end):
    """The scene's stand-in walker and its path, made or updated. Returns (walker, path)."""
    path = own.scene_object(scene, own.WALK_PATH) or _new_path(scene)
    fps = scene.render.fps / scene.render.fps_base
    _shape_path(path, terrain, units.to_units(scene, (end - start) / fps * WALK_SPEED))
    walker = own.scene_object(scene, own.WALKER) or _new_walker(scene, path)
    _animate(walker, start, end)
    return walker, path


def _new_path(scene):
    curve = bpy.data.curves.new("Sandscape Walk Path", "CURVE")
    curve.dimensions = "3D"
    path = own.mark(bpy.data.objects.new("Sandscape Walk Path", curve), own.OBJECT_KEY, own.WALK_PATH)
    scene.collection.objects.link(path)
    return path


def _shape_path(path, terrain, length):
    """A gentle S across the terrain (80 % of its world X extent), or `length` units along X."""
    if terrain is not None:
        corners = np.array([terrain.matrix_world @ Vector(c) for c in terrain.bound_box])
        low, high = corners.min(0), corners.max(0)
        centre, extent, top = (low + high) / 2, high - low, high[2]
        length = 0.8 * extent[0]
        sway = 0.15 * extent[1]
    else:
        centre, top, sway = np.zeros(3), 0.0, 0.1 * length
    curve = path.data
    curve.splines.clear()
    spline = curve.splines.new("BEZIER")
    spline.bezier_points.add(3)
    for index, point in enumerate(spline.bezier_points):
        t = index / 3
        point.co = (centre[0] + (t - 0.5) * length, centre[1] + sway * math.sin(2 * math.pi * t), top)
        point.handle_left_type = point.handle_right_type = "AUTO"


def _new_walker(scene, path):
    # A box standing on its origin: a stand-in for a character.
    x, y, z = (units.to_units(scene, v) for v in (BOX[0] / 2, BOX[1] / 2, BOX[2]))
    verts = [(sx * x, sy * y, sz * z) for sz in (0, 1) for sy in (-1, 1) for sx in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh = bpy.data.meshes.new("Sandscape Walker")
    mesh.from_pydata(verts, [], faces)
    walker = own.mark(bpy.data.objects.new("Sandscape Walker", mesh), own.OBJECT_KEY, own.WALKER)
    scene.collection.objects.link(walker)
    follow = walker.constraints.new("FOLLOW_PATH")
    follow.target = path
    follow.use_curve_follow = True
    follow.use_fixed_location = True
    follow.forward_axis = "FORWARD_X"
    return walker


def _animate(walker, start, end):
    """Offset 0 at the first frame to 1 at the last, linear: an even walking pace."""
    follow = next(c for c in walker.constraints if c.type == "FOLLOW_PATH")
    follow.offset_factor = 0.0
    follow.keyframe_insert("offset_factor", frame=start)
    follow.offset_factor = 1.0
    follow.keyframe_insert("offset_factor", frame=end)
    animation = walker.animation_data
    bag = anim_utils.action_get_channelbag_for_slot(animation.action, animation.action_slot)
    for curve in bag.fcurves:
        # Keys left from an earlier frame range would bend the walk: keep only these two.
        for key in [k for k in curve.keyframe_points if k.co.x not in (start, end)][::-1]:
            curve.keyframe_points.remove(key)
        for key in curve.keyframe_points:
            key.interpolation = "LINEAR"
