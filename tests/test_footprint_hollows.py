"""Prints read as hollows: under a low sun the wall facing it is lit, the wall nearest it is in
shade and casts its shadow over the floor, where a hollow in the sand puts them.

Reference: the painted print as a height field in numpy (the painter's own profile, on the
camera's pixel grid), lit by the sun with N.L and shadowed by marching toward it over the
heights. The render keeps the operator's displacement and swaps the surface for a white
diffuse under a sun of no angle and a black sky, seen straight down.
"""

import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

DEPTH, RIM = 0.05, 0.005  # metres: a walker in loose dry sand, a low soft rim
ELEVATION = math.radians(15.0)
SIZE, VIEW = 320, 1.6  # pixels, metres: 5 mm pixels
TOLERANCE = 0.03  # each region's mean brightness over the ground's, render against the height field


def diffuse_surface(material):
    """A white diffuse as the surface; the Displacement link stays."""
    tree = material.node_tree
    output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    tree.links.new(diffuse.outputs[0], output.inputs["Surface"])


def height_field_shading(heights, texel, light):
    """N.L of the height field, zero where the heights toward the sun rise above its ray."""
    dz_dy, dz_dx = np.gradient(heights, texel)
    normals = np.stack([-dz_dx, -dz_dy, np.ones_like(heights)], axis=-1)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    lit = np.clip(normals @ light, 0.0, None)
    rise = light[2] / math.hypot(light[0], light[1]) * texel  # the ray's climb per texel
    visible = np.ones_like(heights, dtype=bool)
    for step in range(1, int(DEPTH * 2 / rise) + 2):  # the sun shines along +Y: rows upward
        ahead = np.full_like(heights, -np.inf)
        ahead[:-step] = heights[step:]
        visible &= ahead <= heights + step * rise
    return lit * visible


@pytest.fixture
def print_shading(sandscape):
    footprints = sandscape.addon.footprints
    terrain = scenes.height_field(6.0, 12, name="Sand")
    walker = scenes.keyframed_walker(lambda f: (-1.5 + 0.1 * (f - 1), 0.0, 0.0), range(1, 32))
    settings = scenes.footprint_settings(terrain, walker, (1, 31), stride=0.7, variation=0.0,
                                         noise_amount=0.0, depth=DEPTH, rim=RIM, resolution=1024)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    diffuse_surface(terrain.active_material)
    points = footprints.read_points(next(o for o in bpy.data.objects
                                         if o.get("sandscape_object") == "footprints"))
    middle = int(np.argsort(points["co"][:, 0])[len(points["co"]) // 2])
    centre = points["co"][middle, :2]
    scene = readback.cycles_scene(resolution=(SIZE, SIZE), samples=1)
    scenes.sharp_pixels(scene)
    scene.world = None
    scene.cycles.max_bounces = 0
    scene.frame_set(31)
    light = np.array([0.0, math.cos(ELEVATION), math.sin(ELEVATION)])
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 1.0, 0.0
    sun.rotation_euler = (-(math.pi / 2 - ELEVATION), 0.0, 0.0)  # pointing down toward -Y
    scene.collection.objects.link(sun)
    scenes.camera("ORTHO", location=(*centre, 5.0), ortho_scale=VIEW)
    rendered = readback.render(scene)[..., 0].astype(np.float64)
    # The twin: the same prints painted on the camera's pixel centres.
    texel = VIEW / SIZE
    region = sandscape.core.footprints.Region(centre[0] - VIEW / 2, centre[1] - VIEW / 2, texel, SIZE, SIZE)
    forward, lateral = footprints.print_axes(points)
    image = sandscape.core.footprints.paint(points["co"][:, :2], forward, lateral, points["birth_frame"],
                                            points["depth_scale"], region, footprints.sole_from(settings),
                                            footprints.frame_range(scene, settings))
    heights = RIM * image[..., 1].astype(np.float64) - DEPTH * image[..., 0]
    expected = height_field_shading(heights, texel, light)
    offsets = region.y0 + (np.arange(SIZE) + 0.5) * texel - centre[1]  # rows: y from the print's centre
    side = np.broadcast_to(offsets[:, None], heights.shape)
    along = np.broadcast_to(offsets[None, :], heights.shape)  # columns: x (the view is square)
    ground = (image[..., 0] == 0) & (image[..., 1] == 0)
    this_print = np.abs(along) < 0.35  # not its neighbours, 0.7 m off on the other foot
    sloping = (image[..., 0] > 0.1) & (image[..., 0] < 0.9)
    wall = this_print & sloping & (np.abs(side) > settings.foot_width / 2)
    regions = {"floor": this_print & (image[..., 0] >= 0.999), "wall facing the sun": wall & (side < 0),
               "wall nearest the sun": wall & (side > 0)}
    return rendered / rendered[ground].mean(), expected / expected[ground].mean(), regions


def test_walls_and_floor_fall_where_a_hollow_puts_them(print_shading):
    rendered, expected, regions = print_shading
    for name, where in regions.items():
        print(f"{name}: {where.sum()} pixels, rendered {rendered[where].mean():.3f} of the ground, "
              f"height field {expected[where].mean():.3f}")
        assert abs(rendered[where].mean() - expected[where].mean()) <= TOLERANCE
    # A hollow, not a boat: its floor in shadow, the wall across from the sun brighter than the sand.
    assert rendered[regions["floor"]].mean() < 0.5
    assert rendered[regions["wall facing the sun"]].mean() > 1.3
    assert rendered[regions["wall nearest the sun"]].mean() < 0.5
