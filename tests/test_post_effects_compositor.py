"""Compositor groups against their numpy twins on synthetic float images."""

import importlib

import numpy as np
import pytest

from core import post
from devtools import readback

W, H = 48, 32


@pytest.fixture
def helper(sandscape):
    return sandscape.node_groups.helper


@pytest.fixture
def groups(sandscape):
    def module(name):
        return importlib.import_module(f"{sandscape.__name__}.node_groups.{name}")
    return module


# Float32 round-off on values up to 4: the README's figures are these.
BLUR_TOLERANCE, RAYS_TOLERANCE = 2e-6, 2e-5


def synthetic(seed=0, border=0):
    rng = np.random.default_rng(seed)
    image = np.zeros((H, W, 4))
    image[..., :3] = rng.random((H, W, 3)) ** 3 * 4.0  # bright specks on dark, HDR
    image[::7, :, :3] = 0.0
    if border:
        image[:border], image[-border:], image[:, :border], image[:, -border:] = 0, 0, 0, 0
    image[..., 3] = 1.0
    return image


@pytest.mark.parametrize("threshold", [0.0, 0.05, 0.5, 1e9])
def test_gated_blur_matches_its_twin(groups, helper, threshold):
    group = helper.ensure_group(groups("gated_blur"))
    image = synthetic()
    result = readback.composite_group(group, {"Image": image, "Threshold": threshold}, "Image", (W, H))
    expected = post.gated_blur(image, threshold)
    assert np.abs(result[..., :3] - expected[..., :3]).max() < BLUR_TOLERANCE
    if threshold == 1e9:
        scale = max(1.0, float(np.abs(image).max()))  # gate shut: untouched, to float32 round-off
        assert np.abs(result[..., :3] - image[..., :3]).max() <= 1e-6 * scale


def sky_with_a_cloud():
    """An environment pass: sky of 1 with a dark disc (a cloud hiding it), and a faint haze ramp."""
    rows, cols = np.mgrid[:H, :W]
    guide = np.ones((H, W, 4))
    guide[..., :3] *= (1.0 + 0.002 * cols)[..., None]  # haze: 0.2 % a pixel, far under Edge
    guide[(rows - 16) ** 2 + (cols - 20) ** 2 < 64, :3] = 0.02
    return guide


@pytest.mark.parametrize("edge", [0.1, 0.5])
def test_gated_blur_keeps_the_guides_outlines_sharp(groups, helper, edge):
    """The guide's outline (a cloud against the sky) stays sharp, the haze and the flat sky are
    blurred as before; the compositor as its twin."""
    group = helper.ensure_group(groups("gated_blur"))
    image, guide = synthetic(3), sky_with_a_cloud()
    values = {"Image": image, "Threshold": 0.0, "Guide": guide, "Edge": edge}
    result = readback.composite_group(group, values, "Image", (W, H))
    expected = post.gated_blur(image, 0.0, guide, edge)
    assert np.abs(result[..., :3] - expected[..., :3]).max() < BLUR_TOLERANCE
    outline = post.guide_edges(guide, edge)
    rows, cols = np.mgrid[:H, :W]
    ring = np.abs(np.hypot(rows - 16, cols - 20) - 8.0) < 1.0
    assert outline[ring].mean() > 0.9 and not outline[:, 35:].any()  # the disc's rim, not the haze
    unguided = post.gated_blur(image, 0.0)
    assert np.array_equal(expected[outline], image[outline])
    assert np.array_equal(expected[~outline], unguided[~outline])


def test_gated_blur_preserves_energy_with_the_gate_open(groups, helper):
    group = helper.ensure_group(groups("gated_blur"))
    image = synthetic(1, border=2)  # the kernel never reaches the edge, so nothing leaves the frame
    result = readback.composite_group(group, {"Image": image, "Threshold": -1.0}, "Image", (W, H))
    assert abs(result[..., :3].sum() / image[..., :3].sum() - 1.0) < 1e-6


@pytest.mark.parametrize("sun, samples, density, weight, decay", [
    ((0.5, 0.5), 8, 0.9, 0.05, 0.97),
    ((0.8, 0.3), 16, 0.7, 0.1, 0.9),
    ((-0.2, 1.4), 8, 1.0, 0.05, 1.0),  # the sun off screen
    ((0.3, 0.6), 1024, 0.9, 0.01, 0.999),  # a slider's end: the same nodes
])
def test_god_rays_match_their_twin(groups, helper, sun, samples, density, weight, decay):
    group = helper.ensure_group(groups("god_rays"))
    occlusion = synthetic(2)
    values = {"Occlusion": occlusion, "Sun": (*sun, 0.0), "Samples": float(samples), "Density": density,
              "Weight": weight, "Decay": decay, "Exposure": 1.5, "Intensity": 0.8}
    result = readback.composite_group(group, values, "Rays", (W, H))
    expected = post.god_rays(occlusion[..., :3], sun, samples, density, weight, decay, 1.5 * 0.8)
    # Float32 sums of up to 257 taps: relative to the brightest ray, at least RAYS_TOLERANCE.
    assert np.abs(result[..., :3] - expected).max() < max(RAYS_TOLERANCE, 1e-5 * expected.max())
    assert expected.max() > 0.1  # there are rays to compare


def test_god_rays_have_as_many_nodes_at_any_sample_count(sandscape, groups, helper):
    """One group for every Samples value (32 samples had made 267 nodes, 1024 about 8,000, each
    count its own group)."""
    group = helper.ensure_group(groups("god_rays"))
    assert len(group.nodes) < 150 and not any(i.name == "Samples" and i.in_out == "OUTPUT"
                                               for i in group.interface.items_tree)


def disc(sun, radius, size=(160, 90)):
    """A soft sun disc seen against the sky: 1 inside, easing to 0 over a pixel."""
    width, height = size
    v, u = (np.indices((height, width)) + 0.5) / np.array([height, width])[:, None, None]
    distance = np.hypot((u - sun[0]) * width / height, v - sun[1])
    return np.clip((radius - distance) * height + 0.5, 0.0, 1.0)[..., None] * np.ones(3)


@pytest.mark.parametrize("samples, decay, peak, totals", [
    (32, 0.97, 0.03, 0.10),  # the defaults (measured 0.022, 0.909)
    (16, 1.0, 0.06, 0.20),  # no decay: the seed's 16 coarse samples reach further (0.052, 0.809)
    (64, 0.95, 0.12, 0.12),  # a strong decay (0.114, 1.101)
])
def test_god_rays_follow_the_seeds_sum(samples, decay, peak, totals):
    """The group's 256 geometric taps against the seed's own N-sample sum, on a sun disc: the
    largest difference in a pixel, as a share of the seed's brightest, and the rays' total light.
    The taps match the seed's weights at both ends of its span; between them a strong decay
    (N·ln(1/Decay) above 3) falls off more slowly than the seed's, and the seed's coarse samples
    sit half a step further out than a continuous sum would."""
    sun = (0.62, 0.58)
    occlusion = disc(sun, 0.08)
    ours = post.god_rays(occlusion, sun, samples, 0.9, 0.1, decay)
    seed = post.god_rays_seed(occlusion, sun, samples, 0.9, 0.1, decay)
    print(f"N {samples}, decay {decay}: largest difference {np.abs(ours - seed).max() / seed.max():.4f} "
          f"of the peak, totals {ours.sum() / seed.sum():.4f}")
    assert np.abs(ours - seed).max() <= peak * seed.max()
    assert abs(ours.sum() / seed.sum() - 1.0) <= totals
