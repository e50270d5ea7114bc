"""Footprint operators: re-runs update, bad input is refused with nothing changed, stress cases."""

import math
import pathlib
import tempfile

import bpy
import numpy as np
import pytest
from mathutils import Vector

from devtools import operators, readback, scenes


def ours(kind):
    collections = {"points": bpy.data.objects, "patch": bpy.data.objects, "image": bpy.data.images}
    key = {"points": "footprints", "patch": "footprint_patch", "image": "print_map"}[kind]
    field = "sandscape_image" if kind == "image" else "sandscape_object"
    return [d for d in collections[kind] if d.get(field) == key]


def straight(length=3.0, frames=31, name="Walker"):
    return scenes.keyframed_walker(lambda f: (-length / 2 + length * (f - 1) / (frames - 1), 0.0, 0.0),
                                   range(1, frames + 1), name)


@pytest.fixture
def walk():
    terrain = scenes.height_field(6.0, 12, name="Sand")
    walker = straight()
    return scenes.footprint_settings(terrain, walker, (1, 31), resolution=256)


def test_rerun_updates_the_same_data(sandscape, walk):
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    counts = {name: len(getattr(bpy.data, name)) for name in ("objects", "meshes", "images", "materials",
                                                               "node_groups")}
    walk.stride, walk.resolution, walk.depth = 0.5, 300, 0.05
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    assert bpy.ops.sandscape.emit_footprints() == {"FINISHED"}
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    assert {name: len(getattr(bpy.data, name)) for name in counts} == counts
    assert len(ours("points")) == len(ours("patch")) == len(ours("image")) == 1
    assert len(ours("points")[0].data.vertices) == 7  # 3 m at 0.5 m
    assert ours("image")[0].size[0] == 300
    material = walk.terrain.active_material
    node = sandscape.addon.sand.footprint_node(material)
    assert node.inputs["Depth"].default_value == pytest.approx(0.05)
    assert material.displacement_method == "BOTH"
    assert [m.type for m in walk.terrain.modifiers] == ["NODES"]
    # The glint material and the footprints live in one material, on terrain and patch alike.
    assert sandscape.addon.sand.glint_node(material) is not None
    assert ours("patch")[0].active_material == material
    # Switching the glint source keeps the footprint wiring.
    bpy.context.view_layer.objects.active = walk.terrain
    bpy.ops.sandscape.add_sand_material(source="IMAGE", image_resolution=16)
    assert sandscape.addon.sand.footprint_node(material).inputs["Depth"].default_value == \
        pytest.approx(0.05)


def test_edited_points_are_painted_as_they_are(walk):
    bpy.ops.sandscape.emit_footprints()
    points = ours("points")[0]
    points.data.vertices[0].co.x += 0.5  # the artist moves a print
    bpy.ops.sandscape.paint_footprints()
    assert points.data.vertices[0].co.x == pytest.approx(-1.0)  # not re-emitted over the edit


def test_renaming_the_walker_or_terrain_keeps_edited_points(walk):
    bpy.ops.sandscape.emit_footprints()
    points = ours("points")[0]
    points.data.vertices[0].co.x += 0.5  # the artist moves a print
    walk.walker.name, walk.terrain.name = "Hero", "Their Dune"
    bpy.ops.sandscape.paint_footprints()
    assert points.data.vertices[0].co.x == pytest.approx(-1.0)  # kept: the same walker, renamed
    other = straight()
    other.name = "Hero.001"
    walk.walker = other  # another walker on the same path is another source
    bpy.ops.sandscape.paint_footprints()
    assert points.data.vertices[0].co.x == pytest.approx(-1.5)  # emitted again from it


