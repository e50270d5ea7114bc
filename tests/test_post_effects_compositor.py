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
    assert np.abs(result[..., :3] - expected[..., :3]).max() < 1e-4
    if threshold == 1e9:
        scale = max(1.0, float(np.abs(image).max()))  # gate shut: untouched, to float32 round-off
        assert np.abs(result[..., :3] - image[..., :3]).max() <= 1e-6 * scale


def test_gated_blur_preserves_energy_with_the_gate_open(groups, helper):
    group = helper.ensure_group(groups("gated_blur"))
    image = synthetic(1, border=2)  # the kernel never reaches the edge, so nothing leaves the frame
    result = readback.composite_group(group, {"Image": image, "Threshold": -1.0}, "Image", (W, H))
    assert abs(result[..., :3].sum() / image[..., :3].sum() - 1.0) < 1e-6


@pytest.mark.parametrize("sun, samples, density, weight, decay", [
    ((0.5, 0.5), 8, 0.9, 0.05, 0.97),
    ((0.8, 0.3), 16, 0.7, 0.1, 0.9),
    ((-0.2, 1.4), 8, 1.0, 0.05, 1.0),  # the sun off screen
])
def test_god_rays_match_their_twin(groups, helper, sun, samples, density, weight, decay):
    group = helper.ensure_group(groups("god_rays").Builder(samples))
    occlusion = synthetic(2)
    values = {"Occlusion": occlusion, "Sun": (*sun, 0.0), "Density": density, "Weight": weight,
              "Decay": decay, "Exposure": 1.5, "Intensity": 0.8}
    result = readback.composite_group(group, values, "Rays", (W, H))
    expected = post.god_rays(occlusion[..., :3], sun, samples, density, weight, decay, 1.5 * 0.8)
    assert np.abs(result[..., :3] - expected).max() < 1e-3
    assert expected.max() > 0.1  # there are rays to compare
