"""bpy.ops.sandscape.build_demo_scene: every part of the desert in one call, into an empty file."""

import bpy
import numpy as np
import pytest

from devtools import readback


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


def test_the_sun_reaches_the_walker_past_the_clouds_on_every_frame(sandscape, demo_scene):
    """The demo's sand is lit by the low sun, not in the clouds' shadow: from the walker toward
    the sun, the cloud grid holds no density on any frame (a 700 m base let the layer cross the
    6 degree sun's path a few kilometres off, and the whole frame lay in shade)."""
    scene = demo_scene
    walker = scene.sandscape_footprints.walker
    layer = ours("clouds")[0]
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    toward = np.array(sun.matrix_world.col[2][:3])  # a sun lamp shines down its -Z
    toward /= np.linalg.norm(toward)
    inverse = np.array(layer.matrix_world.inverted())
    distances = np.linspace(0.0, 40000.0, 801)  # 50 m steps, out past the layer's box
    for frame in (scene.frame_start, (scene.frame_start + scene.frame_end) // 2, scene.frame_end):
        scene.frame_set(frame)
        world = np.array(walker.matrix_world.translation) + distances[:, None] * toward
        local = world @ inverse[:3, :3].T + inverse[:3, 3]
        density = readback.grid_values(layer, local)
        assert density.max() <= 1e-6, (frame, distances[density.argmax()])



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