def test_cut_and_patch_share_every_face_once(sandscape, walk):
    bpy.ops.sandscape.paint_footprints()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    terrain = walk.terrain.evaluated_get(depsgraph).data
    patch = ours("patch")[0].data
    assert len(terrain.polygons) + len(patch.polygons) == len(walk.terrain.data.polygons)
    assert 0 < len(patch.polygons) < len(walk.terrain.data.polygons)
    centres = {tuple(np.round(p.center, 6)) for p in terrain.polygons}
    assert not centres & {tuple(np.round(p.center, 6)) for p in patch.polygons}
    # The Region Cut group against its twin on the original faces.
    modifier = walk.terrain.modifiers[0]
    identifiers = sandscape.addon.compat.modifier_input_identifiers(modifier)
    low, high = (sandscape.addon.compat.modifier_input(modifier, identifiers[name])
                 for name in ("Min", "Max"))
    original = np.array([p.center for p in walk.terrain.data.polygons])
    inside = sandscape.core.footprints.faces_in_region(original, low, high)
    assert len(terrain.polygons) == (~inside).sum() and len(patch.polygons) == inside.sum()


@pytest.mark.parametrize("cells", [40, 1])
def test_a_coarse_terrain_gets_a_patch_under_every_print(sandscape, cells):
    """A 40 m terrain of 1 m faces (or one face) and a trail 1 m wide: the faces' centres lie outside
    the prints' region, yet every face a print reaches is in the patch, and cut from the terrain."""
    terrain = scenes.height_field(40.0, cells, name="Their Sand")
    walker = straight(length=10.0, frames=90)
    scenes.footprint_settings(terrain, walker, (1, 90), resolution=1024)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    patches = ours("patch")
    assert len(patches) == 1
    faces = [[patches[0].data.vertices[i].co.xy for i in p.vertices] for p in patches[0].data.polygons]
    boxes = np.array([[np.min(f, axis=0), np.max(f, axis=0)] for f in faces])
    markers = ours("points")[0]
    prints = np.array([v.co.xy for v in markers.data.vertices])
    assert len(prints) > 10
    covered = [np.any(np.all((boxes[:, 0] <= xy) & (xy <= boxes[:, 1]), axis=1)) for xy in prints]
    assert all(covered)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    left = len(terrain.evaluated_get(depsgraph).data.polygons)
    assert left + len(patches[0].data.polygons) == len(terrain.data.polygons)


def test_frame_driver_runs_without_python_auto_run(sandscape, walk):
    bpy.ops.sandscape.paint_footprints()
    material = walk.terrain.active_material
    fcurve = next(c for c in material.node_tree.animation_data.drivers if "Footprints" in c.data_path)
    assert fcurve.driver.expression == "frame" and fcurve.driver.is_simple_expression
    path = pathlib.Path(tempfile.mkdtemp()) / "walk.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path), compress=True)
    preferences = bpy.context.preferences.filepaths
    kept = preferences.use_scripts_auto_execute
    preferences.use_scripts_auto_execute = False
    try:
        bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=False)
        material = bpy.data.materials["Sandscape Sand"]
        bpy.context.scene.frame_set(23)
        node = sandscape.addon.sand.footprint_node(material)
        assert node.inputs["Frame"].default_value == pytest.approx(23.0, abs=1e-6)
        image = material.node_tree.nodes[sandscape.addon.sand.PRINT_MAP].image
        assert image.packed_file is not None and image.is_float
    finally:
        preferences.use_scripts_auto_execute = kept


def bad_scene(case, settings):
    if case == "no walker":
        settings.walker = None
    elif case == "not animated":
        settings.walker = bpy.data.objects.new("Statue", None)
        bpy.context.scene.collection.objects.link(settings.walker)
    elif case == "stands still":
        settings.walker = scenes.keyframed_walker(lambda f: (1.0, 1.0, 0.0), range(1, 32), "Idle")
    elif case == "terrain not a mesh":
        curve = bpy.data.objects.new("Curve", bpy.data.curves.new("Curve", "CURVE"))
        bpy.context.scene.collection.objects.link(curve)
        settings.terrain = None
        settings["terrain"] = curve  # a script can bypass the panel's mesh filter
    elif case == "no terrain":
        settings.terrain = None
    elif case == "hidden":  # disabled in viewports: Blender does not play its motion
        settings.walker.hide_viewport = True
    elif case == "off the terrain":
        settings.walker = scenes.keyframed_walker(lambda f: (50.0 + f, 0.0, 0.0), range(1, 32), "Away")


