"""The cloud groups against their numpy twins (core/clouds.py, core/noise_perlin.py) by bake:
Blender's Noise and Voronoi textures, the Weather Map and the Cloud Density, each evaluated
where Cycles shaded (a Position bake of the same plane). Also the twins' own maths: height
gradients, coverage edge, phase normalisation.
"""

import math

import bpy
import numpy as np
import pytest

from core import clouds as twin
from core import noise_perlin
from devtools import readback, scenes

RES = 48
NOISE_TOLERANCE = 2e-5  # float32 noise of coordinates up to ~100, evaluated in another order
GROUP_TOLERANCE = 5e-4  # the noise tolerance through the coverage ramp, whose slope is 1.5 / 0.06 = 25


def bake_on_plane(material, size, height, offset=(0.0, 0.0)):
    """(values (RES, RES), world positions (RES, RES, 3)) of a material's emission on a plane."""
    plane = readback.uv_plane(size)
    plane.location = (offset[0], offset[1], height)
    bpy.context.view_layer.update()
    plane.data.materials.append(material)
    baked, world = readback.bake_emit_with_positions(plane, material, RES)
    return baked[..., 0].astype(np.float64), world


def texture_material(node_type, output, scale, **props):
    material = bpy.data.materials.new("Texture Probe")
    tree = material.node_tree
    tree.nodes.clear()
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    texture = tree.nodes.new(node_type)
    for key, value in props.items():
        setattr(texture, key, value)
    texture.inputs["Scale"].default_value = scale
    if "Distortion" in texture.inputs:
        texture.inputs["Distortion"].default_value = 0.0
    emission = tree.nodes.new("ShaderNodeEmission")
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(geometry.outputs["Position"], texture.inputs["Vector"])
    tree.links.new(texture.outputs[output], emission.inputs["Color"])
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    return material, texture


@pytest.mark.parametrize("detail", [0.0, 2.0, 2.5])
def test_noise_2d_matches_twin(detail):
    material, texture = texture_material("ShaderNodeTexNoise", "Fac", 3.0, noise_dimensions="2D")
    texture.inputs["Detail"].default_value = detail
    baked, world = bake_on_plane(material, 8.0, 0.3, (-1.3, 2.1))
    expected = noise_perlin.fbm(noise_perlin.perlin_2d, world[..., :2] * 3.0, detail)
    assert np.abs(baked - expected).max() < NOISE_TOLERANCE


def test_noise_3d_matches_twin():
    material, texture = texture_material("ShaderNodeTexNoise", "Fac", 2.0, noise_dimensions="3D")
    texture.inputs["Detail"].default_value = 3.0
    baked, world = bake_on_plane(material, 6.0, 0.37, (0.4, -2.2))
    expected = noise_perlin.fbm(noise_perlin.perlin_3d, world * 2.0, 3.0)
    assert np.abs(baked - expected).max() < NOISE_TOLERANCE


def test_voronoi_matches_twin():
    material, texture = texture_material("ShaderNodeTexVoronoi", "Distance", 4.0, voronoi_dimensions="3D",
                                         feature="F1", distance="EUCLIDEAN")
    texture.inputs["Detail"].default_value = 0.0
    baked, world = bake_on_plane(material, 4.0, -0.61, (-3.0, 1.0))
    expected = noise_perlin.voronoi_f1(world * 4.0)
    assert np.abs(baked - expected).max() < NOISE_TOLERANCE


WIND = (4.0, -2.0, 0.0)
FRAME, FPS = 30.0, 24.0


def group_bake(sandscape, builder, output, values, size, height, offset=(0.0, 0.0)):
    group = sandscape.node_groups.helper.ensure_group(builder)
    material = scenes.group_material(group, values, output)
    return bake_on_plane(material, size, height, offset)


@pytest.mark.parametrize("coverage", [0.2, 0.7])
def test_weather_map_matches_twin(sandscape, coverage):
    values = {"Coverage": coverage, "Map Scale": 3.0, "Seed": 2.0, "Wind": WIND, "Frame": FRAME, "FPS": FPS,
              "Precipitation": 0.3, "Mixed Types": 1.0}
    cover, world = group_bake(sandscape, sandscape.node_groups.weather_map, "Coverage", values, 12.0, 0.0)
    carried = world - twin.drift(WIND, FRAME / FPS)
    expected = twin.map_coverage(twin.weather_noise(carried[..., :2], 3.0, 2), coverage)
    assert np.abs(cover - expected).max() < GROUP_TOLERANCE
    assert 0.05 < (cover > 0.5).mean() < 0.95  # both clearer and cloudier ground in the bake
    kind, world = group_bake(sandscape, sandscape.node_groups.weather_map, "Type", values, 12.0, 0.0)
    carried = world - twin.drift(WIND, FRAME / FPS)
    assert np.abs(kind - twin.mixed_type(carried[..., :2], 3.0, 2)).max() < GROUP_TOLERANCE


