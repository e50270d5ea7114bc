"""The bpy side of the dune field: the field mesh grown by core/dunes.py, its horizon ring, the
sand material, the report.

The field is ours (OBJECT_KEY "dunes"), found in the scene the operator runs in, so running
again regrows it in place (same object, same mesh, its materials and modifiers kept). The ring
(OBJECT_KEY "dune_horizon") is the field's child in the field's own space, shares its material
and cannot be selected in the viewport (clicks go to the field). The main wind is the scene's
one wind (scene.sandscape_atmosphere.wind), taken into the field's own space, so dunes,
ripples, dust and clouds agree even on a turned field.
"""

import math

import bpy
import numpy as np

from ..core import dune_horizon, dune_surface
from ..core import dunes as model
from . import footprints, sand, shot, units, walker
from . import ownership as own

TRUE_HORIZON_M = 5000.0  # a camera 2 m up sees level ground end about here (sqrt(2 R h))
SLOPE_LIMIT_DEGREES = 33.5  # every triangle of the mesh, either way a quad is cut


def scene_dunes(scene):
    return own.scene_object(scene, own.DUNES)


def wind_angle(scene, field=None):
    """The scene's wind as an angle in the field's own XY plane (radians from +X), or None when
    it has no horizontal direction."""
    wind = np.array(tuple(scene.sandscape_atmosphere.wind), np.float64)
    if field is not None:
        wind = np.linalg.inv(np.array(field.matrix_world)[:3, :3]) @ wind
    held_inf = np.abs(wind) >= units.FLOAT_MAX
    if not np.all(np.isfinite(wind)) or held_inf.any() or math.hypot(wind[0], wind[1]) <= 1e-12:
        return None
    return math.atan2(wind[1], wind[0])


def _fill_mesh(mesh, vertices, faces, corners, uv=None):
    """Replace a mesh's geometry (its materials stay): vertices (N, 3), faces (M, corners)."""
    mesh.clear_geometry()
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", np.ascontiguousarray(vertices, np.float32).ravel())
    mesh.loops.add(faces.size)
    mesh.loops.foreach_set("vertex_index", np.ascontiguousarray(faces, np.int32).ravel())
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set("loop_start", (np.arange(len(faces)) * corners).astype(np.int32))
    mesh.update(calc_edges=True)
    if uv is not None:
        layer = mesh.uv_layers.get("UVMap") or mesh.uv_layers.new(name="UVMap")
        layer.uv.foreach_set("vector", np.ascontiguousarray(uv, np.float32).ravel())
    mesh.shade_smooth()


def _new_object(scene, name, kind, parent=None):
    obj = own.mark(bpy.data.objects.new(name, bpy.data.meshes.new(name)), own.OBJECT_KEY, kind)
    scene.collection.objects.link(obj)
    if parent is not None:
        obj.parent = parent  # identity parent inverse: the ring lies in the field's own space
    return obj


