"""The bpy side of footprints: sample the walker, project prints onto the terrain, keep the
print frame, the points object, the print image, the patch object and the terrain's cut.

Prints live in world terms: contacts drop straight down (world -Z, gravity) onto the evaluated
terrain in world space, and stride, stance, foot size and depth are world lengths whatever the
terrain's transform (tilted, stretched, a Y-up import). They are painted in the print frame,
an empty that is world-aligned, in world units and at the terrain's origin when the prints are
emitted, and a child of the terrain, so prints ride along when the terrain moves.

Everything we make carries OBJECT_KEY (objects) or IMAGE_KEY (the image) and a pointer to its
terrain (TERRAIN_KEY), found in the operator's scene: re-running updates instead of copying.
"""

import contextlib
import hashlib
import json
import os
import tempfile

import bmesh
import bpy
import numpy as np
from mathutils import Matrix, Vector
from mathutils.bvhtree import BVHTree

from ..core import footprints as painter
from ..core import paths
from ..node_groups import helper as h
from ..node_groups import print_markers, region_cut
from . import compat, evaluation, sand, units
from . import ownership as own

ATTRIBUTES = {  # point attribute name -> (type, meaning)
    "birth_frame": ("FLOAT", "Frame at which the walker passes the print"),
    "heading": ("FLOAT", "Yaw of the print's forward axis about world Z (the print frame's Z), radians"),
    "side": ("INT", "+1 left foot, -1 right foot, 0 unknown (particle source)"),
    "depth_scale": ("FLOAT", "Multiplies the print's depth and rim (seeded variation)"),
    "surface_normal": ("FLOAT_VECTOR", "Terrain normal at the print, in the print frame (world axes)"),
}
MARKER_RADIUS = 0.03  # metres: the viewport dots


class FootprintError(ValueError):
    """Input that cannot make footprints; the message is for the artist."""


# ---------------------------------------------------------------- finding our data

def find_object(scene, kind, terrain):
    return own.scene_object(scene, kind, **{own.TERRAIN_KEY: terrain})


def find_print_map(terrain):
    return own.image(own.PRINT_MAP, **{own.TERRAIN_KEY: terrain})


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


def terrain_problem(terrain):
    """Why a terrain cannot take prints (not editable, a flat transform), or None."""
    problem = own.not_editable(terrain)
    if problem:
        return problem
    if abs(terrain.matrix_world.to_3x3().determinant()) < 1e-12:
        return (f"'{terrain.name}' has a scale of 0 on an axis: the prints' space would be flat. "
                "Give it a non-zero scale (or apply the scale)")
    return None


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
            # The evaluated object: only the shown scene's depsgraph writes back to the original.
            evaluated = walker.evaluated_get(evaluation.scene_depsgraph(scene))
            positions[index] = evaluated.matrix_world.translation
            if progress:
                progress(index / len(frames))
    finally:
        scene.frame_set(kept)
    return positions


def sample_particles(scene, emitter, frames):
    """Each particle where it is born: world positions (M, 3), birth frames, directions of travel."""
    kept = scene.frame_current
    found_positions, found_births, found_directions = [], [], []
    previous = None
    try:
        for frame in frames:
            scene.frame_set(int(frame))
            depsgraph = evaluation.scene_depsgraph(scene)
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


def evaluated_terrain(scene, terrain):
    """The terrain's evaluated mesh without our cut, in world space: (vertices (V, 3), triangles
    (T, 3)). The triangles are Blender's own split of each face, the ones it renders: a
    non-planar quad split along the other diagonal is another surface (metres apart on an
    elevation model's 90 m cells)."""
    depsgraph = evaluation.scene_depsgraph(scene)
    with terrain_uncut(terrain):
        depsgraph.update()
        evaluated = terrain.evaluated_get(depsgraph)
        world = np.array(evaluated.matrix_world)  # evaluated: a scene not shown has stale originals
        mesh = evaluated.to_mesh()
        try:
            local, triangles = evaluation.mesh_triangles(mesh)
        finally:
            evaluated.to_mesh_clear()
    depsgraph.update()
    vertices = local @ world[:3, :3].T + world[:3, 3]
    return vertices, triangles


def project_down(vertices, triangles, contacts_world, progress=None):
    """Drop each contact straight down (world -Z) onto the terrain's triangles: world hits,
    up-facing unit normals and a hit mask. Rays start above the terrain's top, so the topmost
    surface is found.
    """
    bvh = BVHTree.FromPolygons([Vector(v) for v in vertices], triangles.tolist())
    top = float(vertices[:, 2].max()) + 1.0
    contacts = np.asarray(contacts_world, dtype=np.float64)
    hits = np.full((len(contacts), 3), np.nan)
    normals = np.full((len(contacts), 3), np.nan)
    down = Vector((0.0, 0.0, -1.0))
    for index, (x, y, _) in enumerate(contacts):
        location, normal, _, _ = bvh.ray_cast(Vector((x, y, top)), down)
        if location is not None:
            hits[index] = location
            normals[index] = normal if normal.z >= 0 else -normal
        if progress and index % 4096 == 0:
            progress(index / max(len(contacts), 1))
    return hits, normals, ~np.isnan(hits[:, 0])


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


