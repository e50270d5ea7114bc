"""The stand-in walks: each foot passes under its hip where its print lies, and stands still there.

References: the no-slip condition of a pendulum leg (core.gait's amplitude, checked by a finite
difference here) and the prints core.paths plans (their world contacts in the points object).
"""

import math

import bpy
import numpy as np
import pytest
from mathutils import Vector

from core import paths
from devtools import scenes

LEG = 0.88


def test_a_planted_foot_stands_still_as_the_hip_passes_over_it():
    from core import gait

    stride = 0.7
    amplitude = gait.leg_amplitude(LEG, stride)
    for side, prints in ((1, (0.0, 1.4, 2.8)), (-1, (0.7, 2.1))):
        for at in prints:
            arc = at + np.array([-0.01, 0.0, 0.01])
            ahead, below = gait.foot_offset(arc, stride, amplitude, side, LEG)
            foot = arc + ahead  # the foot's place along the walk
            assert ahead[1] == pytest.approx(0.0, abs=1e-12) and below[1] == pytest.approx(LEG)
            # Still to 1e-3 of the walk's own motion (a 10 % wrong swing slides it 2 mm): the hip moves
            # 2 cm, the foot under 0.02 mm.
            assert abs(foot[2] - foot[0]) < 1e-3 * 0.02
            assert ahead[2] < 0 < ahead[0]  # moving back under the hip: the stance, not the swing
    # Half a stride on, the legs are at their widest, one ahead and one behind.
    left, right = (gait.leg_swing(0.35, stride, amplitude, side) for side in (1, -1))
    assert left == pytest.approx(-amplitude) and right == pytest.approx(amplitude)
    assert np.degrees(amplitude) == pytest.approx(14.5, abs=0.1)  # a 0.7 m stride: about 15 degrees
    assert gait.leg_amplitude(LEG, 10.0) == gait.MAX_SWING
    # The knee: straight on its own prints (the stance), bent most a stride later (mid-swing).
    for side, planted in ((1, 0.0), (-1, 0.7)):
        assert gait.knee_bend(planted + np.array([-0.3, 0.0, 0.3]), stride, side) == pytest.approx(0.0)
        assert gait.knee_bend(planted + stride, stride, side) == pytest.approx(gait.KNEE_BEND)


def shins(walker):
    return {o["sandscape_limb"]: o for o in walker.children_recursive
            if o.get("sandscape_object") == "walker_limb"}


def print_frames(scene, walker, points, stride, stance):
    """Each print's side, the frame its foot lands (its birth frame) and the frame the walker
    passes over it: core.paths' plan of the walker's world path, sampled here per frame."""
    count = len(points.data.vertices)
    side, landing = np.empty(count, np.int32), np.empty(count, np.float32)
    points.data.attributes["side"].data.foreach_get("value", side)
    points.data.attributes["birth_frame"].data.foreach_get("value", landing)
    frames = np.arange(scene.frame_start, scene.frame_end + 1, dtype=np.float64)
    path = []
    for frame in frames:
        scene.frame_set(int(frame))
        path.append(np.array(walker.matrix_world.translation))
    passing = paths.plan_steps(np.array(path), frames, stride, stance)["birth"]
    assert len(passing) == count
    return side, landing, passing


def at(scene, frame):
    scene.frame_set(int(np.floor(frame)), subframe=float(frame % 1.0))


def foot(limbs, side):
    leg = limbs["left_shin" if side > 0 else "right_shin"]
    return np.array(leg.matrix_world @ Vector((0.0, 0.0, -LEG / 2)))


