"""bpy.ops.sandscape.add_dunes: a tagged field and its horizon ring, updated in place, the mesh
equal to its numpy twin in any unit scale and wind, the land reaching the horizon from anywhere
in the field, bad input refused with nothing changed, and the walker and prints on the dunes."""

import math

import bpy
import numpy as np
import pytest
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from core import dune_horizon, dune_surface
from core import dunes as twin
from devtools import operators, readback, scenes

SMALL = {"width": 48.0, "depth": 40.0, "cell_size": 0.5, "spacing": 16.0, "horizon": 2000.0}


def add(scale=1.0, **values):
    """Add Dunes with the small field's settings (in metres) in a scene of this unit scale."""
    lengths = {k: v / scale for k, v in SMALL.items()}
    return bpy.ops.sandscape.add_dunes(**{**lengths, **values})


def ours(kind, scene=None):
    scene = scene or bpy.context.scene
    return [o for o in scene.objects if o.get("sandscape_object") == kind]


def local_vertices(obj):
    co = np.empty(len(obj.data.vertices) * 3, np.float32)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3).astype(np.float64)


def test_builds_a_tagged_field_with_its_horizon_and_sand(sandscape):
    assert add() == {"FINISHED"}
    field = bpy.context.active_object
    assert ours("dunes") == [field] and field.select_get()
    assert len(field.data.vertices) == 97 * 81 and len(field.data.polygons) == 96 * 80
    ring, = ours("dune_horizon")
    assert ring.parent == field and ring.hide_select and ring.matrix_world == field.matrix_world
    material = sandscape.addon.sand.find_sand_material(field)
    assert material is not None and ring.active_material == material
    far = local_vertices(ring)[:, :2]
    assert np.abs(far).max() >= 2000.0  # the land reaches as far as asked


def test_running_again_updates_in_place():
    add(seed=1)
    field, ring = bpy.context.active_object, ours("dune_horizon")[0]
    mesh, first = field.data, local_vertices(field)
    counts = {kind: len(getattr(bpy.data, kind)) for kind in ("objects", "meshes", "materials")}
    add(seed=2)
    assert bpy.context.active_object == field and field.data == mesh and ours("dune_horizon") == [ring]
    assert {kind: len(getattr(bpy.data, kind)) for kind in counts} == counts
    assert np.abs(local_vertices(field)[:, 2] - first[:, 2]).max() > 0.1  # another seed, another field
    add(seed=1, horizon=0.0)
    assert np.array_equal(local_vertices(field), first) and not ours("dune_horizon")


def twin_mesh(angle, values=None):
    values = {**SMALL, "seed": 0, "sand_supply": 3.0, **(values or {})}
    surface, _ = twin.grow_surface(values["width"], values["depth"], values["cell_size"], values["spacing"],
                                   values["sand_supply"], values["seed"], angle)
    vertices, quads, _ = twin.field_mesh(surface, values["width"], values["depth"], values["cell_size"])
    dune_surface.limit_triangle_slopes(vertices, dune_surface.quad_triangles(quads), 33.5)
    return vertices


@pytest.mark.parametrize("scale, wind", [(1.0, (3.0, 1.0, 0.0)), (0.01, (-2.0, 2.0, 0.0))])
def test_the_mesh_is_its_twin_in_any_unit_scale_and_wind(scale, wind):
    """Vertices in metres against core/dunes.py's twin within 1e-4 m (float32 vertices)."""
    scene = bpy.context.scene
    scene.unit_settings.scale_length = scale
    scene.sandscape_atmosphere.wind = tuple(w / scale for w in wind)
    assert add(scale) == {"FINISHED"}
    field = bpy.context.active_object
    expected = twin_mesh(math.atan2(wind[1], wind[0]))
    assert np.abs(local_vertices(field) * scale - expected).max() < 1e-4


def test_a_turned_field_regrows_across_the_scene_wind():
    """The wind is taken into the field's own space: a field turned by 90 degrees grows dunes
    whose crests still cross the scene's wind."""
    add()
    field = bpy.context.active_object
    field.rotation_euler.z = math.radians(90.0)
    bpy.context.view_layer.update()
    add()
    wind = np.array(bpy.context.scene.sandscape_atmosphere.wind)
    assert np.abs(local_vertices(field) - twin_mesh(math.atan2(wind[1], wind[0]) - math.pi / 2)).max() < 1e-4


def test_a_second_scene_gets_its_own_field():
    add()
    first = bpy.context.active_object
    second = bpy.data.scenes.new("Second")
    bpy.context.window.scene = second
    second.sandscape_atmosphere.wind = (0.0, 2.0, 0.0)
    add()
    assert ours("dunes", second) != [first] and len(ours("dunes", second)) == 1
    assert ours("dunes", bpy.data.scenes[0]) == [first] and len(ours("dune_horizon", second)) == 1