# Structure a button needs: refused by poll(), whose message bpy.ops puts in its error.
NOT_RUNNABLE = [
    ("no walker", "No walker"),
    ("no terrain", "No terrain"),
    ("terrain not a mesh", "No terrain"),
]
# Values and data that cannot make prints: refused by execute() with an ERROR report.
BAD_INPUT = [
    ("not animated", {}, "not animated"),
    ("stands still", {}, "does not move"),
    ("hidden", {}, "hidden in the viewport"),
    ("off the terrain", {}, "No print lands"),
    ("ok", {"stride": 0.0}, "Stride"),
    ("ok", {"stride": -1.0}, "Stride"),
    ("ok", {"stride": math.nan}, "Stride"),
    ("ok", {"stance": math.inf}, "Stance"),
    ("ok", {"depth": -math.inf}, "Depth"),
    ("ok", {"use_scene_range": False, "frame_start": 10, "frame_end": 5}, "empty"),
    ("ok", {"resolution": 0}, "Resolution"),
    ("ok", {"foot_width": 1.0}, "Foot width"),
    ("ok", {"variation": math.nan}, "Variation"),
    ("ok", {"dicing_pixel_size": 0.0}, "Dicing"),
]


@pytest.mark.parametrize("case,message", NOT_RUNNABLE)
@pytest.mark.parametrize("operator", ["emit_footprints", "paint_footprints"])
def test_what_cannot_run_is_greyed_out_with_a_reason(walk, operator, case, message):
    bad_scene(case, walk)
    before = readback.data_snapshot()
    assert not getattr(bpy.ops.sandscape, operator).poll()
    with pytest.raises(RuntimeError, match=message):
        getattr(bpy.ops.sandscape, operator)()
    assert readback.data_snapshot() == before


@pytest.mark.parametrize("case,values,message", BAD_INPUT)
@pytest.mark.parametrize("operator", ["emit_footprints", "paint_footprints"])
def test_bad_input_is_refused_and_changes_nothing(walk, operator, case, values, message):
    bad_scene(case, walk)
    for key, value in values.items():
        setattr(walk, key, value)
    frame = bpy.context.scene.frame_current
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match=message):
        getattr(bpy.ops.sandscape, operator)()
    assert readback.data_snapshot() == before
    assert bpy.context.scene.frame_current == frame
    # The operator itself returns CANCELLED (bpy.ops turns the ERROR report into the exception).
    result, reports = operators.run_execute(f"sandscape.{operator}")
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"} and message in reports[0][1]
    assert readback.data_snapshot() == before


def test_add_walker_makes_a_walk_that_paints(walk):
    walk.walker = None
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}  # updates, no second walker
    walkers = [o for o in bpy.data.objects if o.get("sandscape_object") == "walker"]
    assert len(walkers) == 1 and walk.walker == walkers[0]
    # A 1.7 m figure standing on its origin (its hood peaks 10 cm over its head), four limbs (the
    # legs; the arms are under the poncho), one red cloak, not a second on the re-run.
    heights = [v.co.z for v in walkers[0].data.vertices]
    assert max(heights) == pytest.approx(1.8, abs=1e-5)
    limbs = [o for o in bpy.data.objects if o.get("sandscape_object") == "walker_limb"]
    assert len(limbs) == 4 and all(limb.parent == walkers[0] or limb.parent in limbs for limb in limbs)
    to_figure = walkers[0].matrix_world.inverted()
    lowest = min((to_figure @ limb.matrix_world @ v.co).z for limb in limbs for v in limb.data.vertices)
    assert -0.03 <= lowest <= 0.0  # a planted foot sinks 2 cm into loose sand
    # Each shin ends in a foot reaching forward from its ankle, about as long as a print.
    for shin in (limb for limb in limbs if limb["sandscape_limb"].endswith("shin")):
        along = [v.co.x for v in shin.data.vertices]
        assert max(along) - min(along) == pytest.approx(0.26, abs=1e-5) and max(along) > 0.1
    # One cloak, one golden trim, one dark wrap: the body wears the cloak, the trim and (its face)
    # the wraps, the legs the wraps.
    cloth = {kind: [m for m in bpy.data.materials if m.get("sandscape_material") == kind]
             for kind in ("cloak", "walker_trim", "walker_wraps")}
    assert all(len(found) == 1 for found in cloth.values())
    cloak, trim, wraps = (found[0] for found in cloth.values())
    assert list(walkers[0].data.materials) == [cloak, trim, wraps]
    assert {face.material_index for face in walkers[0].data.polygons} == {0, 1, 2}  # each worn
    for limb in limbs:
        assert list(limb.data.materials) == [wraps]
        assert {face.material_index for face in limb.data.polygons} == {0}
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    assert len(ours("points")[0].data.vertices) >= 2  # 1.25 s at a walking pace, 0.7 m strides