@pytest.mark.parametrize("stride", [0.7, 0.9])
def test_each_foot_lands_on_its_print(sandscape, stride):
    """Add Walker, then paint with the stride asked (a changed stride re-keys the limbs):
    - as the walker passes over a print its own foot is under it within 3 cm, and in the sand:
      never above it, at most 4 cm down (the leg reaches 2 cm below the hips' height over the
      path, and the sand slopes across the walk), while the other foot swings through, lifted;
    - the print appears (its birth frame) as that foot lands: within 5 cm of it, touching the
      sand (at most 2 cm above it), a quarter stride before the walker passes."""
    terrain = scenes.height_field(30.0, 30, lambda x, y: 0.05 * x + 0.3 * np.sin(y / 3.0), name="Sand")
    settings = scenes.footprint_settings(terrain, None, (1, 97), resolution=256)
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    settings.stride = stride
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    scene = bpy.context.scene
    points = next(o for o in scene.objects if o.get("sandscape_object") == "footprints")
    frame_object = next(o for o in scene.objects if o.get("sandscape_object") == "print_frame")
    contacts = np.array([frame_object.matrix_world @ v.co for v in points.data.vertices])
    side, landing, passing = print_frames(scene, settings.walker, points, stride, settings.stance)
    assert len(contacts) >= 7
    limbs = shins(settings.walker)
    feet, landed, lifts = [], [], []
    for k in range(len(contacts)):
        at(scene, passing[k])
        feet.append(foot(limbs, side[k]))
        if 0 < k < len(contacts) - 1:  # the ends: the walk starts or stops
            lifts.append(foot(limbs, -side[k])[2] - settings.walker.matrix_world.translation.z)
        at(scene, landing[k])
        landed.append(foot(limbs, side[k]))
    feet, landed = np.array(feet), np.array(landed)
    miss = np.linalg.norm(feet[:, :2] - contacts[:, :2], axis=1)
    sink = contacts[:, 2] - feet[:, 2]
    land_miss = np.linalg.norm(landed[1:, :2] - contacts[1:, :2], axis=1)  # the first lands on frame 1
    land_height = landed[1:, 2] - contacts[1:, 2]
    print(f"stride {stride}: foot to print {miss.max() * 100:.1f} cm, {sink.min() * 100:.1f}"
          f"-{sink.max() * 100:.1f} cm into the sand; at landing {land_miss.max() * 100:.1f} cm off, "
          f"{land_height.min() * 100:.1f} to {land_height.max() * 100:.1f} cm above it")
    assert miss.max() < 0.03
    assert 0.0 <= sink.min() and sink.max() < 0.04
    # As one foot passes over its print the other swings through, lifted clear of the sand:
    # the figure walks, not glides.
    assert (np.array(lifts) > 0.1).all()
    assert land_miss.max() < 0.05 and land_height.max() < 0.02
    lead = np.median(passing[1:] - landing[1:])
    assert 0.0 < lead


def test_the_robe_hides_the_legs(sandscape):
    """The stand-in's poncho (flaring from the shoulders to the shins, folded) against its legs over
    a walk at a long stride: every leg vertex (thigh, shin, foot) above the hem stays inside the
    robe's elliptic section at its height, taken in to the folds' deepest, so no leg pokes through
    the cloth on any frame (measured in the walker's own space); and no arm hangs out of it."""
    figure = sandscape.addon.walker_figure
    terrain = scenes.height_field(30.0, 30, lambda x, y: 0.05 * x, name="Sand")
    settings = scenes.footprint_settings(terrain, None, (1, 61), resolution=128)
    assert bpy.ops.sandscape.add_walker() == {"FINISHED"}
    settings.stride = 0.9
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    scene, walker = bpy.context.scene, settings.walker
    limbs = sandscape.addon.walker_gait.limbs(walker)
    assert sorted(limbs) == ["left_shin", "left_thigh", "right_shin", "right_thigh"]

    def robe_share(local):  # under 1 inside the robe's section at the point's height, folds in
        radius, depth = figure.section(local[:, 2])
        radius = radius * (1.0 - figure.fold_depth(local[:, 2]))
        return np.hypot(local[:, 0] / (depth * radius), local[:, 1] / radius)

    legs = []
    for frame in range(1, 62, 3):
        scene.frame_set(frame)
        to_body = np.array(walker.matrix_world.inverted())
        for limb in limbs.values():
            world = np.array(limb.matrix_world)
            local = np.array([v.co[:] for v in limb.data.vertices])
            body = (np.c_[local, np.ones(len(local))] @ (to_body @ world).T)[:, :3]
            legs.append(robe_share(body[body[:, 2] > figure.HEM + figure.HEM_WAVE]))
    legs = np.concatenate(legs)
    print(f"legs reach {legs.max():.2f} of the robe's folded section")
    assert len(legs) > 100 and legs.max() < 1.0


def test_the_poncho_slopes_from_the_hood_and_flares_to_the_hem(sandscape):
    """The figure's outline seen from behind (its half-width against height, in the figure's own
    space): it widens all the way down from the hood's base to the hem (no square shoulder, no
    waist), the shoulders sloping at 30-60 degrees from the horizontal, and the sides below them
    steeper, flaring out by at least 10 cm to the hem."""
    figure = sandscape.addon.walker_figure
    mesh = figure.figure_mesh(1.0)
    body = {i for face in mesh.polygons if face.material_index == figure.CLOAK_SLOT for i in face.vertices}
    points = np.array([mesh.vertices[i].co[:] for i in sorted(body)])
    bpy.data.meshes.remove(mesh)
    # The outline from behind: each ring's vertex at the figure's left side (on a fold's crest).
    below_hood = points[:, 2] <= figure.HOOD[0][0] + 1e-4
    side = points[(np.abs(points[:, 0]) < 1e-4) & (points[:, 1] > 0) & below_hood]
    rows, width = side[np.argsort(side[:, 2]), 2], side[np.argsort(side[:, 2]), 1]
    print("half-width from the hem up:", *(f"{z:.2f}:{w:.3f}" for z, w in zip(rows, width, strict=True)))
    assert len(rows) >= 6 and rows[0] == pytest.approx(figure.HEM)
    assert (np.diff(width) < 0).all()
    slope = np.degrees(np.arctan2(np.diff(rows), -np.diff(width)))  # from the horizontal
    shoulders = rows[1:] > figure.SHOULDERS + 1e-4
    print(f"shoulders slope {slope[shoulders].min():.0f}-{slope[shoulders].max():.0f} degrees, "
          f"the sides {slope[~shoulders].min():.0f}-{slope[~shoulders].max():.0f}")
    assert 30 <= slope[shoulders].min() and slope[shoulders].max() <= 60
    assert slope[~shoulders].min() > slope[shoulders].max()
    assert width[0] - width[rows <= figure.SHOULDERS][-1] >= 0.1


