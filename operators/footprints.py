"""Operators for footprints: a stand-in walker, emitting prints, painting them into the sand.

They read the scene's Sandscape footprint settings (scene.sandscape_footprints).
"""

import math

import bpy
import numpy as np
from bpy_extras import anim_utils
from mathutils import Vector

from ..blender import footprints

WALKER, WALK_PATH = "walker", "walk_path"
WALK_SPEED = 1.4  # metres per second, a walking pace, for the stand-in when there is no terrain


def settings_problem(scene, settings):
    """An error message for settings that cannot make prints, or None."""
    source = settings.walker if settings.source == "WALKER" else settings.particle_object
    if source is None:
        what = "walker" if settings.source == "WALKER" else "particle emitter"
        return f"No {what}: set one in the Footprints panel (or use Add Walker)"
    terrain = settings.terrain
    if terrain is None:
        return "No terrain: choose the mesh the prints go into"
    if terrain.type != "MESH":
        return f"'{terrain.name}' is a {terrain.type.lower()}, not a mesh"
    if source == terrain:
        return "The walker cannot be the terrain"
    if settings.source == "PARTICLES" and not source.particle_systems:
        return f"'{source.name}' has no particle system"
    start, end = footprints.frame_range(scene, settings)
    if end < start:
        return f"The frame range {start}..{end} is empty"
    checks = (
        (settings.stride > 0, f"Stride must be greater than 0, got {settings.stride:g}"),
        (settings.stance >= 0, f"Stance must be 0 or more, got {settings.stance:g}"),
        (settings.foot_length > 0, f"Foot length must be greater than 0, got {settings.foot_length:g}"),
        (0 < settings.foot_width <= settings.foot_length,
         f"Foot width must be greater than 0 and at most the length, got {settings.foot_width:g}"),
        (settings.depth >= 0 and settings.rim >= 0, "Depth and rim must be 0 or more"),
        (settings.rim_width >= 0, f"Rim width must be 0 or more, got {settings.rim_width:g}"),
        (0 <= settings.variation < 1, f"Variation must lie in [0, 1), got {settings.variation:g}"),
        (0 <= settings.noise_amount <= 1, f"Noise must lie in [0, 1], got {settings.noise_amount:g}"),
        (1 <= settings.resolution <= 16384, f"Resolution must lie in 1..16384, got {settings.resolution}"),
        (settings.dicing_pixel_size > 0, "Dicing must be greater than 0"),
    )
    for ok, message in checks:
        if not ok:  # also False for NaN
            return message
    return None


class _FootprintOperator:
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context, task):
        settings = context.scene.sandscape_footprints
        problem = settings_problem(context.scene, settings)
        if problem:
            self.report({"ERROR"}, problem)
            return {"CANCELLED"}
        window_manager = context.window_manager
        window_manager.progress_begin(0, 100)
        try:
            result = task(context.scene, settings, lambda f: window_manager.progress_update(int(100 * f)))
        except footprints.FootprintError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        finally:
            window_manager.progress_end()
        self.report({"INFO"}, self.summary(result))
        return {"FINISHED"}


class SANDSCAPE_OT_emit_footprints(_FootprintOperator, bpy.types.Operator):
    """Place one print per step along the walker's path, on the terrain (a point object you can edit)"""

    bl_idname = "sandscape.emit_footprints"
    bl_label = "Emit Footprints"

    def execute(self, context):
        return self.run(context, footprints.emit)

    def summary(self, result):
        obj, skipped = result
        off = f", {skipped} off the terrain skipped" if skipped else ""
        return f"Emitted {len(obj.data.vertices)} prints into '{obj.name}'{off}"


class SANDSCAPE_OT_paint_footprints(_FootprintOperator, bpy.types.Operator):
    """Paint the prints into a height image and displace the terrain's sand with it (emits first if needed)"""

    bl_idname = "sandscape.paint_footprints"
    bl_label = "Paint Footprints"

    def execute(self, context):
        return self.run(context, footprints.paint)

    def summary(self, result):
        width, height = result["size"]
        off = f", {result['skipped']} off the terrain skipped" if result["skipped"] else ""
        return (f"Painted {result['prints']} prints{off} into '{result['image'].name}' {width}x{height} "
                f"({result['texel'] * 1000:.2f} mm texels, {result['memory'] / 2**20:.1f} MiB in memory, "
                f"{result['packed'] / 2**20:.2f} MiB packed)")


class SANDSCAPE_OT_add_walker(bpy.types.Operator):
    """Add a stand-in character walking a curve path across the terrain over the frame range"""

    bl_idname = "sandscape.add_walker"
    bl_label = "Add Walker"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        scene = context.scene
        settings = scene.sandscape_footprints
        terrain = settings.terrain
        if terrain is None and context.active_object is not None and context.active_object.type == "MESH":
            terrain = context.active_object
        start, end = footprints.frame_range(scene, settings)
        if end <= start:
            self.report({"ERROR"}, f"The frame range {start}..{end} is too short to walk")
            return {"CANCELLED"}
        path = _find(WALK_PATH) or _new_path(scene)
        _shape_path(path, terrain, (end - start) / scene.render.fps * WALK_SPEED)
        walker = _find(WALKER) or _new_walker(scene, path)
        _animate(walker, start, end)
        settings.walker = walker
        settings.source = "WALKER"
        if terrain is not None:
            settings.terrain = terrain
        self.report({"INFO"}, f"'{walker.name}' walks '{path.name}' over frames {start}..{end}")
        return {"FINISHED"}


def _find(kind):
    return next((obj for obj in bpy.data.objects if obj.get(footprints.OBJECT_KEY) == kind), None)


def _new_path(scene):
    curve = bpy.data.curves.new("Sandscape Walk Path", "CURVE")
    curve.dimensions = "3D"
    path = bpy.data.objects.new("Sandscape Walk Path", curve)
    path[footprints.OBJECT_KEY] = WALK_PATH
    scene.collection.objects.link(path)
    return path


def _shape_path(path, terrain, length):
    """A gentle S across the terrain (80 % of its X extent), or `length` metres along X."""
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
    # A 0.4 x 0.3 x 1.7 m box standing on its origin: a stand-in for a character.
    x, y, z = 0.2, 0.15, 1.7
    verts = [(sx * x, sy * y, sz * z) for sz in (0, 1) for sy in (-1, 1) for sx in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh = bpy.data.meshes.new("Sandscape Walker")
    mesh.from_pydata(verts, [], faces)
    walker = bpy.data.objects.new("Sandscape Walker", mesh)
    walker[footprints.OBJECT_KEY] = WALKER
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


classes = (SANDSCAPE_OT_add_walker, SANDSCAPE_OT_emit_footprints, SANDSCAPE_OT_paint_footprints)
