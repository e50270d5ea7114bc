"""A rigged walker leaves a print where each foot lands: an armature with the usual rigs' foot
names, its feet keyed through a walk with a turn and a stop, built here. Reference: the plants
the walk was keyed from (devtools/rigs.py), not the detector."""

import math

import bpy
import numpy as np
import pytest

from core import sole as soles
from devtools import operators, readback, scenes
from devtools.rigs import NAMES, RUN_PLANTS, expected_prints, walking_rig


@pytest.mark.parametrize("convention", sorted(NAMES))
def test_a_print_where_each_foot_lands(convention):
    terrain = scenes.height_field(8.0, 16, name="Their Sand")
    terrain.location.x = 1.5
    armature = walking_rig(convention)
    scenes.footprint_settings(terrain, armature, (1, 90))
    result, reports = operators.run_execute("sandscape.emit_footprints")
    assert result == {"FINISHED"}, reports
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    bpy.context.view_layer.update()  # the new points object's world matrix
    co = np.array([v.co[:] for v in points.data.vertices]) + np.array(points.matrix_world.translation)
    values = {name: np.array([d.value for d in points.data.attributes[name].data])
              for name in ("birth_frame", "heading", "side")}
    wanted = expected_prints()
    assert len(co) == len(wanted) == 6
    order = np.lexsort((-values["side"], values["birth_frame"]))
    for index, (x, y, heading, first, side) in zip(order, wanted, strict=True):
        assert math.hypot(co[index, 0] - x, co[index, 1] - y) < 0.03  # the 3 cm
        assert abs(math.remainder(values["heading"][index] - heading, math.tau)) < math.radians(3)
        assert abs(values["birth_frame"][index] - first) <= 2 and values["side"][index] == side
    assert np.abs(co[:, 2]).max() < 1e-3  # on the flat sand


def test_a_rig_without_known_feet_walks_the_path():
    terrain = scenes.height_field(8.0, 16, name="Their Sand")
    armature = walking_rig("metarig")
    for bone in armature.data.bones:
        bone.name = bone.name.replace("foot", "paw")  # no foot by any rig's names: the path's stride
    armature.keyframe_insert("location", frame=1)
    armature.location.x = 3.0
    armature.keyframe_insert("location", frame=90)
    scenes.footprint_settings(terrain, armature, (1, 90), stride=0.5)
    result, _ = operators.run_execute("sandscape.emit_footprints")
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    assert result == {"FINISHED"} and len(points.data.vertices) == 7  # 3 m at 0.5 m strides


def test_a_rig_whose_feet_never_land_is_refused_with_nothing_made():
    terrain = scenes.height_field(8.0, 16, name="Their Sand")
    armature = walking_rig("metarig")
    armature.location.z = 0.5  # the whole walk half a metre above the sand
    scenes.footprint_settings(terrain, armature, (1, 90))
    before = readback.data_snapshot()
    result, reports = operators.run_execute("sandscape.emit_footprints")
    assert result == {"CANCELLED"} and "no foot touches 'Their Sand'" in reports[0][1]
    assert readback.data_snapshot() == before


def test_the_artists_own_foot_bones_and_the_report_names_them():
    terrain = scenes.height_field(8.0, 16, name="Their Sand")
    armature = walking_rig("metarig")
    for bone in armature.data.bones:
        bone.name = bone.name.replace("foot", "paw").replace("toe", "claw")
    settings = scenes.footprint_settings(terrain, armature, (1, 90))
    settings.left_foot, settings.right_foot = "paw.L", "paw.R"
    result, reports = operators.run_execute("sandscape.emit_footprints")
    assert result == {"FINISHED"} and "on its feet (chosen bones 'paw.L', 'paw.R')" in reports[-1][1]
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    assert len(points.data.vertices) == 6
    settings.left_foot = "hoof.L"
    result, reports = operators.run_execute("sandscape.emit_footprints")
    assert result == {"CANCELLED"} and "'Rig' has no bone 'hoof.L'" in reports[0][1]


def test_two_walkers_with_their_own_feet_go_into_one_image():
    """A rig and a keyed empty on the same sand; the empty's feet 1.5 times the size and its prints
    half as deep. Reference: the painted area of a print grows with the square of its size."""
    terrain = scenes.height_field(8.0, 16, name="Their Sand")
    armature = walking_rig("metarig")
    settings = scenes.footprint_settings(terrain, armature, (1, 90), stride=0.7, resolution=1024)
    hiker = scenes.keyframed_walker(lambda f: (-1.0 + 3.0 * (f - 1) / 89, -2.0, 0.0), range(1, 91),
                                    name="Hiker")
    bpy.context.view_layer.objects.active = hiker
    assert bpy.ops.sandscape.footprint_walker_add() == {"FINISHED"}
    entry = settings.more_walkers[0]
    assert entry.walker == hiker
    entry.foot_scale, entry.depth_scale = 1.5, 0.5
    result, reports = operators.run_execute("sandscape.paint_footprints")
    assert result == {"FINISHED"}, reports
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    sizes = np.array([d.value for d in points.data.attributes["size_scale"].data])
    depths = np.array([d.value for d in points.data.attributes["depth_scale"].data])
    assert (sizes == 1.0).sum() == 6 and (sizes == 1.5).sum() == 5  # 3 m of path at 0.7 m strides
    assert np.all(depths[sizes == 1.5] < 0.6) and np.all(depths[sizes == 1.0] > 0.7)
    image = next(i for i in bpy.data.images if i.get("sandscape_image") == "print_map")
    pixels = np.empty(image.size[0] * image.size[1] * 4, np.float32)
    image.pixels.foreach_get(pixels)
    pressed = pixels.reshape(image.size[1], image.size[0], 4)[..., 0] > 1e-3
    low, size = np.array(image["region_min"]), np.array(image["region_size"])
    rows = low[1] + (np.arange(image.size[1]) + 0.5) / image.size[1] * size[1]
    area = image["texel"] ** 2
    hiker_area = pressed[rows < -1.0].sum() * area / 5
    rig_area = pressed[rows > -0.5].sum() * area / 6
    print(f"pressed area per print: hiker {hiker_area * 1e4:.0f} cm², rig {rig_area * 1e4:.0f} cm²")
    assert hiker_area / rig_area == pytest.approx(1.5 ** 2, rel=0.1)
    assert settings.more_walkers and bpy.ops.sandscape.footprint_walker_remove(index=0) == {"FINISHED"}
    assert not settings.more_walkers


