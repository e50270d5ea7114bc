"""Prints land under the feet and keep their size on terrains the way artists have them: tilted
and turned, stretched, scaled, moved, imported Y-up. Gravity is world -Z.

Reference, analytic: the walker goes straight along world +X at a constant height above the
ground, so the contacts are a stride apart along its path (x = x0 + k * stride / sqrt(1 + a^2)
where the ground rises by a along x), at y = +-stance / 2 (left first), and the ground under a
contact is where the terrain's plane, transformed, meets the vertical line through it.
"""

import math

import bpy
import numpy as np
import pytest

from devtools import scenes

STRIDE, STANCE, FOOT = 0.7, 0.2, 0.27
X0, X1, FRAMES = -2.0, 2.0, 41
POSITION_TOLERANCE = 0.01  # metres, in x and y: the "within 1 cm"
HEIGHT_TOLERANCE = 0.001  # metres: the ground under a flat plane is exact up to float32
LENGTH_TOLERANCE = 0.10  # the sole's length on the map, relative to Foot Length

TERRAINS = {
    "tilted 15 degrees and turned": {"rotation": (math.radians(15), 0.0, math.radians(30))},
    "stretched (2, 1, 1)": {"scale": (2.0, 1.0, 1.0)},
    "scaled (3, 3, 3)": {"scale": (3.0, 3.0, 3.0)},
    "moved and turned": {"location": (1.0, -1.0, 2.0), "rotation": (0.0, 0.0, math.radians(-70))},
    "Y-up import": {"y_up": True},
}


def terrain_for(case):
    """A flat plane of 8 m (in its own units) with the case's transform; a Y-up import has its
    plane in local XZ and a 90 degree X rotation, as glTF and FBX importers leave it."""
    spec = TERRAINS[case]
    terrain = scenes.height_field(8.0, 32, name="Ground")
    if spec.get("y_up"):
        mesh = terrain.data
        co = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get("co", co)
        co = co.reshape(-1, 3)
        co[:, [1, 2]] = co[:, [2, 1]] * (1, -1)  # (x, y, 0) -> (x, 0, -y): the plane in local XZ
        mesh.vertices.foreach_set("co", co.ravel())
        mesh.update()
        terrain.rotation_euler = (math.radians(90), 0.0, 0.0)
    terrain.location = spec.get("location", (0.0, 0.0, 0.0))
    terrain.rotation_euler = spec.get("rotation", terrain.rotation_euler)
    terrain.scale = spec.get("scale", (1.0, 1.0, 1.0))
    bpy.context.view_layer.update()
    return terrain


def ground_plane(terrain):
    """A point and the upward unit normal of the terrain's plane, in world space."""
    mesh, world = terrain.data, terrain.matrix_world
    a, b, c = (world @ mesh.vertices[i].co for i in (0, 32, 33 * 32))
    normal = (b - a).cross(c - a).normalized()
    return a, normal if normal.z > 0 else -normal


def ground_height(terrain, x, y):
    """World z where the vertical through (x, y) meets the terrain's plane."""
    point, normal = ground_plane(terrain)
    return point.z - (normal.x * (x - point.x) + normal.y * (y - point.y)) / normal.z


@pytest.fixture(params=list(TERRAINS))
def painted(request):
    terrain = terrain_for(request.param)
    # The walker 0.9 m above the ground it crosses, straight along world +X.
    walker = scenes.keyframed_walker(
        lambda f: (X0 + (X1 - X0) * (f - 1) / (FRAMES - 1), 0.0,
                   ground_height(terrain, X0 + (X1 - X0) * (f - 1) / (FRAMES - 1), 0.0) + 0.9),
        range(1, FRAMES + 1))
    scenes.footprint_settings(terrain, walker, (1, FRAMES), stride=STRIDE, stance=STANCE, foot_length=FOOT,
                              variation=0.0, resolution=1024)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    points = next(o for o in bpy.context.scene.objects if o.get("sandscape_object") == "footprints")
    return request.param, terrain, points


def test_prints_land_straight_under_the_feet(painted):
    case, terrain, points = painted
    co = np.array([points.matrix_world @ v.co for v in points.data.vertices])
    _, normal = ground_plane(terrain)
    horizontal_stride = STRIDE / math.sqrt(1.0 + (normal.x / normal.z) ** 2)
    k = np.arange(len(co))
    expected = np.stack([X0 + k * horizontal_stride, np.where(k % 2 == 0, STANCE / 2, -STANCE / 2)], 1)
    assert len(co) == int((X1 - X0) / horizontal_stride) + 1, case
    assert np.abs(co[:, :2] - expected).max() <= POSITION_TOLERANCE, case
    heights = [ground_height(terrain, x, y) for x, y in co[:, :2]]
    assert np.abs(co[:, 2] - heights).max() <= HEIGHT_TOLERANCE, case


def test_sole_keeps_its_length_in_world_metres(painted):
    case, terrain, points = painted
    image = next(i for i in bpy.data.images if i.get("sandscape_image") == "print_map")
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    # The sole's outline: the slumped wall is half pressed there (its top as far out as its foot in).
    pressed = pixels.reshape(height, width, 4)[..., 3] >= 0.5
    texel, low = image["texel"], np.array(image["region_min"])
    # The first print: alone on its row through the centre, the walk along the map's X.
    centre = np.array(points.data.vertices[0].co[:2])
    col, row = ((centre - low) / texel).astype(int)
    reach = int(FOOT / texel)
    run = pressed[row, max(col - reach, 0):col + reach]
    length = run.sum() * texel
    # On a slope the sole lies along the ground: seen from above (the map) it is shorter by the
    # cosine of the rise along the walk.
    _, normal = ground_plane(terrain)
    seen_from_above = FOOT / math.sqrt(1.0 + (normal.x / normal.z) ** 2)
    print(f"{case}: sole {length:.4f} m, expected {seen_from_above:.4f} m")
    assert abs(length - seen_from_above) <= LENGTH_TOLERANCE * FOOT, (case, length)