def build(scene, values, progress):
    """Grow the field from `values` (lengths in scene units: width, depth, cell_size, spacing,
    horizon; sand_supply in percent, seed, use_second_wind, second_wind_angle,
    second_wind_share, sand_material) and lay it into the scene. Returns facts for the report."""
    scale = units.metres_per_unit(scene)
    width, depth, cell, spacing, reach = (values[k] * scale for k in
                                         ("width", "depth", "cell_size", "spacing", "horizon"))
    field = scene_dunes(scene)
    angle = wind_angle(scene, field)
    second = values["second_wind_angle"] if values["use_second_wind"] else None
    progress.stage("growing the dunes", 0.0, 0.7)
    surface, facts = model.grow_surface(width, depth, cell, spacing, values["sand_supply"], values["seed"],
                                        angle, second, values["second_wind_share"], progress.update)
    progress.stage("laying the field", 0.7, 0.85)
    vertices, quads, uv = model.field_mesh(surface, width, depth, cell)
    dune_surface.limit_triangle_slopes(vertices, dune_surface.quad_triangles(quads), SLOPE_LIMIT_DEGREES)
    if field is None:
        field = _new_object(scene, "Sandscape Dunes", own.DUNES)
    _fill_mesh(field.data, vertices / scale, quads, 4, uv)
    field["sandscape_dunes_period_m"] = facts["period"]
    progress.stage("laying the land out to the horizon", 0.85, 0.95)
    ring = own.scene_object(scene, own.DUNE_HORIZON)
    if reach > 0:
        count_x, count_y = max(int(round(width / cell)), 1), max(int(round(depth / cell)), 1)
        edge = dune_horizon.boundary_indices(count_x, count_y)
        ring_vertices, triangles = dune_horizon.ring(surface, width, depth, cell, reach, vertices[edge].T)
        fixed = np.zeros(len(ring_vertices), bool)
        fixed[:len(edge)] = True  # the field's own boundary: shared, stays
        dune_surface.limit_triangle_slopes(ring_vertices, triangles, SLOPE_LIMIT_DEGREES, fixed)
        ring = ring or _new_object(scene, "Sandscape Dune Horizon", own.DUNE_HORIZON, parent=field)
        ring.parent = field
        ring.matrix_parent_inverse.identity()
        ring.hide_select = True
        _fill_mesh(ring.data, ring_vertices / scale, triangles, 3)
        facts["ring_vertices"] = len(ring_vertices)
    elif ring is not None:
        own.remove_with_data(ring)
        ring = None
    progress.stage("sand material", 0.95, 1.0)
    material = _material(scene, field, ring, values["sand_material"])
    facts.update(field=field, ring=ring, material=material, vertices=len(vertices),
                 angle=angle, camera_problem=clip_problem(scene, reach / scale))
    facts["relaid"], facts["relay_problem"] = relay(scene, field)
    return facts


def relay(scene, field):
    """What stood on the old sand, laid on the new: our stand-in's path and the painted prints
    (their patch and cut followed the old heights: the figure floated on a slab over a hole).
    Returns (what was laid again, why the prints could not be), for the report."""
    settings = scene.sandscape_footprints
    if settings.terrain != field:
        return [], None
    relaid = []
    figure = settings.walker
    if figure is not None and figure.get(own.OBJECT_KEY) == own.WALKER:
        walker.ensure_walker(scene, field, *footprints.frame_range(scene, settings))
        relaid.append("the walker's path")
    if footprints.find_object(scene, own.PATCH, field) is not None:
        try:
            footprints.paint(scene, settings)
        except footprints.FootprintError as error:  # the field stands; the prints wait for a repaint
            return relaid, f"Prints not repainted on the new sand: {error}"
        relaid.append("the prints")
    return relaid, None


def _material(scene, field, ring, wanted):
    """The sand on the field (added unless told not to, kept if there) and the ring's slots the
    same as the field's, so the land beyond looks like the land near."""
    material = sand.find_sand_material(field)
    if material is None and wanted:
        material, _ = sand.apply(field, sand.default_glint_values(),
                                 ripple_values=sand.default_ripples(scene), scene=scene)
    if ring is not None:
        ring.data.materials.clear()
        for slot in field.material_slots:
            ring.data.materials.append(slot.material)
        if field.material_slots:
            index = [field.active_material_index] * len(ring.data.polygons)
            ring.data.polygons.foreach_set("material_index", index)
    return material


def clip_problem(scene, reach):
    """Why the scene camera cannot see the dunes meet the horizon (its clip end falls short), or
    None. reach: the ring's reach in scene units."""
    camera = shot.scene_camera(scene)
    if camera is None or reach <= 0:
        return None
    wanted = min(reach, units.to_units(scene, TRUE_HORIZON_M))
    if camera.data.clip_end >= wanted:
        return None
    return (f"Camera '{camera.name}' clips at {units.length_text(scene, camera.data.clip_end)}: raise its "
            f"Clip End to {units.length_text(scene, wanted)} or more to see the dunes reach the horizon")


def activate(context, field):
    """The field becomes the active, selected object, as a newly added object does."""
    for obj in context.view_layer.objects.selected:
        obj.select_set(False)
    context.view_layer.objects.active = field
    field.select_set(True)
