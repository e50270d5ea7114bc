"""Quality presets: each sets exactly its measured settings, denoising in the compositor; the CLI
takes --preset."""

import pathlib
import re

import bpy
import pytest

README = pathlib.Path(__file__).resolve().parent.parent / "README.md"


def readme_preset(name):
    """(samples, volume step rate) of a preset as the README's preset table states them."""
    row = re.search(rf"^\| {name.title()} \| (\d+)[^|]*\| ray marched, step rate ([\d.]+) \|",
                    README.read_text(), re.MULTILINE)
    assert row, f"no {name.title()} row in the README's preset table"
    return int(row.group(1)), float(row.group(2))


@pytest.mark.parametrize("name", ["DRAFT", "PREVIEW", "FINAL"])
def test_preset_sets_its_settings(sandscape, name):
    presets = sandscape.addon.presets
    assert bpy.ops.sandscape.apply_quality_preset(preset=name) == {"FINISHED"}
    settings = presets.PRESETS[name]
    scene = bpy.context.scene
    for key, value in settings.items():
        if key == presets.DENOISE:
            continue
        if isinstance(value, str):
            assert getattr(scene.cycles, key) == value, key
        else:
            assert getattr(scene.cycles, key) == pytest.approx(value), key
    # What the README tells artists, not only the dict the operator reads.
    assert (scene.cycles.samples, scene.cycles.volume_step_rate) == pytest.approx(readme_preset(name))
    # The compositor denoises all but the glints; Cycles' denoiser would smear them first.
    assert scene.sandscape_post.use_denoise and not scene.cycles.use_denoising
    tree = sandscape.addon.ownership.scene_compositor(scene)
    assert tree is not None and scene.compositing_node_group == tree
    assert sandscape.addon.ownership.node(tree, sandscape.addon.post.DENOISE) is not None
    # A scene without post effects gets only the denoising: no god rays without a sun.
    assert sandscape.addon.sun_screen.rays_node(tree) is None
    layer = scene.view_layers[0]
    assert layer.cycles.denoising_store_passes and layer.use_pass_glossy_direct
    assert any(aov.name == sandscape.addon.post.GLINT_AOV for aov in layer.aovs)


def test_presets_get_cheaper_in_order(sandscape):
    presets = sandscape.addon.presets.PRESETS
    samples = [presets[name]["samples"] for name in ("DRAFT", "PREVIEW", "FINAL")]
    assert samples == sorted(samples) and samples[-1] < sandscape.addon.presets.BLENDER_DEFAULTS["samples"]
    assert not any(settings["use_denoising"] for settings in presets.values())