DENSITY_VALUES = {"Base": 1.0, "Thickness": 2.0, "Density": 1.0, "Shape Scale": 1.5, "Detail Scale": 0.4,
                  "Erosion": 0.4, "Curl": 0.5, "Skew": 0.3, "Seed": 1.0, "Wind": WIND, "Frame": FRAME,
                  "FPS": FPS, "Coverage": 0.8, "Precipitation": 0.25}


@pytest.mark.parametrize(("height", "cloud_type"), [(1.3, 0.5), (2.1, 0.9), (1.15, 0.1)])
def test_cloud_density_matches_twin(sandscape, height, cloud_type):
    values = {**DENSITY_VALUES, "Type": cloud_type}
    baked, world = group_bake(sandscape, sandscape.node_groups.cloud_density, "Density", values, 5.0, height)
    parameters = {"base": 1.0, "thickness": 2.0, "coverage": None, "map_scale": None, "shape_scale": 1.5,
                  "detail_scale": 0.4, "erosion": 0.4, "curl": 0.5, "skew": 0.3, "density": 1.0,
                  "precipitation": 0.25, "cloud_type": cloud_type, "seed": 1, "wind": WIND,
                  "time": FRAME / FPS}
    expected = twin.shaped_density(world, parameters, cover=0.8)
    assert expected.max() > 0.05, "the bake should hold cloud"
    assert np.abs(baked - expected).max() < GROUP_TOLERANCE


def test_height_gradients_follow_the_seed():
    h = np.linspace(0.0, 1.0, 1001)
    for name, (a, b, c, d) in twin.GRADIENTS.items():
        def profile(x, name=name):
            return twin.height_gradient(x, twin.TYPE_VALUES[name])
        assert profile(0.0) == 0.0 and profile(b) == 1.0 and profile(c) == 1.0, name
        assert profile(d) == 0.0 or d == 1.0, name
        assert profile((a + b) / 2) == pytest.approx(0.5) and profile((c + d) / 2) == pytest.approx(0.5), name
        values = profile(h)
        assert np.all(np.diff(values[h <= b]) >= 0) and np.all(np.diff(values[h >= c]) <= 0), name
    # Between cumulus and cumulonimbus the four numbers stay between theirs (the seed's
    # unclamped 2t would push them past cumulonimbus's).
    blend = twin.type_gradient(0.75)
    low, high = np.array(twin.GRADIENTS["CUMULUS"]), np.array(twin.GRADIENTS["CUMULONIMBUS"])
    assert np.all(blend >= np.minimum(low, high) - 1e-12) and np.all(blend <= np.maximum(low, high) + 1e-12)


def test_dual_lobe_phase_is_normalised():
    for forward, back, weight in ((0.8, -0.3, 0.3), (0.5, -0.5, 0.5), (0.95, 0.0, 0.1), (0.0, -0.9, 1.0)):
        total = twin.sphere_integral(lambda mu, f=forward, b=back, w=weight: twin.dual_lobe(mu, f, b, w))
        assert total == pytest.approx(1.0, abs=1e-6)
    # The seed's 1 / (4 x 3.1415) the wrong way up would integrate to (4 pi)^2, not 1.
    assert twin.sphere_integral(lambda mu: twin.henyey_greenstein(mu, 0.6)) == pytest.approx(1.0, abs=1e-9)


def test_coverage_edge_is_monotone_and_bounded():
    coverage = np.linspace(0.0, 1.0, 101)
    edge = twin.coverage_edge(coverage)
    assert np.all(np.diff(edge) < 0)
    assert edge[0] > 1.0 and edge[-1] < 0.0  # beyond the noise: no cloud, cloud everywhere
    assert math.isfinite(edge[0]) and math.isfinite(edge[-1])


def test_coverage_edge_splits_the_map_noise_by_coverage():
    """The fit against the noise it stands for: the share of the map above the edge."""
    points = np.random.default_rng(3).uniform(-400.0, 400.0, (400_000, 2))
    values = noise_perlin.fbm(noise_perlin.perlin_2d, points, twin.MAP_DETAIL)
    for coverage in (0.02, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.9, 0.98):
        share = float((values > twin.coverage_edge(coverage)).mean())
        assert share == pytest.approx(coverage, abs=0.006), coverage
    assert not (values > twin.coverage_edge(0.0)).any() and (values > twin.coverage_edge(1.0)).all()
