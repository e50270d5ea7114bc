"""The stand-in walker: a simple figure in a red cloak on a Follow Path constraint along a gentle
S-shaped curve at a walking pace, the path laid on the evaluated terrain every PATH_STEP, for
artists without a rig. Any animated object works as a walker; this one is only a start.

Both objects are ours (OBJECT_KEY "walker" and "walk_path") and found in the scene the
operator runs in, so running it again updates them and another scene gets its own. Its limbs
swing to the prints' stride (walker_gait).
"""

import math

import bpy
import numpy as np
from bpy_extras import anim_utils
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from . import evaluation, shot, units, walker_figure, walker_flutter, walker_gait, walker_wind
from . import ownership as own
from .footprint_terrain import frame_list, sample_walker

WALK_SPEED = 1.4  # metres per second: a walking pace
PATH_STEP = 0.25  # metres between path points laid on the ground
SWAY = 0.1  # the S reaches a tenth of its length to either side: it turns up to 32 degrees
TERRAIN_SHARE = 0.8  # the walk never leaves the middle 80 % of the terrain (slower if it must)
GAIT_KEY = "sandscape_stride"  # on the walker: what its limbs were keyed for


def frame_range_problem(start, end):
    if end <= start:
        return f"The frame range {start}..{end} is too short to walk"
    return None


def ensure_walker(scene, terrain, start, end, sway=SWAY):
    """The scene's stand-in walker and its path, made or updated (`sway`: the S's reach to either
    side, a share of its length). Returns (walker, path)."""
    path = own.scene_object(scene, own.WALK_PATH) or _new_path(scene)
    fps = shot.frames_per_second(scene)
    _shape_path(scene, path, terrain, units.to_units(scene, (end - start) / fps * WALK_SPEED),
                units.to_units(scene, PATH_STEP), sway)
    walker = own.scene_object(scene, own.WALKER)
    if walker is None:
        walker = _new_walker(scene, path)
    elif walker.get(walker_figure.FIGURE_SHAPE_KEY) != walker_figure.FIGURE_SHAPE:
        # an older figure's body: this one replaces it, in the materials it wore
        cloth = walker_figure.Cloth(walker)
        walker_figure.add_fold_shading(cloth[own.CLOAK])  # the new body's folds, shaded as a new cloak's
        walker_gait.swap_mesh(walker, walker_figure.figure_mesh(units.to_units(scene, 1.0)))
        walker_figure.dress(walker, cloth)
    walker[walker_figure.FIGURE_SHAPE_KEY] = walker_figure.FIGURE_SHAPE
    walker_wind.ensure(scene, walker, path.data.splines[0].calc_length() / ((end - start) / fps), start, end)
    walker_flutter.ensure(walker, units.to_units(scene, 1.0))
    _stay_upright(walker)
    _animate(walker, start, end)
    update_stride(scene, walker, start, end)
    return walker, path


def update_stride(scene, walker, start, end):
    """Key the stand-in's limbs to the prints' stride and stance (the scene's footprint settings)."""
    steps, scale = scene.sandscape_footprints, units.to_units(scene, 1.0)
    walker_gait.ensure_limbs(walker, walker_figure.Cloth(walker), scale, steps.stance)
    frames = frame_list(start, end)
    walker_gait.key_stride(walker, sample_walker(scene, walker, frames), frames, steps.stride, scale)
    walker[GAIT_KEY] = stride_keyed_for(scene, start, end)


def stride_keyed_for(scene, start, end):
    """What the limbs' keys depend on besides the walk itself: paint re-keys when it changed."""
    steps = scene.sandscape_footprints
    return [float(steps.stride), float(steps.stance), float(start), float(end)]


def needs_new_stride(scene, walker, start, end):
    """Our stand-in, keyed for another stride, stance or frame range."""
    return (walker is not None and walker.get(own.OBJECT_KEY) == own.WALKER
            and list(walker.get(GAIT_KEY, [])) != stride_keyed_for(scene, start, end))