BAD_INPUT = [
    ({"width": 0.0}, "Width"),
    ({"width": -5.0}, "Width"),
    ({"depth": math.nan}, "Depth"),
    ({"cell_size": math.inf}, "got inf"),  # not 3.4e38, where a property keeps an inf
    ({"spacing": math.nan}, "Dune Spacing"),
    ({"sand_supply": 0.0}, "Sand Supply"),
    ({"horizon": -1.0}, "Horizon"),
    ({"second_wind_share": math.nan}, "Second Wind Share"),
    ({"second_wind_angle": math.inf}, "Second Wind Angle"),
    ({"cell_size": 100.0}, "larger than the field"),
    ({"spacing": 1.0}, "at least 4 cells"),
    ({"width": 1e6, "depth": 1e6, "cell_size": 0.01}, "would need about"),
]


@pytest.mark.parametrize("props, message", BAD_INPUT)
def test_bad_input_is_refused_and_changes_nothing(props, message):
    assert add() == {"FINISHED"}  # a field there already must survive
    before = readback.data_snapshot()
    settings = dict(bpy.context.scene.sandscape_dunes.items())
    with pytest.raises(RuntimeError, match=message):
        add(**props)
    assert readback.data_snapshot() == before
    assert dict(bpy.context.scene.sandscape_dunes.items()) == settings
    result, reports = operators.run_execute("sandscape.add_dunes", **{**SMALL, **props})
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"} and message in reports[0][1]
    assert readback.data_snapshot() == before


@pytest.mark.parametrize("wind", [(0.0, 0.0, 0.0), (0.0, 0.0, 4.0), (math.nan, 1.0, 0.0),
                                  (math.inf, 1.0, 0.0)])
def test_a_wind_without_a_direction_is_refused(wind):
    bpy.context.scene.sandscape_atmosphere.wind = wind
    before = readback.data_snapshot()
    result, reports = operators.run_execute("sandscape.add_dunes", **SMALL)
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"}
    assert "Wind" in reports[0][1] and readback.data_snapshot() == before


def test_batch_runs_print_a_line_per_stage(capfd):
    add(seed=5)
    out = capfd.readouterr().out
    for stage in ("growing the dunes", "laying the field", "laying the land out to the horizon", "done in"):
        assert f"Sandscape dunes: {stage}" in out


def world_bvh(objects):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    vertices, polygons = [], []
    for obj in objects:
        mesh = obj.evaluated_get(depsgraph).to_mesh()
        matrix = obj.matrix_world
        base = len(vertices)
        vertices += [matrix @ v.co for v in mesh.vertices]
        polygons += [[base + i for i in p.vertices] for p in mesh.polygons]
        obj.evaluated_get(depsgraph).to_mesh_clear()
    return BVHTree.FromPolygons(vertices, polygons)


def test_the_land_reaches_the_horizon_from_anywhere_in_the_field():
    """From 1.7 m above the sand anywhere in the field, every ray below the horizon (the Earth's
    curve puts it dune_horizon.horizon_depression below level) meets land, none of it the
    ring's far edge. Without the ring the same rays run off the field's edge."""
    add(horizon=20000.0)
    field = bpy.context.active_object
    ring, = ours("dune_horizon")
    bvh = world_bvh([field, ring])
    # Off the grid's lines: a ray running exactly along an edge between two faces may slip through.
    spots = [(0.13, 0.07), (20.13, 15.07), (-23.13, -19.07), (23.63, -5.07)]
    azimuths = np.radians(np.arange(7.0, 360.0, 30.0))
    misses, far = 0, 0.0
    for x, y in spots:
        ground = bvh.ray_cast(Vector((x, y, 100.0)), Vector((0.0, 0.0, -1.0)))[0].z
        eye = Vector((x, y, ground + 1.7))
        dip = dune_horizon.horizon_depression(1.7 + 3.0, math.sqrt(2 * dune_horizon.EARTH_RADIUS_M * 4.7))
        for azimuth in azimuths:
            for below in np.radians([0.05, 0.2, 1.0, 5.0]) + dip:
                ray = Vector((math.cos(azimuth) * math.cos(below), math.sin(azimuth) * math.cos(below),
                              -math.sin(below)))
                hit = bvh.ray_cast(eye, ray)[0]
                misses += hit is None
                if hit is not None:
                    far = max(far, max(abs(hit.x), abs(hit.y)))
    assert misses == 0
    assert far < 19000.0  # the ring's edge lies beyond the horizon: never the land's last line
    near = world_bvh([field])
    eye = Vector((0.0, 0.0, 1.7 + near.ray_cast(Vector((0, 0, 100.0)), Vector((0, 0, -1.0)))[0].z))
    assert near.ray_cast(eye, Vector((math.cos(0.01), 0.0, -math.sin(0.01))))[0] is None


