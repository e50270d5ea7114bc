"""Where prints are drawn: the print image (a packed 32-bit EXR), the patch object that is diced
over the prints' region, and the terrain's cut that hides its own faces there."""

import os
import tempfile

import bmesh
import bpy
import numpy as np

from ..core import footprints as painter
from ..node_groups import helper as h
from ..node_groups import region_cut
from . import compat, evaluation, units
from . import ownership as own
from .footprint_terrain import find_cut_modifier, find_object, find_print_map, frame_world, terrain_uncut

EEVEE_EDGE = 0.03  # metres: EEVEE's edge over the prints, fine enough for a print's walls
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
    Faces count when they reach into the region (low, high), which is grown to take their centres.
    Returns the patch object (None when no face of the terrain lies in the region) and the grown
    region, which the terrain's cut takes.
    """
    depsgraph = evaluation.scene_depsgraph(scene)
    with terrain_uncut(terrain):
        depsgraph.update()
        evaluated = terrain.evaluated_get(depsgraph)
        placed = evaluated.matrix_world.copy()
        mesh = bpy.data.meshes.new_from_object(evaluated, depsgraph=depsgraph)
    depsgraph.update()
    to_frame = np.array(frame_world(scene, frame).inverted() @ placed)

    def in_frame(collection, attribute, count):
        values = np.empty(count * 3, np.float32)
        collection.foreach_get(attribute, values)
        return values.reshape(-1, 3).astype(np.float64) @ to_frame[:3, :3].T + to_frame[:3, 3]

    centres = in_frame(mesh.polygons, "center", len(mesh.polygons))
    points = in_frame(mesh.vertices, "co", len(mesh.vertices))
    corner_vertex = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", corner_vertex)
    sizes = np.empty(len(mesh.polygons), np.int32)
    mesh.polygons.foreach_get("loop_total", sizes)
    corner_face = np.repeat(np.arange(len(sizes)), sizes)
    low, high = painter.region_for_faces(points[corner_vertex], corner_face, centres, low, high)
    keep = painter.faces_in_region(centres, low, high)
    patch = find_object(scene, own.PATCH, terrain)
    if not keep.any():
        bpy.data.meshes.remove(mesh)
        if patch is not None:
            bpy.data.objects.remove(patch)
        return None, (low, high)
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
    subdivision = patch.modifiers["Adaptive Subdivision"]
    subdivision.adaptive_pixel_size = pixel_size
    # EEVEE has no adaptive dicing: it displaces the vertices the render levels give.
    subdivision.render_levels = painter.eevee_levels(points, corner_vertex, corner_face, keep,
                                                     units.to_units(scene, EEVEE_EDGE))
    patch.parent = terrain
    patch.matrix_parent_inverse.identity()
    patch.matrix_basis.identity()
    patch.hide_select = True  # it follows the terrain; edit the terrain and paint again
    return patch, (low, high)


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
    compat.set_modifier_input_named(modifier, "Min", (float(low[0]), float(low[1]), -1e30))
    compat.set_modifier_input_named(modifier, "Max", (float(high[0]), float(high[1]), 1e30))
    compat.set_modifier_input_named(modifier, "Frame", frame)
    return modifier
