"""Prints sit on the terrain and face along the path: a 30 degree slope and a curved dune.

Reference: the analytic surface z(x, y) and the analytic path tangent, not the mesh or the planner.
"""

import math

import bpy
import numpy as np
import pytest
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from core import paths
from devtools import scenes

RADIUS, FRAMES = 5.0, (1, 121)


def arc(frame):
    """Half a circle of RADIUS over the frame range, at a height the terrain never reaches."""
    angle = (frame - FRAMES[0]) / (FRAMES[1] - FRAMES[0]) * math.pi
    return (RADIUS * math.cos(angle), RADIUS * math.sin(angle) - 2.0, 20.0)


def path_angle(co):
    """Where along the half circle a print lies (its stance offset is radial: no change)."""
    return np.arctan2(co[:, 1] + 2.0, co[:, 0])


SURFACES = {
    "slope 30 deg": (lambda x, y: math.tan(math.radians(30)) * x, 20),
    "curved dune": (lambda x, y: 1.5 * np.sin(2 * np.pi * x / 10) * np.cos(2 * np.pi * y / 14), 400),
}


def read(obj, name, width=1):
    values = np.empty(len(obj.data.vertices) * width, np.float32)
    obj.data.attributes[name].data.foreach_get("vector" if width == 3 else "value", values)
    return values.reshape(-1, width) if width == 3 else values


@pytest.mark.parametrize("surface", sorted(SURFACES))
def test_prints_lie_on_the_surface_and_follow_the_tangent(surface):
    height, subdivisions = SURFACES[surface]
    terrain = scenes.height_field(20.0, subdivisions, height)
    walker = scenes.keyframed_walker(arc, range(FRAMES[0], FRAMES[1] + 1))
    scenes.footprint_settings(terrain, walker, FRAMES, stride=0.5)
    bpy.ops.sandscape.emit_footprints()
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    co = np.empty(len(points.data.vertices) * 3, np.float32)
    points.data.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3).astype(np.float64)
    assert len(co) == int(RADIUS * math.pi / 0.5) + 1
    assert np.abs(co[:, 2] - height(co[:, 0], co[:, 1])).max() < 1e-3  # on the surface within 1 mm
    angle = path_angle(co)
    # Each foot's toes turn TOE_OUT out of the tangent: the left (side +1) to the left.
    toes = read(points, "side") * paths.TOE_OUT
    error = np.angle(np.exp(1j * (read(points, "heading") - (angle + math.pi / 2 + toes))))
    assert np.degrees(np.abs(error)).max() < 1.0
    # Each is born as its foot lands, a quarter stride before the walker passes it (the first on
    # the first frame): within a hundredth of a frame of the path's formula.
    frames_per_metre = (FRAMES[1] - FRAMES[0]) / (RADIUS * math.pi)
    passing = FRAMES[0] + angle / math.pi * (FRAMES[1] - FRAMES[0])
    landing = np.maximum(passing - 0.25 * 0.5 * frames_per_metre, FRAMES[0])
    assert np.abs(read(points, "birth_frame") - landing).max() < 0.01
    # Left and right alternate at half the stance from the path.
    centre = np.array([RADIUS * 0, -2.0])
    offset = np.hypot(co[:, 0] - centre[0], co[:, 1] - centre[1]) - RADIUS
    np.testing.assert_allclose(np.abs(offset), 0.1, atol=2e-3)
    assert (np.sign(offset) == -read(points, "side")).all()  # left of a left turn is inside the circle
    normals = read(points, "surface_normal", 3)
    assert (normals[:, 2] > 0).all()


def test_prints_off_the_terrain_are_skipped_and_counted():
    terrain = scenes.height_field(6.0, 12)
    walker = scenes.keyframed_walker(lambda f: (-2.0 + f * 0.1, 0.0, 1.0), range(0, 61))
    scenes.footprint_settings(terrain, walker, (0, 60), stride=0.5)
    assert bpy.ops.sandscape.emit_footprints() == {"FINISHED"}
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    planned = int(6.0 / 0.5) + 1
    assert points["skipped"] == planned - len(points.data.vertices) > 0


