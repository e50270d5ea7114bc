"""The bpy side of footprints: walk, emit and paint; the print frame and the points object. The
terrain side (finding our data, sampling, dropping prints onto the render triangles) is in
footprint_terrain.py, the print image, patch and cut in footprint_patch.py.

Prints live in world terms: contacts drop straight down (world -Z, gravity) onto the evaluated
terrain in world space, and stride, stance, foot size and depth are world lengths whatever the
terrain's transform (tilted, stretched, a Y-up import). They are painted in the print frame,
an empty that is world-aligned, in world units and at the terrain's origin when the prints are
emitted, and a child of the terrain, so prints ride along when the terrain moves.

Everything we make carries OBJECT_KEY (objects) or IMAGE_KEY (the image) and a pointer to its
terrain (TERRAIN_KEY), found in the operator's scene: re-running updates instead of copying.
"""

import hashlib
import json

import bpy
import numpy as np
from mathutils import Matrix

from ..core import footprints as painter
from ..core import paths
from ..core import sole as sole_shape
from ..node_groups import helper as h
from ..node_groups import print_markers
from . import compat, evaluation, rig_feet, sand, shot, units
from . import ownership as own
from . import walker as stand_in
from .footprint_patch import ensure_cut, ensure_patch, region_box, write_print_image  # noqa: F401
from .footprint_terrain import (  # noqa: F401 (the footprints API)
    FootprintError,
    evaluated_terrain,
    find_cut_modifier,
    find_object,
    find_print_map,
    frame_list,
    frame_world,
    project_down,
    sample_particles,
    sample_walker,
    terrain_problem,
    terrain_uncut,
)

ATTRIBUTES = {  # point attribute name -> (type, meaning)
    "birth_frame": ("FLOAT", "Frame at which the print's foot lands"),
    "heading": ("FLOAT", "Yaw of the print's forward axis about world Z (the print frame's Z), radians"),
    "side": ("INT", "+1 left foot, -1 right foot, 0 unknown (particle source)"),
    "depth_scale": ("FLOAT", "Multiplies the print's depth and rim (seeded variation)"),
    "surface_normal": ("FLOAT_VECTOR", "Terrain normal at the print, in the print frame (world axes)"),
    "size_scale": ("FLOAT", "Multiplies the print's length and width (its walker's Foot Size)"),
    "length_scale": ("FLOAT", "Multiplies the print's length once more (a run's print is longer)"),
    "toe_bias": ("FLOAT", "Depth from x (1 - bias) at the heel to x (1 + bias) at the toe (a run)"),
}
# Of an attribute missing from older or edited points:
DEFAULTS = {"depth_scale": 1, "size_scale": 1, "length_scale": 1}
MARKER_RADIUS = 0.03  # metres: the viewport dots


# ---------------------------------------------------------------- the print frame and the points

def ensure_print_frame(scene, terrain, collection):
    """The terrain's print frame: an empty, world-aligned and unscaled at the terrain's origin,
    a child of the terrain. Its space is where prints are emitted, painted and cut."""
    frame = find_object(scene, own.PRINT_FRAME, terrain)
    if frame is None:
        frame = own.mark(bpy.data.objects.new(f"{terrain.name} Print Frame", None), own.OBJECT_KEY,
                         own.PRINT_FRAME, **{own.TERRAIN_KEY: terrain})
        collection.objects.link(frame)
        frame.empty_display_type = "PLAIN_AXES"
        frame.empty_display_size = units.to_units(scene, 0.25)
        frame.hide_select = True  # it follows the terrain; paint again to realign it
    frame.parent = terrain
    # A full inverse (not loc/rot/scale) cancels any terrain transform, sheared or not.
    placed = evaluation.world_matrix(scene, terrain)
    frame.matrix_parent_inverse = placed.inverted()
    frame.matrix_basis = Matrix.Translation(placed.translation)
    return frame