def frame_world(scene, frame):
    """The print frame's world matrix from its parent, now (matrix_world waits for an update)."""
    return evaluation.world_matrix(scene, frame.parent) @ frame.matrix_parent_inverse @ frame.matrix_basis


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
        radius = next(i.identifier for i in markers.node_group.interface.items_tree
                      if getattr(i, "in_out", None) == "INPUT" and i.name == "Radius")
        compat.set_modifier_input(markers, radius, units.to_units(scene, MARKER_RADIUS))
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
            values[:] = {"birth_frame": 0, "heading": 0, "side": 0, "depth_scale": 1}.get(name, 0)
            if name == "surface_normal":
                values.reshape(-1, 3)[:] = (0, 0, 1)
        else:
            attribute.data.foreach_get("vector" if width == 3 else "value", values)
        out[name] = values.reshape(-1, 3).astype(np.float64) if width == 3 else values.astype(np.float64)
    return out


def print_axes(points):
    """Forward and lateral axes of each print, projected onto the frame's XY plane: (N, 2) each."""
    heading = points["heading"]
    forward = np.stack([np.cos(heading), np.sin(heading), np.zeros_like(heading)], axis=1)
    forward, lateral = paths.surface_frames(forward, points["surface_normal"])
    return forward[:, :2], lateral[:, :2]


# ---------------------------------------------------------------- the print image

def write_print_image(scene, terrain, pixels, region, frame_range):
    """Store the painted RGBA floats as our packed, ZIP-compressed 32-bit EXR image.

    Custom properties on the image record the region in the print frame's X and Y.
    """
    image = find_print_map(terrain)
    height, width = pixels.shape[:2]
    scratch = bpy.data.images.new("Sandscape Print Scratch", width, height, alpha=True, float_buffer=True)
    scratch.colorspace_settings.name = "Non-Color"
    scratch.pixels.foreach_set(pixels.ravel())
    settings = scene.render.image_settings
    kept = (settings.file_format, settings.color_depth, settings.exr_codec, settings.color_mode)
    handle, path = tempfile.mkstemp(suffix=".exr", prefix="sandscape-prints-")
    os.close(handle)
    try:
        settings.file_format, settings.color_mode = "OPEN_EXR", "RGBA"
        settings.color_depth, settings.exr_codec = "32", "ZIP"
        scratch.save_render(path, scene=scene)
        if image is None:
            image = bpy.data.images.load(path, check_existing=False)
            image.name = f"{terrain.name} Print Map"
            own.mark(image, own.IMAGE_KEY, own.PRINT_MAP, **{own.TERRAIN_KEY: terrain})
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
    image["region_min"] = (region.x0, region.y0)
    image["region_size"] = region.extent()
    image["texel"] = region.texel
    image["frame_range"] = tuple(float(f) for f in frame_range)
    return image


# ---------------------------------------------------------------- patch and cut

def region_box(image):
    """The X-Y box, print-frame space, that the patch covers and the terrain loses."""
    low = np.array(image["region_min"])
    return low, low + np.array(image["region_size"])


def ensure_patch(scene, terrain, frame, low, high, collection, pixel_size=1.0):
    """Our patch object: the terrain's faces over the region, adaptively subdivided.

    The terrain keeps its other faces (a Region Cut modifier hides these), so dicing stays
    where prints are. Subdivision is SIMPLE: a smoothing scheme would move the patch's boundary
    away from the coarse terrain's edges and open a crack. The patch is a child of the terrain
    in the terrain's own space, with the terrain's normals (custom normals from the whole
    terrain), so shading does not change at its border.
    Returns the patch object, or None when no face of the terrain lies in the region.
    """
    depsgraph = evaluation.scene_depsgraph(scene)
    with terrain_uncut(terrain):
        depsgraph.update()
        evaluated = terrain.evaluated_get(depsgraph)
        placed = evaluated.matrix_world.copy()
        mesh = bpy.data.meshes.new_from_object(evaluated, depsgraph=depsgraph)
    depsgraph.update()
    centres = np.empty(len(mesh.polygons) * 3, np.float32)
    mesh.polygons.foreach_get("center", centres)
    to_frame = np.array(frame_world(scene, frame).inverted() @ placed)
    in_frame = centres.reshape(-1, 3).astype(np.float64) @ to_frame[:3, :3].T + to_frame[:3, 3]
    keep = painter.faces_in_region(in_frame, low, high)
    patch = find_object(scene, own.PATCH, terrain)
    if not keep.any():
        bpy.data.meshes.remove(mesh)
        if patch is not None:
            bpy.data.objects.remove(patch)
        return None
    _keep_faces(mesh, keep)
    mesh.name = f"{terrain.name} Footprint Patch"
    if patch is None:
        patch = own.mark(bpy.data.objects.new(f"{terrain.name} Footprint Patch", mesh), own.OBJECT_KEY,
                         own.PATCH, **{own.TERRAIN_KEY: terrain})
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


