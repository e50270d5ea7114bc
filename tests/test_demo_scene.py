"""bpy.ops.sandscape.build_demo_scene: every part of the desert in one call, into an empty file."""

import bpy
import numpy as np
import pytest

from devtools import readback
from devtools.cloud_gap import NEAR_SUN, ROUND_SUN, cone
from devtools.demo import HERO_FRAME


def ours(kind):
    return [o for o in bpy.data.objects if o.get("sandscape_object") == kind]


def test_builds_every_part(sandscape, demo_scene):
    """The run's demo (tests/conftest.py: built by the operator, which finished, and saved)."""
    scene = demo_scene
    terrain = scene.sandscape_footprints.terrain
    material = terrain.active_material
    groups = sandscape.addon.sand
    assert groups.glint_node(material) is not None and groups.footprint_node(material) is not None
    assert len(ours("footprints")[0].data.vertices) > 20 and ours("footprint_patch")
    assert ours("walker") and ours("sun") and ours("dust_volume")
    tree = scene.compositing_node_group
    assert tree is not None and tree.get("sandscape_compositor")
    assert [c.type for c in scene.camera.constraints] == ["TRACK_TO"]
    assert ours("dunes") == [terrain] and ours("dune_horizon")
    assert not scene.cycles.use_denoising


def test_refuses_a_scene_with_meshes():
    bpy.ops.mesh.primitive_cube_add()
    with pytest.raises(RuntimeError, match="empty scene"):
        bpy.ops.sandscape.build_demo_scene()


def test_every_frame_the_camera_is_above_the_sand_and_the_walker_on_it(sandscape, demo_scene):
    """The whole animation, frame by frame: the camera at least half a metre above the sand under
    it (it keeps 0.6 m), the walker's feet on the sand within 5 cm."""
    scene = demo_scene
    terrain, walker = scene.sandscape_footprints.terrain, scene.sandscape_footprints.walker
    top = float(np.max([v[2] for v in terrain.bound_box]))
    cameras, feet = [], []
    for frame in range(scene.frame_start, scene.frame_end + 1):
        scene.frame_set(frame)
        cameras.append(np.array(scene.camera.matrix_world.translation))
        feet.append(np.array(walker.matrix_world.translation))
    cameras, feet = np.array(cameras), np.array(feet)
    ground = sandscape.addon.walker.ground_heights
    assert (cameras[:, 2] - ground(scene, terrain, cameras[:, :2], top)).min() > 0.5
    assert np.abs(feet[:, 2] - ground(scene, terrain, feet[:, :2], top)).max() < 0.05
    assert np.linalg.norm(np.diff(cameras, axis=0), axis=1).max() < 0.2  # no jumps: 1.4 m/s is 6 cm a frame
    speed = np.linalg.norm(np.diff(feet, axis=0), axis=1) * scene.render.fps / scene.render.fps_base
    assert 1.35 < speed.min() and speed.max() < 1.5  # a walking pace on every frame


def _cloud_on_rays(layer, origin, rays, far=40000.0):
    """Per ray from origin, the grid's largest cloudiness out to `far` (50 m steps): > 0 is cloud."""
    inverse = np.array(layer.matrix_world.inverted())
    distances = np.linspace(0.0, far, int(far / 50.0) + 1)
    world = origin + distances[None, :, None] * rays[:, None, :]
    local = world @ inverse[:3, :3].T + inverse[:3, 3]
    return readback.grid_values(layer, local.reshape(-1, 3)).reshape(len(rays), -1).max(axis=1)


def test_the_sun_reaches_the_walker_past_the_clouds_on_every_frame(sandscape, demo_scene):
    """The demo's sand is lit by the low sun, not in the clouds' shadow: from the walker toward
    the sun, and 0.6 degrees round it (the sky round the disc), the cloud grid holds no density on
    every 40th frame (a 700 m base let the layer cross the 6 degree sun's path a few kilometres
    off, and the whole frame lay in shade). The layer reaches 25 km, so the sun sits in a gap:
    there is cloud 2-6 degrees from it."""
    scene = demo_scene
    walker = scene.sandscape_footprints.walker
    layer = ours("clouds")[0]
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    toward = np.array(sun.matrix_world.col[2][:3])  # a sun lamp shines down its -Z
    toward /= np.linalg.norm(toward)
    rays = np.vstack([toward, cone(toward, ROUND_SUN)])
    for frame in range(scene.frame_start, scene.frame_end + 1, 40):
        scene.frame_set(frame)
        cloud = _cloud_on_rays(layer, np.array(walker.matrix_world.translation), rays)
        assert cloud.max() <= 1e-6, (frame, cloud)
    scene.frame_set(HERO_FRAME)
    near = np.vstack([cone(toward, degrees) for degrees in NEAR_SUN])
    assert (_cloud_on_rays(layer, np.array(walker.matrix_world.translation), near) > 0).sum() >= 4