def test_a_camera_that_clips_before_the_horizon_is_warned():
    scenes.camera("PERSP", location=(0.0, 0.0, 3.0), rotation=(math.radians(88.0), 0.0, 0.0))
    bpy.context.scene.camera.data.clip_end = 1000.0
    result, reports = operators.run_execute("sandscape.add_dunes", **{**SMALL, "horizon": 20000.0})
    assert result == {"FINISHED"}
    warning = [text for kinds, text in reports if kinds == {"WARNING"}]
    assert warning and "Clip End" in warning[0] and "1 km" in warning[0]


def feet_above_sand(sandscape, field, walker):
    top = float(np.max([v[2] for v in field.bound_box]))
    heights = []
    for frame in range(1, 97, 8):
        bpy.context.scene.frame_set(frame)
        position = np.array(walker.matrix_world.translation)
        ground = sandscape.addon.walker.ground_heights(bpy.context.scene, field, position[None, :2], top)[0]
        heights.append(position[2] - ground)
    return np.abs(heights).max()


def test_the_walker_walks_on_the_dunes_and_its_prints_paint(sandscape):
    """And when the dunes are grown again under them, the walk and the prints follow the new sand
    (they stood on a slab of the old sand, over a hole in the new, 2 m up)."""
    add()
    field = bpy.context.active_object
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, 96
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    settings = bpy.context.scene.sandscape_footprints
    assert settings.terrain == field
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    assert ours("footprints") and ours("footprint_patch")
    assert feet_above_sand(sandscape, field, settings.walker) < 0.05
    result, reports = operators.run_execute("sandscape.add_dunes", **{**SMALL, "seed": 7})
    assert result == {"FINISHED"} and "laid the walker's path and the prints on the new sand" in reports[0][1]
    assert feet_above_sand(sandscape, field, settings.walker) < 0.05
    patch, = ours("footprint_patch")
    to_world = np.array(patch.matrix_world)
    corners = local_vertices(patch) @ to_world[:3, :3].T + to_world[:3, 3]
    top = float(np.max([v[2] for v in field.bound_box]))
    with sandscape.addon.footprints.terrain_uncut(field):
        ground = sandscape.addon.walker.ground_heights(bpy.context.scene, field, corners[:, :2], top)
    assert np.abs(corners[:, 2] - ground).max() < 0.02  # the patch lies on the new sand


def slider_cases():
    """Each numeric setting alone at each end of its slider (where that is not its default), then
    all at their lows and highs."""
    rna = bpy.ops.sandscape.add_dunes.get_rna_type()
    props = [p for p in rna.properties if p.type in {"INT", "FLOAT"}]
    ends = {p.identifier: (p.soft_min, min(p.soft_max, 10**6)) for p in props}
    defaults = {p.identifier: p.default for p in props}
    cases = [{name: value} for name, pair in ends.items() for value in pair if value != defaults[name]]
    # The widest field stands in the all-highs case (at the largest spacing; at small spacing it is
    # a lattice of the largest size, which bench/dunes.py times as its 1 km case).
    # The all-lows case stands in for the finest cells alone (16 s on its own at this field size).
    cases = [case for case in cases if case not in ({"width": ends["width"][1]}, {"depth": ends["depth"][1]},
                                                    {"cell_size": ends["cell_size"][0]})]
    cases.append({name: pair[0] for name, pair in ends.items()})
    cases.append({name: pair[1] for name, pair in ends.items()})
    return cases


@pytest.mark.stress
def test_every_setting_at_its_slider_ends_builds_finite_land_or_is_refused():
    """From the small field, each setting to each end of its slider (and all at once): the
    operator finishes with finite land no steeper than repose, or refuses with a report."""
    finished = 0
    for case in slider_cases():
        booleans = {"use_second_wind": True} if any(name.startswith("second_wind") for name in case) else {}
        try:
            outcome = bpy.ops.sandscape.add_dunes(**{**SMALL, "cell_size": 1.0, "spacing": 40.0, **booleans,
                                                     **case})
        except RuntimeError as error:
            assert operators.is_refusal(error), (case, str(error))
            continue
        assert outcome == {"FINISHED"}, case
        finished += 1
        field = bpy.context.active_object
        vertices = local_vertices(field)
        assert np.isfinite(vertices).all(), case
        quads = np.empty(len(field.data.polygons) * 4, np.int32)
        field.data.polygons.foreach_get("vertices", quads)
        triangles = dune_surface.quad_triangles(quads.reshape(-1, 4))
        assert dune_surface.face_slopes(vertices, triangles).max() <= 34.0, case
        for ring in ours("dune_horizon"):
            assert np.isfinite(local_vertices(ring)).all(), case
    assert finished > len(slider_cases()) / 2
