"""The bpy side of footprints: sample the walker, project prints onto the terrain, keep the
points object, the print image, the patch object and the terrain's cut modifier.

Everything we make carries OBJECT_KEY (objects) or images.IMAGE_KEY (the image) plus a
pointer to its terrain, so re-running finds and updates it instead of adding copies.
"""

import contextlib
import json
import os
import tempfile

import bmesh
import bpy
import numpy as np
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from ..core import footprints as painter
from ..core import paths
from ..node_groups import helper as h
from ..node_groups import print_markers, region_cut
from . import compat, images
from . import sand as sand_material

OBJECT_KEY = "sandscape_object"
TERRAIN_KEY = "sandscape_terrain"
POINTS, PATCH = "footprints", "footprint_patch"
PRINT_MAP = "print_map"
ATTRIBUTES = {  # point attribute name -> (type, meaning)
    "birth_frame": ("FLOAT", "Frame at which the walker passes the print"),
    "heading": ("FLOAT", "Yaw of the print's forward axis about the terrain's Z, radians"),
    "side": ("INT", "+1 left foot, -1 right foot, 0 unknown (particle source)"),
    "depth_scale": ("FLOAT", "Multiplies the print's depth and rim (seeded variation)"),
    "surface_normal": ("FLOAT_VECTOR", "Terrain normal at the print, terrain object space"),
}


class FootprintError(ValueError):
    """Input that cannot make footprints; the message is for the artist."""


# ---------------------------------------------------------------- finding our data

def find_object(kind, terrain):
    for obj in bpy.data.objects:
        if obj.get(OBJECT_KEY) == kind and obj.get(TERRAIN_KEY) == terrain:
            return obj
    return None


def find_print_map(terrain):
    for image in bpy.data.images:
        if image.get(images.IMAGE_KEY) == PRINT_MAP and image.get(TERRAIN_KEY) == terrain:
            return image
    return None


def find_cut_modifier(terrain):
    for modifier in terrain.modifiers:
        group = getattr(modifier, "node_group", None)
        if modifier.type == "NODES" and group is not None and group.get(h.GROUP_KEY) == region_cut.NAME:
            return modifier
    return None


@contextlib.contextmanager
def terrain_uncut(terrain):
    """The terrain as the artist made it: our cut modifier off while we sample it."""
    modifier = find_cut_modifier(terrain)
    state = None if modifier is None else (modifier.show_viewport, modifier.show_render)
    if modifier is not None:
        modifier.show_viewport = modifier.show_render = False
    try:
        yield
    finally:
        if modifier is not None:
            modifier.show_viewport, modifier.show_render = state


# ---------------------------------------------------------------- sampling the scene

def frame_list(frame_start, frame_end):
    if frame_end < frame_start:
        raise FootprintError(f"The frame range {frame_start}..{frame_end} is empty")
    return np.arange(frame_start, frame_end + 1, dtype=np.float64)


def sample_walker(scene, walker, frames, progress=None):
    """World positions of the walker's evaluated matrix_world at each frame: (F, 3)."""
    kept = scene.frame_current
    positions = np.empty((len(frames), 3))
    try:
        for index, frame in enumerate(frames):
            scene.frame_set(int(frame))
            positions[index] = walker.matrix_world.translation
            if progress:
                progress(index / len(frames))
    finally:
        scene.frame_set(kept)
    return positions


def sample_particles(scene, emitter, frames):
    """Each particle where it is born: positions (M, 3), birth frames, directions of travel."""
    kept = scene.frame_current
    found_positions, found_births, found_directions = [], [], []
    previous = None
    try:
        for frame in frames:
            scene.frame_set(int(frame))
            depsgraph = bpy.context.evaluated_depsgraph_get()
            evaluated = emitter.evaluated_get(depsgraph)
            if not evaluated.particle_systems:
                raise FootprintError(f"'{emitter.name}' has no particle system")
            particles = evaluated.particle_systems[0].particles
            count = len(particles)
            state = np.empty(count, np.int32)
            birth = np.empty(count, np.float32)
            location = np.empty(count * 3, np.float32)
            velocity = np.empty(count * 3, np.float32)
            particles.foreach_get("alive_state", state)
            particles.foreach_get("birth_time", birth)
            particles.foreach_get("location", location)
            particles.foreach_get("velocity", velocity)
            # Born during this frame step (the first frame takes everything born so far).
            newborn = (state == 3) & (birth <= frame) & ((birth > frame - 1) | (frame == frames[0]))
            here = np.array(emitter.matrix_world.translation)
            motion = here - previous if previous is not None else np.zeros(3)
            previous = here
            direction = velocity.reshape(-1, 3)[newborn]
            still = np.linalg.norm(direction[:, :2], axis=1) < 1e-9
            direction[still] = motion
            found_positions.append(location.reshape(-1, 3)[newborn])
            found_births.append(birth[newborn])
            found_directions.append(direction)
    finally:
        scene.frame_set(kept)
    return tuple(np.concatenate(found).astype(np.float64)
                 for found in (found_positions, found_births, found_directions))