def write_points(scene, terrain, frame, points, collection):
    """Create or update the footprints object of a terrain: one vertex per print, attributes.

    points: dict of arrays in print-frame space (see ATTRIBUTES, plus "co"). The object is a
    child of the print frame, so its vertices are frame coordinates.
    """
    obj = find_object(scene, own.FOOTPRINTS, terrain)
    if obj is None:
        mesh = bpy.data.meshes.new(f"{terrain.name} Footprints")
        obj = own.mark(bpy.data.objects.new(f"{terrain.name} Footprints", mesh), own.OBJECT_KEY,
                       own.FOOTPRINTS, **{own.TERRAIN_KEY: terrain})
        collection.objects.link(obj)
        modifier = obj.modifiers.new("Print Markers", "NODES")
        modifier.node_group = h.ensure_group(print_markers)
        obj.hide_render = True  # a marker for the artist, never part of the picture
    markers = next((m for m in obj.modifiers if m.type == "NODES"), None)
    if markers is not None:
        compat.set_modifier_input_named(markers, "Radius", units.to_units(scene, MARKER_RADIUS))
    obj.parent = frame
    obj.matrix_parent_inverse.identity()
    obj.matrix_basis.identity()
    mesh = obj.data
    mesh.clear_geometry()
    count = len(points["co"])
    mesh.vertices.add(count)
    mesh.vertices.foreach_set("co", np.ascontiguousarray(points["co"], dtype=np.float32).ravel())
    for name, (kind, _) in ATTRIBUTES.items():
        attribute = mesh.attributes.get(name) or mesh.attributes.new(name, kind, "POINT")
        field = "vector" if kind == "FLOAT_VECTOR" else "value"
        dtype = np.int32 if kind == "INT" else np.float32
        attribute.data.foreach_set(field, np.ascontiguousarray(points[name], dtype=dtype).ravel())
    mesh.update()
    return obj


def read_points(obj):
    """The prints as the artist left them (positions and attributes may have been edited)."""
    mesh = obj.data
    count = len(mesh.vertices)
    out = {"co": np.empty(count * 3, np.float32)}
    mesh.vertices.foreach_get("co", out["co"])
    out["co"] = out["co"].reshape(-1, 3).astype(np.float64)
    for name, (kind, _) in ATTRIBUTES.items():
        attribute = mesh.attributes.get(name)
        width = 3 if kind == "FLOAT_VECTOR" else 1
        values = np.empty(count * width, np.int32 if kind == "INT" else np.float32)
        if attribute is None:
            values[:] = DEFAULTS.get(name, 0)
            if name == "surface_normal":
                values.reshape(-1, 3)[:] = (0, 0, 1)
        else:
            attribute.data.foreach_get("vector" if width == 3 else "value", values)
        out[name] = values.reshape(-1, 3).astype(np.float64) if width == 3 else values.astype(np.float64)
    return out


def print_axes(points):
    """Forward and lateral axes of each print, projected onto the frame's XY plane: (N, 2) each,
    the lateral one toward the foot's inner side (core.paths.print_axes)."""
    heading = points["heading"]
    forward = np.stack([np.cos(heading), np.sin(heading), np.zeros_like(heading)], axis=1)
    return paths.print_axes(forward, points["surface_normal"], points["side"])


# ---------------------------------------------------------------- emit and paint

def sole_from(settings):
    """A foot's sole in dry sand at the set depth, in scene units (core.sole.dry_sand_sole)."""
    return sole_shape.dry_sand_sole(settings.depth, settings.foot_length, settings.foot_width,
                                    settings.rim_width)


def frame_range(scene, settings):
    if settings.use_scene_range:
        return scene.frame_start, scene.frame_end
    return settings.frame_start, settings.frame_end


def is_animated(obj):
    while obj is not None:
        if obj.animation_data is not None or obj.constraints:
            return True
        obj = obj.parent
    return False