def test_the_stand_in_walks_at_a_walking_pace_on_the_ground(walk):
    """1.2-1.6 m/s whatever the terrain's size, feet on the (evaluated, tilted) terrain, upright."""
    walk.terrain.rotation_euler.x = math.radians(8)  # a slope
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 97  # 4 s
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    walker = walk.walker
    positions, tilts = [], []
    for frame in range(1, 98, 4):
        scene.frame_set(frame)
        positions.append(np.array(walker.matrix_world.translation))
        tilts.append(walker.matrix_world.col[2][2])  # the figure's up axis against world Z
    positions = np.array(positions)
    speed = np.linalg.norm(np.diff(positions, axis=0), axis=1) * 24 / 4
    print(f"stand-in speed {speed.min():.2f}-{speed.max():.2f} m/s")
    assert 1.2 <= speed.min() and speed.max() <= 1.6
    assert min(tilts) >= 0.9999
    depsgraph = bpy.context.evaluated_depsgraph_get()
    terrain = walk.terrain.evaluated_get(depsgraph)
    to_local = walk.terrain.matrix_world.inverted()
    for x, y, z in positions:
        origin = to_local @ Vector((x, y, z + 10.0))
        hit, location, *_ = terrain.ray_cast(origin, to_local.to_3x3() @ Vector((0.0, 0.0, -1.0)))
        assert hit
        ground = (walk.terrain.matrix_world @ location).z
        assert abs(z - ground) <= 0.02, (z, ground)  # within 2 cm between path points 25 cm apart


def test_progress_only_moves_forward(sandscape, walk):
    seen = []
    sandscape.addon.footprints.paint(bpy.context.scene, walk, seen.append)
    assert seen and seen == sorted(seen) and 0.0 <= seen[0] and seen[-1] <= 1.0
    assert seen[-1] >= 0.9  # emitting and painting both reported


def test_add_walker_refuses_a_range_too_short_to_walk():
    scene = bpy.context.scene
    scene.frame_start = scene.frame_end = 7
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match="too short to walk"):
        bpy.ops.sandscape.add_walker()
    assert readback.data_snapshot() == before
    result, reports = operators.run_execute("sandscape.add_walker")
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"}


def test_add_walker_refuses_a_terrain_with_no_faces():
    mesh = bpy.data.meshes.new("Their Outline")
    mesh.from_pydata([(0.0, 0.0, 0.0), (5.0, 0.0, 0.0), (5.0, 5.0, 0.0)], [(0, 1), (1, 2)], [])
    outline = bpy.data.objects.new("Their Outline", mesh)
    bpy.context.scene.collection.objects.link(outline)
    bpy.context.view_layer.objects.active = outline
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match="has no faces to walk on"):
        bpy.ops.sandscape.add_walker()
    assert readback.data_snapshot() == before


def test_add_walker_gives_an_older_walkers_shins_feet(walk):
    """A walker saved before shins had feet: Add Walker again replaces its limbs' meshes in place
    (the same objects, the old meshes gone), and the legs reach forward into feet."""
    walk.walker = None
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    limbs = {o["sandscape_limb"]: o for o in bpy.data.objects if o.get("sandscape_object") == "walker_limb"}
    shin = limbs["left_shin"]
    bare = bpy.data.meshes.new("bare shin")
    bare.from_pydata([(0, 0, 0), (0, 0, -0.44), (0.01, 0, -0.44)], [], [(0, 1, 2)])
    shin.data, shin["sandscape_limb_shape"] = bare, 1
    meshes = len(bpy.data.meshes)
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    again = {o["sandscape_limb"]: o for o in bpy.data.objects if o.get("sandscape_object") == "walker_limb"}
    assert again == limbs and "bare shin" not in bpy.data.meshes and len(bpy.data.meshes) == meshes
    assert max(v.co.x for v in shin.data.vertices) > 0.1