def project_onto_terrain(terrain, contacts_world, progress=None):
    """Ray cast each contact straight down (terrain -Z) onto the evaluated terrain.

    Returns terrain-local hit points (N, 3), unit normals (N, 3) and a hit mask (N,).
    Rays start above the terrain's bounding box, so the topmost surface is found.
    """
    depsgraph = bpy.context.evaluated_depsgraph_get()
    with terrain_uncut(terrain):
        depsgraph.update()
        evaluated = terrain.evaluated_get(depsgraph)
        bvh = BVHTree.FromObject(evaluated, depsgraph)
        top = max(corner[2] for corner in evaluated.bound_box) + 1.0
    depsgraph.update()
    inverse = np.array(terrain.matrix_world.inverted())
    contacts = np.asarray(contacts_world, dtype=np.float64)
    local = contacts @ inverse[:3, :3].T + inverse[:3, 3]
    hits = np.full((len(local), 3), np.nan)
    normals = np.full((len(local), 3), np.nan)
    down = Vector((0.0, 0.0, -1.0))
    for index, (x, y, _) in enumerate(local):
        location, normal, _, _ = bvh.ray_cast(Vector((x, y, top)), down)
        if location is not None:
            hits[index] = location
            normals[index] = normal if normal.z >= 0 else -normal
        if progress and index % 4096 == 0:
            progress(index / max(len(local), 1))
    return hits, normals, ~np.isnan(hits[:, 0])


def local_directions(terrain, directions_world):
    rotation = np.array(terrain.matrix_world.inverted().to_3x3())
    return np.asarray(directions_world) @ rotation.T


# ---------------------------------------------------------------- the points object

def write_points(terrain, points, collection):
    """Create or update the footprints object of a terrain: one vertex per print, attributes.

    points: dict of arrays, all in terrain object space (see ATTRIBUTES, plus "co").
    """
    obj = find_object(POINTS, terrain)
    if obj is None:
        mesh = bpy.data.meshes.new(f"{terrain.name} Footprints")
        obj = bpy.data.objects.new(f"{terrain.name} Footprints", mesh)
        obj[OBJECT_KEY] = POINTS
        obj[TERRAIN_KEY] = terrain
        collection.objects.link(obj)
        modifier = obj.modifiers.new("Print Markers", "NODES")
        modifier.node_group = h.ensure_group(print_markers)
        obj.hide_render = True  # a marker for the artist, never part of the picture
    obj.parent = terrain
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
            values[:] = {"birth_frame": 0, "heading": 0, "side": 0, "depth_scale": 1}.get(name, 0)
            if name == "surface_normal":
                values.reshape(-1, 3)[:] = (0, 0, 1)
        else:
            attribute.data.foreach_get("vector" if width == 3 else "value", values)
        out[name] = values.reshape(-1, 3).astype(np.float64) if width == 3 else values.astype(np.float64)
    return out


def print_axes(points):
    """Forward and lateral axes of each print, projected onto the terrain's XY plane: (N, 2) each."""
    heading = points["heading"]
    forward = np.stack([np.cos(heading), np.sin(heading), np.zeros_like(heading)], axis=1)
    forward, lateral = paths.surface_frames(forward, points["surface_normal"])
    return forward[:, :2], lateral[:, :2]


# ---------------------------------------------------------------- the print image

def write_print_image(terrain, pixels, region, frame_range):
    """Store the painted RGBA floats as our packed, ZIP-compressed 32-bit EXR image.

    Custom properties on the image record the region in the terrain's object space.
    """
    image = find_print_map(terrain)
    height, width = pixels.shape[:2]
    scratch = bpy.data.images.new("Sandscape Print Scratch", width, height, alpha=True, float_buffer=True)
    scratch.colorspace_settings.name = "Non-Color"
    scratch.pixels.foreach_set(pixels.ravel())
    settings = bpy.context.scene.render.image_settings
    kept = (settings.file_format, settings.color_depth, settings.exr_codec, settings.color_mode)
    handle, path = tempfile.mkstemp(suffix=".exr", prefix="sandscape-prints-")
    os.close(handle)
    try:
        settings.file_format, settings.color_mode = "OPEN_EXR", "RGBA"
        settings.color_depth, settings.exr_codec = "32", "ZIP"
        scratch.save_render(path, scene=bpy.context.scene)
        if image is None:
            image = bpy.data.images.load(path, check_existing=False)
            image.name = f"{terrain.name} Print Map"
            image[images.IMAGE_KEY] = PRINT_MAP
            image[TERRAIN_KEY] = terrain
        else:
            if image.packed_file:
                image.unpack(method="REMOVE")
            image.source = "FILE"
            image.filepath = path
            image.reload()
        image.colorspace_settings.name = "Non-Color"
        image.alpha_mode = "CHANNEL_PACKED"
        image.pack()
        image.filepath = f"//{terrain.name}_prints.exr"
        image.use_fake_user = True  # survives a save even while no material uses it
    finally:
        settings.file_format, settings.color_depth, settings.exr_codec, settings.color_mode = kept
        bpy.data.images.remove(scratch)
        os.remove(path)
    low_x, low_y = region.x0, region.y0
    image["region_min"] = (low_x, low_y)
    image["region_size"] = region.extent()
    image["texel"] = region.texel
    image["frame_range"] = tuple(float(f) for f in frame_range)
    return image