def test_a_particle_system_is_a_print_source():
    terrain = scenes.height_field(6.0, 12)
    emitter = scenes.keyframed_walker(lambda f: (-2.0 + 0.1 * f, 0.0, 0.5), range(1, 41), "Feet")
    mesh = bpy.data.meshes.new("Feet")
    mesh.from_pydata([(-0.01, -0.01, 0), (0.01, -0.01, 0), (0.01, 0.01, 0), (-0.01, 0.01, 0)], [],
                     [(0, 1, 2, 3)])
    feet = bpy.data.objects.new("Feet Mesh", mesh)
    bpy.context.scene.collection.objects.link(feet)
    feet.parent = emitter
    feet.modifiers.new("Steps", "PARTICLE_SYSTEM")
    particles = feet.particle_systems[0].settings
    particles.count, particles.frame_start, particles.frame_end, particles.lifetime = 12, 1, 30, 200
    particles.physics_type, particles.normal_factor = "NO", 0.0
    settings = scenes.footprint_settings(terrain, None, (1, 40), source="PARTICLES")
    settings.particle_object = feet
    assert bpy.ops.sandscape.emit_footprints() == {"FINISHED"}
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    births = read(points, "birth_frame")
    co = np.array([v.co for v in points.data.vertices])
    assert len(co) == 12 and (births >= 1).all() and (births <= 30).all()
    # Each print lies on the ground where the feet were on the first whole frame of its life
    # (a particle without physics sits where the emitter is at that frame), +- the 2 cm face.
    np.testing.assert_allclose(co[:, 0], -2.0 + 0.1 * np.ceil(births - 1e-4), atol=0.011)
    np.testing.assert_allclose(co[:, 2], 0.0, atol=1e-6)
    np.testing.assert_allclose(np.abs(read(points, "heading")), 0.0, atol=1e-3)  # moving along +X


def test_prints_sit_on_the_triangles_blender_renders_on_an_elevation_model():
    """A quad grid of 90 m cells (3 arc-seconds) with heights up to 40 m apart: each quad is far
    from planar, and which diagonal splits it decides the ground by metres. Reference: Blender's
    own ray cast on the evaluated terrain (its render triangles), not Sandscape's split."""
    heights = np.random.default_rng(3).uniform(-40.0, 40.0, (13, 13))
    terrain = scenes.height_field(1080.0, 12, lambda x, y: heights)
    frames = (1, 61)
    walker = scenes.keyframed_walker(lambda f: (-500.0 + 1000.0 * (f - 1) / 60, 37.0, 500.0),
                                     range(frames[0], frames[1] + 1))
    scenes.footprint_settings(terrain, walker, frames, stride=7.0, stance=3.0)
    assert bpy.ops.sandscape.emit_footprints() == {"FINISHED"}
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    origin = np.array(points.matrix_world.translation)
    co = np.empty(len(points.data.vertices) * 3, np.float32)
    points.data.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3).astype(np.float64) + origin
    normals = read(points, "surface_normal", 3)
    evaluated = terrain.evaluated_get(bpy.context.evaluated_depsgraph_get())
    rendered, rendered_normals = [], []
    for x, y, _ in co:
        hit, location, normal, _ = evaluated.ray_cast((x, y, 1000.0), (0.0, 0.0, -1.0))
        assert hit
        rendered.append(location.z)
        rendered_normals.append(normal)
    error = np.abs(co[:, 2] - np.array(rendered))
    assert len(co) > 100 and error.max() < 1e-3, error.max()
    np.testing.assert_allclose(normals, np.array(rendered_normals), atol=1e-4)
    # The test can tell: Sandscape's own split of the same faces (mathutils' polygon fill) puts
    # prints metres off the rendered ground.
    mesh = terrain.data
    own_split = BVHTree.FromPolygons([v.co for v in mesh.vertices], [p.vertices for p in mesh.polygons])
    other = np.array([own_split.ray_cast(Vector((x, y, 1000.0)), Vector((0.0, 0.0, -1.0)))[0].z
                      for x, y, _ in co])
    print(f"rendered ground vs prints: {error.max():.2e} m; vs polygon fill: "
          f"{np.abs(other - rendered).max():.2f} m")
    assert np.abs(other - np.array(rendered)).max() > 1.0