def test_add_walker_dresses_an_older_walker_in_the_cloak_it_wore(walk):
    """A walker saved before the scarf (figure and limb shape 3, everything in one cloak the artist
    has recoloured, arms hanging from its shoulders): Add Walker again gives it the new body and
    legs, keeps that cloak (its colour too) and shades its folds, removes the arms the poncho now
    covers and makes one trim and one wrap, nothing twice."""
    walk.walker = None
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    walker = next(o for o in bpy.data.objects if o.get("sandscape_object") == "walker")
    limbs = [o for o in bpy.data.objects if o.get("sandscape_object") == "walker_limb"]
    cloak = walker.data.materials[0]
    for obj, key in ((walker, "sandscape_figure_shape"), *((limb, "sandscape_limb_shape") for limb in limbs)):
        old = bpy.data.meshes.new("older " + obj.name)
        old.from_pydata([(0, 0, 0), (0, 0, -0.4), (0.01, 0, -0.4)], [], [(0, 1, 2)])
        old.materials.append(cloak)
        obj.data, obj[key] = old, 3
    arms = []
    for side in ("left_arm", "right_arm"):
        old = bpy.data.meshes.new("older " + side)
        old.from_pydata([(0, 0, 0), (0, 0, -0.6), (0.01, 0, -0.6)], [], [(0, 1, 2)])
        arm = bpy.data.objects.new("older " + side, old)
        arm["sandscape_object"], arm["sandscape_limb"], arm["sandscape_limb_shape"] = "walker_limb", side, 3
        arm.parent = walker
        bpy.context.scene.collection.objects.link(arm)
        arms.append(arm.name)
    newer = ("walker_trim", "walker_wraps")
    for material in [m for m in bpy.data.materials if m.get("sandscape_material") in newer]:
        bpy.data.materials.remove(material)
    cloak.diffuse_color = (0.1, 0.2, 0.6, 1.0)  # the artist's blue
    tree = cloak.node_tree  # made before the folds were shaded: no Attribute, no Mix
    principled = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    for node in [principled.inputs["Base Color"].links[0].from_node,
                 *(n for n in tree.nodes if n.bl_idname == "ShaderNodeAttribute")]:
        tree.nodes.remove(node)
    principled.inputs["Base Color"].default_value = (0.1, 0.2, 0.6, 1.0)
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    kinds = [m.get("sandscape_material") for m in bpy.data.materials]
    assert sorted(k for k in kinds if k in ("cloak", "walker_trim", "walker_wraps")) == [
        "cloak", "walker_trim", "walker_wraps"]
    trim, wraps = (next(m for m in bpy.data.materials if m.get("sandscape_material") == k) for k in newer)
    assert list(walker.data.materials) == [cloak, trim, wraps]
    assert tuple(cloak.diffuse_color) == pytest.approx((0.1, 0.2, 0.6, 1.0))
    # The cloak's folds shaded as a new cloak's, in the artist's colour, once however often it runs.
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    mix = principled.inputs["Base Color"].links[0].from_node
    folds = [n for n in tree.nodes if n.bl_idname == "ShaderNodeAttribute"]
    assert len(folds) == 1 and folds[0].attribute_name == "sandscape_fold"
    assert tuple(next(i for i in mix.inputs if i.name == "A" and i.enabled).default_value) == pytest.approx(
        (0.1, 0.2, 0.6, 1.0))
    assert not [m for m in bpy.data.meshes if m.name.startswith("older ")]
    assert not [name for name in arms if name in bpy.data.objects]
    for limb in limbs:
        assert list(limb.data.materials) == [wraps]