# ---------------------------------------------------------------- patch and cut

def region_box(image, margin):
    """The X-Y box, terrain object space, that the patch covers and the terrain loses."""
    low = np.array(image["region_min"]) - margin
    high = low + np.array(image["region_size"]) + 2 * margin
    return low, high


def ensure_patch(terrain, low, high, collection, pixel_size=1.0):
    """Our patch object: the terrain's faces over the region, adaptively subdivided.

    The terrain keeps its other faces (a Region Cut modifier hides these), so dicing
    stays where prints are. Subdivision is SIMPLE: a smoothing scheme would move the
    patch's boundary away from the coarse terrain's edges and open a crack.
    Returns the patch object, or None when no face of the terrain lies in the region.
    """
    depsgraph = bpy.context.evaluated_depsgraph_get()
    with terrain_uncut(terrain):
        depsgraph.update()
        mesh = bpy.data.meshes.new_from_object(terrain.evaluated_get(depsgraph), depsgraph=depsgraph)
    depsgraph.update()
    centres = np.empty(len(mesh.polygons) * 3, np.float32)
    mesh.polygons.foreach_get("center", centres)
    keep = painter.faces_in_region(centres.reshape(-1, 3), low, high)
    patch = find_object(PATCH, terrain)
    if not keep.any():
        bpy.data.meshes.remove(mesh)
        if patch is not None:
            bpy.data.objects.remove(patch)
        return None
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bm.faces.ensure_lookup_table()
    bmesh.ops.delete(bm, geom=[bm.faces[i] for i in np.flatnonzero(~keep)], context="FACES")
    bm.to_mesh(mesh)
    bm.free()
    mesh.name = f"{terrain.name} Footprint Patch"
    if patch is None:
        patch = bpy.data.objects.new(f"{terrain.name} Footprint Patch", mesh)
        patch[OBJECT_KEY] = PATCH
        patch[TERRAIN_KEY] = terrain
        collection.objects.link(patch)
        subdivision = patch.modifiers.new("Adaptive Subdivision", "SUBSURF")
        subdivision.subdivision_type = "SIMPLE"
        subdivision.use_adaptive_subdivision = True
        subdivision.adaptive_space = "PIXEL"
        subdivision.levels = 0  # the viewport shows the coarse patch; Cycles dices it
    else:
        old = patch.data
        patch.data = mesh
        if old.users == 0:
            bpy.data.meshes.remove(old)
    patch.modifiers["Adaptive Subdivision"].adaptive_pixel_size = pixel_size
    patch.parent = terrain
    patch.matrix_parent_inverse.identity()
    patch.matrix_basis.identity()
    patch.hide_select = True  # it follows the terrain; edit the terrain and paint again
    return patch


def ensure_cut(terrain, low, high):
    modifier = find_cut_modifier(terrain)
    if modifier is None:
        modifier = terrain.modifiers.new("Sandscape Footprint Cut", "NODES")
        modifier.node_group = h.ensure_group(region_cut)
    identifiers = {item.name: item.identifier for item in modifier.node_group.interface.items_tree
                   if item.item_type == "SOCKET" and item.in_out == "INPUT"}
    compat.set_modifier_input(modifier, identifiers["Min"], (float(low[0]), float(low[1]), -1e30))
    compat.set_modifier_input(modifier, identifiers["Max"], (float(high[0]), float(high[1]), 1e30))
    return modifier


# ---------------------------------------------------------------- emit signature

def signature(settings_values):
    """A stable text of the emit inputs: paint re-emits when they changed."""
    return json.dumps(settings_values, sort_keys=True, default=str)


# ---------------------------------------------------------------- emit and paint

def sole_from(settings):
    return painter.Sole(length=settings.foot_length, width=settings.foot_width,
                        rim_width=settings.rim_width)


def frame_range(scene, settings):
    if settings.use_scene_range:
        return scene.frame_start, scene.frame_end
    return settings.frame_start, settings.frame_end