def point_values(names):
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    bpy.context.view_layer.update()
    co = np.array([v.co[:] for v in points.data.vertices]) + np.array(points.matrix_world.translation)
    return co, {name: np.array([d.value for d in points.data.attributes[name].data]) for name in names}


def test_a_run_leaves_longer_prints_deepest_at_the_toe():
    """A jog (each foot down 5 frames, 0.21 s) ending in a stop: the running prints where the
    feet landed, 25 % longer and deeper at the toe; the standing ones even. Reference: the keyed
    plants, and the painted image read back along each print's axis."""
    terrain = scenes.height_field(12.0, 16, name="Their Sand")
    terrain.location.x = 3.0
    armature = walking_rig("mixamo", plants=RUN_PLANTS)
    scenes.footprint_settings(terrain, armature, (1, 90), resolution=2048, variation=0.0)
    result, reports = operators.run_execute("sandscape.paint_footprints")
    assert result == {"FINISHED"}, reports
    co, values = point_values(("birth_frame", "side", "length_scale", "toe_bias"))
    wanted = [row for row in expected_prints(RUN_PLANTS) if row[3] >= 1]  # plants within the scene
    assert len(co) == len(wanted) == 6
    order = np.lexsort((-values["side"], values["birth_frame"]))
    for index, (x, y, _, first, _) in zip(order, wanted, strict=True):
        assert math.hypot(co[index, 0] - x, co[index, 1] - y) < 0.03
        assert abs(values["birth_frame"][index] - first) <= 2
    running = values["birth_frame"] < 35  # the last plant of each foot is the stop
    assert running.sum() == 4
    assert np.allclose(values["length_scale"][running], 1.25)
    assert np.allclose(values["toe_bias"][running], 0.4)
    assert np.all(values["length_scale"][~running] == 1.0) and np.all(values["toe_bias"][~running] == 0.0)
    image = next(i for i in bpy.data.images if i.get("sandscape_image") == "print_map")
    pixels = np.empty(image.size[0] * image.size[1] * 4, np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(image.size[1], image.size[0], 4)
    low, size = np.array(image["region_min"]), np.array(image["region_size"])

    def depth_at(x, y):
        col = int((x - low[0]) / size[0] * image.size[0])
        row = int((y - low[1]) / size[1] * image.size[1])
        return pixels[row, col, 0]

    frame = np.array(next(o for o in bpy.data.objects if o.get("sandscape_object") == "print_frame")
                     .matrix_world.translation)
    # The foot's floor (deepest under heel and ball) times the run's tilt, at +-8 cm.
    sole = soles.Sole(arch=soles.FOOT_ARCH, waist=soles.FOOT_WAIST)

    def floor_ratio(along):
        return float(soles.floor_depth(along, sole) / soles.floor_depth(-along, sole))

    for index in np.flatnonzero(running):
        x, y = co[index, :2] - frame[:2]
        along = 0.08 / 1.25  # 8 cm toward the toe in the world is this far along the unstretched sole
        ratio = depth_at(x + 0.08, y) / depth_at(x - 0.08, y)
        expected = (1 + 0.4 * along / 0.135) / (1 - 0.4 * along / 0.135) * floor_ratio(along)
        assert ratio == pytest.approx(expected, rel=0.05)
    stop = np.flatnonzero(~running)[0]
    x, y = co[stop, :2] - frame[:2]
    assert depth_at(x + 0.08, y) / depth_at(x - 0.08, y) == pytest.approx(floor_ratio(0.08), rel=0.02)


def test_each_path_walker_keeps_its_own_stride():
    """A grown-up and a child along paths: the child's Stride 0.5 halves its stride and stance.
    Reference: the spacing of its prints along the path and across it."""
    terrain = scenes.height_field(8.0, 16, name="Their Sand")
    def along(y):
        return lambda f: (-3.0 + 6.0 * (f - 1) / 89, y, 0.0)

    adult = scenes.keyframed_walker(along(1.0), range(1, 91), name="Adult")
    settings = scenes.footprint_settings(terrain, adult, (1, 90), stride=0.7, stance=0.2)
    child = scenes.keyframed_walker(along(-1.0), range(1, 91), name="Child")
    entry = settings.more_walkers.add()
    entry.walker, entry.foot_scale, entry.stride_scale = child, 0.6, 0.5
    result, reports = operators.run_execute("sandscape.emit_footprints")
    assert result == {"FINISHED"}, reports
    co, _ = point_values(())
    for middle, stride, stance in ((1.0, 0.7, 0.2), (-1.0, 0.35, 0.1)):
        mine = co[np.abs(co[:, 1] - middle) < 0.5]
        xs = np.sort(mine[:, 0])
        assert np.diff(xs).mean() == pytest.approx(stride, rel=0.02)
        assert np.ptp(mine[:, 1]) == pytest.approx(stance, abs=1e-3)