def test_each_painted_print_narrows_on_the_side_toward_the_walk():
    """Through the operators, on a walk along -Y (so no axis is the painter's default): a foot's
    arch curves in on its inner side, toward the line the walker follows; its outer edge runs
    straight. Reference: which side of the walk's line each print lies on, not print_axes."""
    terrain = scenes.height_field(6.0, 12)
    walker = scenes.keyframed_walker(lambda f: (0.3, 2.0 - 4.0 * (f - 1) / 40, 1.0), range(1, 42))
    scenes.footprint_settings(terrain, walker, (1, 41), stride=0.6, stance=0.24, resolution=1024)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    image = next(i for i in bpy.data.images if i.get("sandscape_image") == "print_map")
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    depth = pixels.reshape(height, width, 4)[..., 0]
    low, size = np.array(image["region_min"]), np.array(image["region_size"])
    texel = size[0] / width
    co = np.array([v.co for v in points.data.vertices])[:, :2] + np.array(points.matrix_world.translation)[:2]
    inner_areas, outer_areas = [], []
    for x, y in co[2:-2]:  # whole prints, away from the walk's ends
        # The arch's stretch along the walk (heel and toe centres of the default 27 cm sole):
        # rows of texels across it; pressed texels either side of the print's centre line.
        rows = np.arange(int((y - 0.05 - low[1]) / texel), int((y + 0.04 - low[1]) / texel) + 1)
        columns = np.arange(width)
        xs = low[0] + (columns + 0.5) * texel
        pressed = depth[rows][:, (xs > x - 0.15) & (xs < x + 0.15)] > 0.2 * depth.max()
        offsets = xs[(xs > x - 0.15) & (xs < x + 0.15)] - x
        toward_line = np.sign(0.3 - x) * offsets > 0
        inner_areas.append(pressed[:, toward_line].sum())
        outer_areas.append(pressed[:, ~toward_line].sum())
    inner, outer = np.array(inner_areas, float), np.array(outer_areas, float)
    print(f"arch rows: pressed texels toward the walk's line {inner.tolist()}, away {outer.tolist()}")
    assert len(inner) >= 3 and (inner < 0.85 * outer).all()
    assert inner.sum() < 0.75 * outer.sum()


def test_print_axes_point_the_lateral_axis_to_each_foot_s_inner_side():
    """On a 30 degree slope rising along +X, walking up it, across it and obliquely: a left foot's
    (side +1) lateral axis lies clockwise of the heading in plan, a right or unknown foot's
    counter-clockwise; the forward axis keeps the heading in plan. Up and across the slope the
    lateral axis is the heading turned a right angle. Reference: the heading turned by hand."""
    slope = math.radians(30.0)
    normal = (-math.sin(slope), 0.0, math.cos(slope))
    headings = np.radians([0.0, 90.0, 0.0, 90.0, 45.0, 45.0])
    sides = np.array([1, 1, -1, -1, 1, 0])
    forward = np.stack([np.cos(headings), np.sin(headings), 0 * headings], -1)
    along, lateral = paths.print_axes(forward, np.tile(normal, (len(sides), 1)), sides)
    plan = forward[:, :2]
    assert np.allclose(along / np.linalg.norm(along, axis=1)[:, None], plan, atol=1e-12)
    turn = plan[:, 0] * lateral[:, 1] - plan[:, 1] * lateral[:, 0]  # heading x lateral: < 0 clockwise
    assert np.all(np.sign(turn) == np.where(sides > 0, -1.0, 1.0))
    square = slice(0, 4)
    clockwise = np.stack([plan[square, 1], -plan[square, 0]], -1)
    expected = np.where((sides[square] > 0)[:, None], clockwise, -clockwise)
    unit = lateral[square] / np.linalg.norm(lateral[square], axis=1)[:, None]
    assert np.allclose(unit, expected, atol=1e-12)