def _stage(progress, low, high):
    """A progress callback for one stage, mapping its 0..1 onto low..high of the whole bar."""
    if progress is None:
        return None
    return lambda fraction: progress(low + (high - low) * fraction)


def _digest(*arrays):
    sha = hashlib.sha1()
    for array in arrays:
        sha.update(np.ascontiguousarray(array, dtype=np.float64).round(7).tobytes())
    return sha.hexdigest()


STEP_KEYS = ("contact", "birth", "forward", "side", "depth", "stretch", "toe")


def _walker_steps(scene, settings, walker, chosen, frames, progress=None, stride_scale=1.0):
    """(steps, motion) of one walker: where a rig's feet land, else its path's stride. steps
    carries each print's "depth" multiplier from how hard it landed, and "stretch" and "toe" (its
    length scale and toe bias) from how long the foot stayed down: a run's print is longer and
    deepest at the toe (a path's prints: 1, 1, 0)."""
    terrain = settings.terrain
    start, end = frames[0], frames[-1]
    if not is_animated(walker):
        raise FootprintError(f"'{walker.name}' is not animated: give it keyframes, a Follow Path "
                             "constraint or an animated parent, or use Add Walker")
    armature = rig_feet.armature_of(walker)
    try:
        steps = rig_feet.steps(scene, armature, terrain, frames, chosen) if armature is not None else None
    except rig_feet.core_contacts.ContactError as error:
        raise FootprintError(str(error)) from error
    if steps is not None:  # a rig: one print where each foot lands
        if not len(steps["birth"]):
            raise FootprintError(f"'{walker.name}': no foot touches '{terrain.name}' in {start}..{end} "
                                 "(a foot lands when its sole comes within a tenth of its length "
                                 "of the ground and nearly stops)")
        # A harder landing presses deeper, against this walker's usual strike.
        strike = np.asarray(steps["strike"], np.float64)
        steps["depth"] = np.clip(np.sqrt(strike / max(float(np.median(strike)), 1e-6)), 0.8, 1.4)
        steps["stretch"], steps["toe"] = rig_feet.core_contacts.gait_shape(np.asarray(steps["seconds"]))
        return steps, np.c_[steps["contact"], steps["birth"], steps["strike"]]
    positions = sample_walker(scene, walker, frames, progress)
    try:
        steps = paths.plan_steps(positions, frames, settings.stride * stride_scale,
                                 settings.stance * stride_scale, toe_out=paths.TOE_OUT)
    except paths.PathError as error:
        # Blender does not evaluate a walker hidden in the viewport: its motion is not played.
        hidden = walker.hide_viewport or not walker.visible_get(view_layer=evaluation.scene_view_layer(scene))
        why = "; it is hidden in the viewport, where Blender does not move it: unhide it" if hidden else ""
        raise FootprintError(f"'{walker.name}': {error} ({start}..{end}){why}") from error
    steps["birth"] = steps["landing"]  # a print appears as its foot lands, as a rig's does
    steps["depth"], steps["stretch"] = np.ones(len(steps["birth"])), np.ones(len(steps["birth"]))
    steps["toe"] = np.zeros(len(steps["birth"]))
    steps["how"] = "along its path"
    return steps, positions


