"""The stand-in walker: a simple figure in a red cloak on a Follow Path constraint along a gentle
S-shaped curve at a walking pace, the path laid on the evaluated terrain every PATH_STEP, for
artists without a rig. Any animated object works as a walker; this one is only a start.

Both objects are ours (OBJECT_KEY "walker" and "walk_path") and found in the scene the
operator runs in, so running it again updates them and another scene gets its own. Its limbs
swing to the prints' stride (walker_gait).
"""

import itertools
import math

import bmesh
import bpy
import numpy as np
from bpy_extras import anim_utils
from mathutils import Matrix, Vector
from mathutils.bvhtree import BVHTree

from . import evaluation, units, walker_gait
from . import ownership as own
from .footprint_terrain import frame_list, sample_walker

WALK_SPEED = 1.4  # metres per second: a walking pace
PATH_STEP = 0.25  # metres between path points laid on the ground
SWAY = 0.1  # the S reaches a tenth of its length to either side: it turns up to 32 degrees
TERRAIN_SHARE = 0.8  # the walk never leaves the middle 80 % of the terrain (slower if it must)
HEIGHT = 1.7  # metres: a person-sized stand-in
CLOAK = (0.36, 0.03, 0.02, 1.0)  # linear: a red cloak against the sand (the traveller of seed 004)
# Cloth's sheen (weight, roughness): a fabric's soft grazing lobe. It does not rim the figure against
# a low sun ahead (README, the fourth review); whether it pales the cloak is not yet measured.
CLOAK_SHEEN = (1.0, 0.3)
GAIT_KEY = "sandscape_stride"  # on the walker: what its limbs were keyed for
# A robe from the shoulders to below the knees, flaring as the traveller's cloak of seed 004 does
# (a box-like torso over bare legs read as a mannequin): radius at the hem, at the shoulders, the
# hem's height over the soles, and its depth front to back against its width.
ROBE = (0.3, 0.19, 0.5, 0.7)
SHOULDERS = 1.42  # metres over the soles
# 3: the robe and a hood (2: the robe under a bare head on a neck; 1: a torso over the hips)
FIGURE_SHAPE_KEY, FIGURE_SHAPE = "sandscape_figure_shape", 3
HEAD = 0.11  # radius; its top at HEIGHT
HEAD_FORWARD = 0.035  # metres: the face fills the hood's opening
# Above the robe's shoulders, as (height over the soles, radius, depth against width): the
# shoulders slope into a hood rounding the head and ending in a peak that falls back, the
# traveller's of seed 004 (square shoulders and a ball on a neck read as a mannequin).
HOOD = ((1.46, 0.155, 0.8), (1.5, 0.1, 0.95), (1.56, 0.125, 1.0), (1.64, 0.132, 1.0), (1.71, 0.115, 1.0),
        (1.77, 0.075, 1.0), (1.82, 0.02, 1.0))
HOOD_FALL = 0.07  # metres the peak falls back
ROBE_SEGMENTS = 24


def frame_range_problem(start, end):
    if end <= start:
        return f"The frame range {start}..{end} is too short to walk"
    return None


def ensure_walker(scene, terrain, start, end, sway=SWAY):
    """The scene's stand-in walker and its path, made or updated (`sway`: the S's reach to either
    side, a share of its length). Returns (walker, path)."""
    path = own.scene_object(scene, own.WALK_PATH) or _new_path(scene)
    fps = scene.render.fps / scene.render.fps_base
    _shape_path(scene, path, terrain, units.to_units(scene, (end - start) / fps * WALK_SPEED),
                units.to_units(scene, PATH_STEP), sway)
    walker = own.scene_object(scene, own.WALKER)
    if walker is None:
        walker = _new_walker(scene, path)
    elif walker.get(FIGURE_SHAPE_KEY) != FIGURE_SHAPE:  # an older figure's body: the robe replaces it
        cloak = own.slot_material(walker, own.CLOAK)
        walker_gait.swap_mesh(walker, figure_mesh(units.to_units(scene, 1.0)))
        walker.data.materials.append(cloak or _cloak_material())
    walker[FIGURE_SHAPE_KEY] = FIGURE_SHAPE
    _stay_upright(walker)
    _animate(walker, start, end)
    update_stride(scene, walker, start, end)
    return walker, path


def update_stride(scene, walker, start, end):
    """Key the stand-in's limbs to the prints' stride and stance (the scene's footprint settings)."""
    steps, scale = scene.sandscape_footprints, units.to_units(scene, 1.0)
    walker_gait.ensure_limbs(walker, own.slot_material(walker, own.CLOAK), scale, steps.stance)
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


def figure_mesh(scale):
    """A low-poly figure's body standing on its origin facing +X: a robe broader across than deep
    whose shoulders slope into a peaked hood, a head (its limbs are walker_gait's, the legs swinging
    inside the robe and the shins showing below it). `scale`: scene units per metre."""
    hem_radius, shoulder_radius, hem, depth_share = ROBE
    profile = [(hem, hem_radius, depth_share), (SHOULDERS, shoulder_radius, depth_share), *HOOD]
    bm = bmesh.new()
    turn = np.linspace(0.0, 2 * np.pi, ROBE_SEGMENTS, endpoint=False)
    fall_from, peak = HOOD[-3][0], HOOD[-1][0]  # above the head's top the hood falls back
    rings = []
    for height, radius, depth in profile:
        fall = HOOD_FALL * max(0.0, (height - fall_from) / (peak - fall_from))
        ring = np.stack([depth * radius * np.cos(turn) - fall, radius * np.sin(turn),
                         np.full_like(turn, height)])
        rings.append([bm.verts.new(point) for point in ring.T])
    bm.faces.new(rings[0][::-1])  # the hem, facing down
    for low, high in itertools.pairwise(rings):
        for i in range(ROBE_SEGMENTS):
            j = (i + 1) % ROBE_SEGMENTS
            bm.faces.new((low[i], low[j], high[j], high[i]))
    bm.faces.new(rings[-1])  # the peak's small top
    bmesh.ops.create_uvsphere(bm, u_segments=12, v_segments=8, radius=HEAD,
                              matrix=Matrix.Translation((HEAD_FORWARD, 0.0, HEIGHT - HEAD)))
    walker_gait.shade_smooth_but_edges(bm)
    bmesh.ops.scale(bm, vec=(scale, scale, scale), verts=bm.verts)
    mesh = bpy.data.meshes.new("Sandscape Walker")
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def _cloak_material():
    material = own.mark(bpy.data.materials.new("Sandscape Walker Cloak"), own.MATERIAL_KEY, own.CLOAK)
    material.diffuse_color = CLOAK
    nodes = material.node_tree.nodes if material.node_tree else ()
    shader = next((n for n in nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    if shader is not None:
        shader.inputs["Base Color"].default_value = CLOAK
        shader.inputs["Roughness"].default_value = 0.8
        for name, value in zip(("Sheen Weight", "Sheen Roughness"), CLOAK_SHEEN, strict=True):
            shader.inputs[name].default_value = value
    return material


def _new_walker(scene, path):
    mesh = figure_mesh(units.to_units(scene, 1.0))
    walker = own.mark(bpy.data.objects.new("Sandscape Walker", mesh), own.OBJECT_KEY, own.WALKER)
    scene.collection.objects.link(walker)
    walker.data.materials.append(_cloak_material())
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