def test_the_hood_hides_the_head_from_behind_and_shows_the_face(sandscape):
    """The figure's hood against its head, in the figure's own space: every head vertex behind the
    head's centre lies inside the hood's elliptic section at its height (a camera behind the walker
    sees a hood, not a ball), and the face in front reaches out of it."""
    walker_module = sandscape.addon.walker_figure
    mesh = walker_module.figure_mesh(1.0)
    points = np.array([v.co[:] for v in mesh.vertices])
    bpy.data.meshes.remove(mesh)
    centre = np.array([walker_module.HEAD_FORWARD, 0.0, walker_module.HEIGHT - walker_module.HEAD])
    head = points[np.abs(np.linalg.norm(points - centre, axis=1) - walker_module.HEAD) < 1e-4]
    heights, radii, depths = np.array(walker_module.HOOD).T

    def hood_share(local):  # under 1 inside the hood's section at the point's height (no fall there)
        radius, depth = np.interp(local[:, 2], heights, radii), np.interp(local[:, 2], heights, depths)
        return np.hypot(local[:, 0] / (depth * radius), local[:, 1] / radius)

    assert len(head) >= 50 and heights[0] < head[:, 2].min() and head[:, 2].max() < heights[-3]
    back, front = hood_share(head[head[:, 0] <= centre[0]]), hood_share(head[head[:, 0] > centre[0]])
    print(f"the back of the head reaches {back.max():.2f} of the hood, the face {front.max():.2f}")
    assert back.max() < 1.0 < front.max()


def test_the_scarf_wraps_the_neck_and_streams_behind(sandscape):
    """The golden scarf, in the figure's own space: its wrap at the neck lies 0.5-7 cm outside the
    cloth's elliptic section (on the figure, not in it nor in the air); its tail never enters the
    cloth, leaves it within 7 cm at the nape and streams behind and to the left, its end at least
    40 cm off the cloth (a tail glued to the back read as a stiff sash, the ninth review)."""
    figure = sandscape.addon.walker_figure
    mesh = figure.figure_mesh(1.0)
    band_top = figure.HEM + figure.HEM_BAND + figure.HEM_WAVE
    scarf = {i for face in mesh.polygons if face.material_index == figure.TRIM_SLOT
             for i in face.vertices if mesh.vertices[i].co.z > band_top + 1e-6}
    points = np.array([mesh.vertices[i].co[:] for i in sorted(scarf)])
    bpy.data.meshes.remove(mesh)
    heights, radii, depths = np.array(figure.profile()).T

    def gap(at):  # outward from the section along the point's own direction, metres
        radius, depth = np.interp(at[:, 2], heights, radii), np.interp(at[:, 2], heights, depths)
        share = np.hypot(at[:, 0] / (depth * radius), at[:, 1] / radius)
        return np.hypot(at[:, 0], at[:, 1]) * (1.0 - 1.0 / share)

    wrap_heights = [height for height, _ in figure.COLLAR]
    is_wrap = np.isin(np.round(points[:, 2], 6), np.round(wrap_heights, 6))
    wrap, tail = gap(points[is_wrap]), points[~is_wrap]
    centre = figure.tail_centre(np.linspace(0.0, 1.0, 50)).T
    print(f"wrap {is_wrap.sum()} vertices {wrap.min() * 100:.1f}-{wrap.max() * 100:.1f} cm off the cloth; "
          f"tail {len(tail)} vertices {gap(tail).min() * 100:.1f}-{gap(tail).max() * 100:.0f} cm, "
          f"its centre {gap(centre[:1])[0] * 100:.1f} cm off at the nape")
    assert is_wrap.sum() == figure.ROBE_SEGMENTS * len(figure.COLLAR)
    assert 0.005 < wrap.min() and wrap.max() < 0.07
    assert len(tail) >= 30 and gap(tail).min() > 0.005 and gap(centre).min() > 0.005
    assert gap(centre[:1])[0] < 0.07 and gap(tail).max() >= 0.4
    end = centre[-1]
    assert end[0] < 0.0 and end[1] > 0.0 and end[2] > figure.HEM