def walk(scene, settings, progress=None):
    """Sample the source over the frame range, and everything the prints depend on.

    Returns a dict: the steps (world contacts, forward, side, births), the terrain's evaluated
    world geometry, and "signature", a text of all of it: paint re-emits when it changed (the
    walker's motion, the terrain's transform or geometry, or a walk setting).
    Raises FootprintError before touching any data.
    """
    terrain = settings.terrain
    start, end = frame_range(scene, settings)
    frames = frame_list(start, end)
    if settings.source == "WALKER":
        walkers = [(settings.walker, 1.0, 1.0, (settings.left_foot, settings.right_foot), 1.0)]
        walkers += [(entry.walker, entry.foot_scale, entry.depth_scale, (entry.left_foot, entry.right_foot),
                     entry.stride_scale) for entry in settings.more_walkers if entry.walker is not None]
        found = [_walker_steps(scene, settings, walker, chosen, frames, progress, stride)
                 for walker, _, _, chosen, stride in walkers]
        steps = {key: np.concatenate([one[key] for one, _ in found]) for key in STEP_KEYS}
        steps["size"] = np.concatenate([np.full(len(one["birth"]), size)
                                        for (one, _), (_, size, *_) in zip(found, walkers, strict=True)])
        steps["depth"] = np.concatenate([one["depth"] * depth
                                         for (one, _), (_, _, depth, *_) in zip(found, walkers, strict=True)])
        steps["how"] = "; ".join(f"'{walker.name}' {one['how']}"
                                 for (one, _), (walker, *_) in zip(found, walkers, strict=True))
        motion = np.concatenate([np.ravel(m) for _, m in found]
                                + [np.ravel([(w[1], w[2], w[4]) for w in walkers])])
    else:
        contacts, births, forward = sample_particles(scene, settings.particle_object, frames)
        if len(contacts) == 0:
            raise FootprintError(f"'{settings.particle_object.name}' emits no particles in "
                                 f"{start}..{end}")
        steps = {"contact": contacts, "birth": births, "forward": forward,
                 "side": np.zeros(len(contacts), np.int32), "depth": np.ones(len(contacts)),
                 "size": np.ones(len(contacts)), "stretch": np.ones(len(contacts)),
                 "toe": np.zeros(len(contacts))}
        motion = np.concatenate([contacts, births[:, None]], axis=1)
    vertices, triangles = evaluated_terrain(scene, terrain)
    source = settings.walker if settings.source == "WALKER" else settings.particle_object
    # The source and terrain by identity, not name: renaming either keeps the prints (the points
    # object names its terrain by pointer; the source is kept beside the signature).
    inputs = {"source": settings.source, "start": start,
              "end": end, "stride": settings.stride, "stance": settings.stance,
              "variation": settings.variation, "seed": settings.seed, "motion": _digest(motion),
              "placement": _digest(np.array(evaluation.world_matrix(scene, terrain)), vertices)}
    return {"steps": steps, "vertices": vertices, "triangles": triangles, "source": source,
            "signature": json.dumps(inputs, sort_keys=True, default=str)}


def emit(scene, settings, progress=None, walked=None):
    """Walk the source over the frame range, drop prints onto the terrain, write the points.

    Raises FootprintError before touching any data. Returns (points object, skipped count).
    """
    walked = walked or walk(scene, settings, _stage(progress, 0.0, 0.5))
    terrain, steps = settings.terrain, walked["steps"]
    hits, normals, landed = project_down(walked["vertices"], walked["triangles"], steps["contact"],
                                         _stage(progress, 0.5, 1.0))
    if not landed.any():
        raise FootprintError(f"No print lands on '{terrain.name}': the walk never crosses it")
    collection = terrain.users_collection[0] if terrain.users_collection else scene.collection
    frame = ensure_print_frame(scene, terrain, collection)
    origin = np.array(frame_world(scene, frame).translation)
    forward = np.asarray(steps["forward"], dtype=np.float64)
    rng = np.random.default_rng(settings.seed)
    scale = (1.0 + settings.variation * rng.uniform(-1.0, 1.0, len(hits))) * np.asarray(steps["depth"])
    points = {"co": hits[landed] - origin, "birth_frame": np.asarray(steps["birth"])[landed],
              "heading": np.arctan2(forward[landed, 1], forward[landed, 0]),
              "side": np.asarray(steps["side"])[landed], "depth_scale": scale[landed],
              "size_scale": np.asarray(steps["size"], np.float64)[landed],
              "length_scale": np.asarray(steps["stretch"], np.float64)[landed],
              "toe_bias": np.asarray(steps["toe"], np.float64)[landed],
              "surface_normal": normals[landed]}
    obj = write_points(scene, terrain, frame, points, collection)
    obj["emitted_from"] = walked["signature"]
    obj["walked"] = steps.get("how", "")
    obj["emitted_source"] = walked["source"]
    obj["skipped"] = int((~landed).sum())
    return obj, int((~landed).sum())