def test_the_clouds_reach_down_to_the_haze_at_the_horizon(sandscape, demo_scene):
    """Seen from the camera on the hero frame, the layer is not one deck over the frame's top:
    rays 3-5 degrees up across the view's width meet cloud on at least a quarter of them (within
    8 km the layer began 8.5 degrees up, and none did)."""
    scene = demo_scene
    scene.frame_set(HERO_FRAME)
    camera = scene.camera
    layer = ours("clouds")[0]
    view = -np.array(camera.matrix_world.col[2][:3])
    heading = np.arctan2(view[1], view[0])
    headings = heading + np.radians(np.linspace(-40.0, 40.0, 33))
    hits = []
    for elevation in np.radians((3.0, 4.0, 5.0)):
        rays = np.stack([np.cos(headings) * np.cos(elevation), np.sin(headings) * np.cos(elevation),
                         np.full(len(headings), np.sin(elevation))], axis=-1)
        hits.append(_cloud_on_rays(layer, np.array(camera.matrix_world.translation), rays) > 0)
    share = float(np.mean(hits))
    print(f"rays 3-5 degrees up meeting cloud: {share:.2f}")
    assert share >= 0.25


def test_every_frame_the_trail_runs_toward_the_walker_and_the_sun_is_in_frame(sandscape, demo_scene):
    """The camera turns with the walk: on every frame the walker's heading is within 30 degrees of
    the camera's view (the trail runs from the camera's side toward it, not off sideways: a fixed
    offset saw 50 degrees), and the low sun stays in frame, left of the walker."""
    from bpy_extras.object_utils import world_to_camera_view

    scene = demo_scene
    walker, camera = scene.sandscape_footprints.walker, scene.camera
    sun = ours("sun")[0]
    turns, suns = [], []
    for frame in range(scene.frame_start, scene.frame_end + 1):
        scene.frame_set(frame)
        heading = walker.matrix_world.col[0]
        view = -camera.matrix_world.col[2]
        turns.append(np.degrees(np.arctan2(heading[1], heading[0]) - np.arctan2(view[1], view[0])))
        far = camera.matrix_world.translation + sun.matrix_world.col[2].xyz.normalized() * 1000.0
        suns.append(world_to_camera_view(scene, camera, far)[:])
    turns, suns = np.abs(np.array(turns)), np.array(suns)
    print(f"heading from view {turns.min():.1f}-{turns.max():.1f} deg, sun at x {suns[:, 0].min():.2f}"
          f"-{suns[:, 0].max():.2f}")
    assert turns.max() < 30.0
    assert (suns[:, 2] > 0).all() and 0.02 < suns[:, 0].min() and suns[:, 0].max() < 0.4
    assert (suns[:, 1] < 0.98).all()


def test_every_frame_the_prints_behind_the_walker_run_up_the_middle_of_the_frame(sandscape, demo_scene):
    """The camera walks the trail: on every 5th frame from the first, prints already made lie
    between 0.45 and 0.9 of the way from the camera to the walker (2-4 m at the film's start, 4.5 m
    back; the walker sets off before the film starts: starting with it, frames 1-30 had none), each
    in frame, in its middle 60 % across and its lower 70 % (a
    camera beside the walk saw the trail come in from the frame's left edge, x 0.0-0.2)."""
    from bpy_extras.object_utils import world_to_camera_view
    from mathutils import Vector

    scene = demo_scene
    footprints = sandscape.addon.footprints
    terrain, walker = scene.sandscape_footprints.terrain, scene.sandscape_footprints.walker
    points = footprints.read_points(ours("footprints")[0])
    to_world = footprints.find_object(scene, "print_frame", terrain).matrix_world
    places, seen = [to_world @ Vector(co) for co in points["co"]], []
    for frame in range(scene.frame_start, scene.frame_end + 1, 5):
        scene.frame_set(frame)
        camera = scene.camera
        reach = world_to_camera_view(scene, camera, walker.matrix_world.translation).z
        for place, birth in zip(places, points["birth_frame"], strict=True):
            ahead = world_to_camera_view(scene, camera, place)
            if birth <= frame and 0.45 * reach < ahead.z < 0.9 * reach:
                seen.append((frame, *ahead[:2]))
    seen = np.array(seen)
    print(f"{len(seen)} prints seen; x {seen[:, 1].min():.2f}-{seen[:, 1].max():.2f}, "
          f"y {seen[:, 2].min():.2f}-{seen[:, 2].max():.2f}")
    assert len(np.unique(seen[:, 0])) == len(range(scene.frame_start, scene.frame_end + 1, 5))
    assert 0.2 < seen[:, 1].min() and seen[:, 1].max() < 0.8
    assert 0.0 < seen[:, 2].min() and seen[:, 2].max() < 0.7