def test_the_cloak_darkens_into_its_folds(sandscape):
    """The cloak's fold shading, in the figure's own space: the fold attribute is 1 in the hem's
    troughs and 0 on its crests, where the cloth really is taken in and out (the trough vertices
    nearer the axis than the crests at the same height), fading to 0 at the shoulders' points; a new
    cloak's Base Color multiplies its colour by the attribute's share of FOLD_SHADE."""
    figure = sandscape.addon.walker_figure
    mesh = figure.figure_mesh(1.0)
    points = np.array([v.co[:] for v in mesh.vertices])
    fold = np.array([d.value for d in mesh.attributes[figure.FOLD_ATTRIBUTE].data])
    bpy.data.meshes.remove(mesh)
    at_hem = np.abs(points[:, 2] - figure.HEM) < 1e-4  # the lowest ring, the hem's wave aside
    at_hem |= np.abs(points[:, 2] - figure.HEM - figure.HEM_WAVE) < 1e-4
    radius, depth = figure.section(figure.HEM)
    share = np.hypot(points[at_hem, 0] / depth, points[at_hem, 1]) / radius
    troughs, crests = fold[at_hem] > 0.99, fold[at_hem] < 0.01
    print(f"hem: {troughs.sum()} trough vertices at {share[troughs].mean():.2f} of the section, "
          f"{crests.sum()} crests at {share[crests].mean():.2f}")
    assert troughs.sum() == crests.sum() == figure.FOLDS
    assert share[troughs].max() == pytest.approx(1.0 - figure.FOLD_DEPTH)
    assert share[crests].min() == pytest.approx(1.0)
    assert fold[points[:, 2] >= figure.SHOULDERS - 1e-4].max() == 0.0
    cloth = figure.Cloth(bpy.data.objects.new("Figure", None))
    tree = cloth[sandscape.addon.ownership.CLOAK].node_tree
    principled = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    mix = principled.inputs["Base Color"].links[0].from_node
    attribute = next(link.from_node for i in mix.inputs for link in i.links)
    assert mix.blend_type == "MULTIPLY" and attribute.attribute_name == figure.FOLD_ATTRIBUTE
    darkest = np.array(next(i for i in mix.inputs if i.name == "B" and i.enabled).default_value)
    assert darkest[:3] == pytest.approx(1.0 - figure.FOLD_SHADE)


def test_the_scarfs_tail_flutters_from_the_nape(sandscape):
    """The Wave modifier Add Walker gives the body: over one flap (wavelength over speed, in
    frames) the tail's end sweeps across its face by most of the amplitude, the tail's first row at
    the nape and everything off the tail stay put (the next row within 2 mm), and a second call
    changes nothing."""
    figure, flutter = sandscape.addon.walker_figure, sandscape.addon.walker_flutter
    walker = bpy.data.objects.new("Figure", figure.figure_mesh(1.0))
    bpy.context.scene.collection.objects.link(walker)
    flutter.ensure(walker, 1.0)
    flutter.ensure(walker, 1.0)
    assert len(walker.modifiers) == 1 and len(walker.vertex_groups) == 1
    weights = np.array([d.value for d in walker.data.attributes[figure.FLUTTER_ATTRIBUTE].data])
    rest = np.array([v.co[:] for v in walker.data.vertices])
    end, nape, off = weights > 0.99, (weights > 0) & (weights < 0.03), weights == 0  # off: the nape's row too
    assert end.sum() >= 2 and off.sum() > 0.8 * len(weights)
    ends = []
    for frame in range(1, 1 + math.ceil(flutter.WAVELENGTH / flutter.SPEED) + 1):
        bpy.context.scene.frame_set(frame)
        evaluated = walker.evaluated_get(bpy.context.evaluated_depsgraph_get())
        mesh = evaluated.to_mesh()
        moved = np.array([v.co[:] for v in mesh.vertices]) - rest
        evaluated.to_mesh_clear()
        assert np.abs(moved[off]).max() < 1e-6 and np.linalg.norm(moved[nape], axis=1).max() < 2e-3
        ends.append(np.linalg.norm(moved[end], axis=1).max())
    print(f"the tail's end moves {min(ends) * 100:.1f}-{max(ends) * 100:.1f} cm over a flap")
    assert max(ends) - min(ends) > 0.8 * flutter.AMPLITUDE
    assert max(ends) <= flutter.AMPLITUDE * 1.001