def _keep_faces(mesh, keep):
    """Delete the faces not kept, carrying the whole terrain's corner normals over as custom
    normals: the patch's own border vertices would otherwise average only its faces."""
    normals = np.empty(len(mesh.loops) * 3, np.float32)
    mesh.corner_normals.foreach_get("vector", normals)
    bm = bmesh.new()
    bm.from_mesh(mesh)
    layer = bm.loops.layers.int.new("sandscape_source_corner")
    for face in bm.faces:
        for corner in face.loops:
            corner[layer] = corner.index
    bm.faces.ensure_lookup_table()
    bmesh.ops.delete(bm, geom=[bm.faces[i] for i in np.flatnonzero(~keep)], context="FACES")
    source = [corner[layer] for face in bm.faces for corner in face.loops]
    bm.loops.layers.int.remove(layer)
    bm.to_mesh(mesh)
    bm.free()
    mesh.normals_split_custom_set(normals.reshape(-1, 3)[source].tolist())


def ensure_cut(terrain, frame, low, high):
    modifier = find_cut_modifier(terrain)
    if modifier is None:
        modifier = terrain.modifiers.new("Sandscape Footprint Cut", "NODES")
        modifier.node_group = h.ensure_group(region_cut)
    elif modifier.node_group.get(h.VERSION_KEY) != region_cut.VERSION:
        modifier.node_group = h.ensure_group(region_cut)
    identifiers = {item.name: item.identifier for item in modifier.node_group.interface.items_tree
                   if item.item_type == "SOCKET" and item.in_out == "INPUT"}
    compat.set_modifier_input(modifier, identifiers["Min"], (float(low[0]), float(low[1]), -1e30))
    compat.set_modifier_input(modifier, identifiers["Max"], (float(high[0]), float(high[1]), 1e30))
    compat.set_modifier_input(modifier, identifiers["Frame"], frame)
    return modifier


# ---------------------------------------------------------------- emit and paint

def sole_from(settings):
    """The sole, its wall as wide as dry sand crumbles at the set depth (all in scene units)."""
    return painter.Sole(length=settings.foot_length, width=settings.foot_width,
                        edge=painter.wall_width(settings.depth), rim_width=settings.rim_width)


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
        walker = settings.walker
        if not is_animated(walker):
            raise FootprintError(f"'{walker.name}' is not animated: give it keyframes, a Follow Path "
                                 "constraint or an animated parent, or use Add Walker")
        positions = sample_walker(scene, walker, frames, progress)
        try:
            steps = paths.plan_steps(positions, frames, settings.stride, settings.stance)
        except paths.PathError as error:
            raise FootprintError(f"'{walker.name}': {error} ({start}..{end})") from error
        motion = positions
    else:
        contacts, births, forward = sample_particles(scene, settings.particle_object, frames)
        if len(contacts) == 0:
            raise FootprintError(f"'{settings.particle_object.name}' emits no particles in "
                                 f"{start}..{end}")
        steps = {"contact": contacts, "birth": births, "forward": forward,
                 "side": np.zeros(len(contacts), np.int32)}
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
    scale = 1.0 + settings.variation * rng.uniform(-1.0, 1.0, len(hits))
    points = {"co": hits[landed] - origin, "birth_frame": np.asarray(steps["birth"])[landed],
              "heading": np.arctan2(forward[landed, 1], forward[landed, 0]),
              "side": np.asarray(steps["side"])[landed], "depth_scale": scale[landed],
              "surface_normal": normals[landed]}
    obj = write_points(scene, terrain, frame, points, collection)
    obj["emitted_from"] = walked["signature"]
    obj["emitted_source"] = walked["source"]
    obj["skipped"] = int((~landed).sum())
    return obj, int((~landed).sum())


def paint(scene, settings, progress=None):
    """Emit if anything the prints depend on changed (or nothing was emitted), then paint, store
    and wire up. Returns a dict of what was done, for the report.
    """
    terrain = settings.terrain
    walked = walk(scene, settings, _stage(progress, 0.0, 0.4))
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
    region = painter.fit_region(centres, sole.reach(), settings.resolution,
                                margin=units.to_units(scene, 0.05) + sole.rim_width)
    forward, lateral = print_axes(points)
    start, end = frame_range(scene, settings)
    pixels = painter.paint(centres, forward, lateral, points["birth_frame"], points["depth_scale"], region,
                           sole, (start, end))
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
        "Noise Amount": settings.noise_amount, "Noise Scale": 40.0 * units.metres_per_unit(scene)})
    low, high = region_box(image)
    collection = terrain.users_collection[0] if terrain.users_collection else scene.collection
    patch = ensure_patch(scene, terrain, frame, low, high, collection, settings.dicing_pixel_size)
    ensure_cut(terrain, frame, low, high)
    return {"prints": len(points["co"]), "skipped": int(points_obj.get("skipped", 0)), "emitted": emitted,
            "image": image, "size": (region.width, region.height), "texel": region.texel,
            "memory": pixels.nbytes, "packed": image.packed_file.size, "patch": patch,
            "added_material": added_material}