def _new_path(scene):
    curve = bpy.data.curves.new("Sandscape Walk Path", "CURVE")
    curve.dimensions = "3D"
    path = own.mark(bpy.data.objects.new("Sandscape Walk Path", curve), own.OBJECT_KEY, own.WALK_PATH)
    scene.collection.objects.link(path)
    return path


def _shape_path(scene, path, terrain, length, step, sway_share):
    """A gentle S `length` units along X through the terrain's middle (at most TERRAIN_SHARE of
    its world X extent), or through the origin without a terrain."""
    centre, top = np.zeros(3), 0.0
    if terrain is not None:
        corners = np.array([terrain.matrix_world @ Vector(c) for c in terrain.bound_box])
        low, high = corners.min(0), corners.max(0)
        centre, extent, top = (low + high) / 2, high - low, high[2]
        length = min(length, TERRAIN_SHARE * extent[0])
    sway = sway_share * length
    count = 4 if terrain is None else max(4, int(math.ceil(length / step)) + 1)
    t = np.linspace(0.0, 1.0, count)
    points = np.stack([centre[0] + (t - 0.5) * length, centre[1] + sway * np.sin(2 * math.pi * t),
                       np.full(count, top)], axis=-1)
    if terrain is not None:
        points[:, 2] = ground_heights(scene, terrain, points[:, :2], top)
    curve = path.data
    curve.splines.clear()
    spline = curve.splines.new("BEZIER")
    spline.bezier_points.add(count - 1)
    for point, co in zip(spline.bezier_points, points, strict=True):
        point.co = tuple(co)
        point.handle_left_type = point.handle_right_type = "AUTO"


def ground_heights(scene, terrain, xy, top):
    """World Z of the terrain's evaluated surface under each (x, y), cast down from above `top`
    (its highest point); the original mesh where the evaluated one has none (the footprint cut
    leaves a hole where the patch takes over), else `top`. The walk path is laid on these, so
    the stand-in's feet touch the ground."""
    evaluated = terrain.evaluated_get(evaluation.scene_depsgraph(scene))
    world = np.array(terrain.matrix_world)
    to_local = np.linalg.inv(world)
    down = Vector(to_local[:3, :3] @ np.array([0.0, 0.0, -1.0]))
    original = None  # built only when a ray falls through a hole
    heights = np.full(len(xy), float(top))
    for index, (x, y) in enumerate(xy):
        origin = Vector((to_local @ np.array([x, y, top + 1.0, 1.0]))[:3])
        hit, location, *_ = evaluated.ray_cast(origin, down)
        if not hit:
            if original is None:  # Blender's own triangles, as rendered
                local, triangles = evaluation.mesh_triangles(terrain.data)
                original = BVHTree.FromPolygons([Vector(v) for v in local], triangles.tolist())
            location, *_ = original.ray_cast(origin, down)
            hit = location is not None
        if hit:
            heights[index] = (world @ np.r_[location[:], 1.0])[2]
    return heights


def _new_walker(scene, path):
    mesh = walker_figure.figure_mesh(units.to_units(scene, 1.0))
    walker = own.mark(bpy.data.objects.new("Sandscape Walker", mesh), own.OBJECT_KEY, own.WALKER)
    scene.collection.objects.link(walker)
    walker_figure.dress(walker, walker_figure.Cloth(walker))
    follow = walker.constraints.new("FOLLOW_PATH")
    follow.target = path
    follow.use_curve_follow = True
    follow.use_fixed_location = True
    follow.forward_axis = "FORWARD_X"
    return walker


def _stay_upright(walker):
    """A walker turns along the path but stands upright on a slope (the path follows the dunes)."""
    upright = next((c for c in walker.constraints if c.type == "LIMIT_ROTATION"), None)
    if upright is None:
        upright = walker.constraints.new("LIMIT_ROTATION")
        upright.name = "Sandscape Stand Upright"
    upright.use_limit_x = upright.use_limit_y = True
    upright.min_x = upright.max_x = upright.min_y = upright.max_y = 0.0
    upright.owner_space = "WORLD"


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