def paint(scene, settings, progress=None):
    """Emit if anything the prints depend on changed (or nothing was emitted), then paint, store
    and wire up. Returns a dict of what was done, for the report.
    """
    terrain = settings.terrain
    walked = walk(scene, settings, _stage(progress, 0.0, 0.4))
    figure = settings.walker if settings.source == "WALKER" else None
    if stand_in.needs_new_stride(scene, figure, *frame_range(scene, settings)):
        stand_in.update_stride(scene, figure, *frame_range(scene, settings))  # its feet on its prints
    points_obj = find_object(scene, own.FOOTPRINTS, terrain)
    frame = find_object(scene, own.PRINT_FRAME, terrain)
    emitted = (points_obj is None or frame is None or points_obj.get("emitted_from") != walked["signature"]
               or points_obj.get("emitted_source") != walked["source"])
    if emitted:
        points_obj, _ = emit(scene, settings, _stage(progress, 0.4, 0.6), walked)
        frame = find_object(scene, own.PRINT_FRAME, terrain)
    points = read_points(points_obj)
    if len(points["co"]) == 0:
        raise FootprintError(f"'{points_obj.name}' holds no prints to paint")
    sole = sole_from(settings)
    centres = points["co"][:, :2]
    sizes = np.where(points["size_scale"] > 0, points["size_scale"], np.nan)  # 0: the print is skipped
    lengths = np.where(points["length_scale"] > 0, points["length_scale"], np.nan)
    reach = sole.reach() * float(np.nanmax(sizes * np.maximum(lengths, 1.0), initial=1.0))
    region = painter.fit_region(centres, reach, settings.resolution,
                                margin=units.to_units(scene, 0.05) + sole.rim_width)
    forward, lateral = print_axes(points)
    # Longer axes make a larger print: the painter reads offsets through their inverse.
    forward, lateral = forward * (sizes * lengths)[:, None], lateral * sizes[:, None]
    start, end = frame_range(scene, settings)
    pixels = painter.paint(centres, forward, lateral, points["birth_frame"], points["depth_scale"], region,
                           sole, (start, end), toe_bias=points["toe_bias"])
    if progress:
        progress(0.9)
    image = write_print_image(scene, terrain, pixels, region, (start, end))
    material = sand.find_sand_material(terrain)
    added_material = material is None
    if added_material:
        material = sand.assign_new_material(terrain)
        sand.update_material(material, sand.default_glint_values(), ripple_values=sand.default_ripples(scene),
                             scene=scene)
    sand.attach_footprints(material, image, frame, {
        "Depth": settings.depth, "Rim": settings.rim, "Frame Start": float(start), "Frame End": float(end),
        "Noise Amount": settings.noise_amount, "Noise Scale": 40.0 * units.metres_per_unit(scene),
        "Refill Time": settings.refill_time * shot.frames_per_second(scene),
        "Wind": tuple(scene.sandscape_atmosphere.wind)})
    low, high = region_box(image)
    collection = terrain.users_collection[0] if terrain.users_collection else scene.collection
    patch, (low, high) = ensure_patch(scene, terrain, frame, low, high, collection,
                                      settings.dicing_pixel_size)
    ensure_cut(terrain, frame, low, high)
    return {"prints": len(points["co"]), "skipped": int(points_obj.get("skipped", 0)), "emitted": emitted,
            "image": image, "size": (region.width, region.height), "texel": region.texel,
            "memory": pixels.nbytes, "packed": image.packed_file.size, "patch": patch,
            "added_material": added_material}