def emit_inputs(scene, settings):
    """What the prints depend on; stored on the points object to tell when to re-emit."""
    start, end = frame_range(scene, settings)
    source = settings.walker if settings.source == "WALKER" else settings.particle_object
    return {"source": settings.source, "object": source.name if source else "",
            "terrain": settings.terrain.name, "start": start, "end": end, "stride": settings.stride,
            "stance": settings.stance, "variation": settings.variation, "seed": settings.seed}


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


def emit(scene, settings, progress=None):
    """Walk the source over the frame range, project prints onto the terrain, write the points.

    Raises FootprintError before touching any data. Returns (points object, skipped count).
    """
    terrain = settings.terrain
    start, end = frame_range(scene, settings)
    frames = frame_list(start, end)
    if settings.source == "WALKER":
        walker = settings.walker
        if not is_animated(walker):
            raise FootprintError(f"'{walker.name}' is not animated: give it keyframes, a Follow Path "
                                 "constraint or an animated parent, or use Add Walker")
        positions = sample_walker(scene, walker, frames, _stage(progress, 0.0, 0.5))
        try:
            steps = paths.plan_steps(positions, frames, settings.stride, settings.stance)
        except paths.PathError as error:
            raise FootprintError(f"'{walker.name}': {error} ({start}..{end})") from error
        contacts, forward, side, births = steps["contact"], steps["forward"], steps["side"], steps["birth"]
    else:
        contacts, births, forward = sample_particles(scene, settings.particle_object, frames)
        if len(contacts) == 0:
            raise FootprintError(f"'{settings.particle_object.name}' emits no particles in {start}..{end}")
        side = np.zeros(len(contacts), np.int32)
    hits, normals, landed = project_onto_terrain(terrain, contacts, _stage(progress, 0.5, 1.0))
    if not landed.any():
        raise FootprintError(f"No print lands on '{terrain.name}': the walk never crosses it")
    forward_local = local_directions(terrain, forward)
    rng = np.random.default_rng(settings.seed)
    scale = 1.0 + settings.variation * rng.uniform(-1.0, 1.0, len(contacts))
    points = {"co": hits[landed], "birth_frame": births[landed],
              "heading": np.arctan2(forward_local[landed, 1], forward_local[landed, 0]),
              "side": side[landed], "depth_scale": scale[landed], "surface_normal": normals[landed]}
    collection = terrain.users_collection[0] if terrain.users_collection else scene.collection
    obj = write_points(terrain, points, collection)
    obj["emitted_from"] = signature(emit_inputs(scene, settings))
    obj["skipped"] = int((~landed).sum())
    return obj, int((~landed).sum())


def paint(scene, settings, progress=None):
    """Emit if the inputs changed (or nothing was emitted), then paint, store and wire up.

    Returns a dict of what was done, for the report.
    """
    terrain = settings.terrain
    points_obj = find_object(POINTS, terrain)
    emitted = points_obj is None or points_obj.get("emitted_from") != signature(emit_inputs(scene, settings))
    if emitted:
        points_obj, _ = emit(scene, settings, _stage(progress, 0.0, 0.6))
    points = read_points(points_obj)
    if len(points["co"]) == 0:
        raise FootprintError(f"'{points_obj.name}' holds no prints to paint")
    sole = sole_from(settings)
    centres = points["co"][:, :2]
    region = painter.fit_region(centres, sole.reach(), settings.resolution, margin=0.05 + sole.rim_width)
    forward, lateral = print_axes(points)
    start, end = frame_range(scene, settings)
    pixels = painter.paint(centres, forward, lateral, points["birth_frame"], points["depth_scale"], region,
                           sole, (start, end))
    if progress:
        progress(0.9)
    image = write_print_image(terrain, pixels, region, (start, end))
    material = sand_material.find_sand_material(terrain)
    added_material = material is None
    if added_material:
        material = sand_material.assign_new_material(terrain)
        sand_material.update_material(material, sand_material.default_glint_values())
    sand_material.attach_footprints(material, image, terrain, {
        "Depth": settings.depth, "Rim": settings.rim, "Frame Start": float(start), "Frame End": float(end),
        "Noise Amount": settings.noise_amount})
    low, high = region_box(image, 0.0)
    collection = terrain.users_collection[0] if terrain.users_collection else scene.collection
    patch = ensure_patch(terrain, low, high, collection, settings.dicing_pixel_size)
    ensure_cut(terrain, low, high)
    return {"prints": len(points["co"]), "skipped": int(points_obj.get("skipped", 0)), "emitted": emitted,
            "image": image, "size": (region.width, region.height), "texel": region.texel,
            "memory": pixels.nbytes, "packed": image.packed_file.size, "patch": patch,
            "added_material": added_material}
