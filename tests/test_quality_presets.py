"""Quality presets: each sets exactly its measured settings; the CLI takes --preset."""

import bpy
import pytest


@pytest.mark.parametrize("name", ["DRAFT", "PREVIEW", "FINAL"])
def test_preset_sets_its_settings(sandscape, name):
    assert bpy.ops.sandscape.apply_quality_preset(preset=name) == {"FINISHED"}
    settings = sandscape.blender.presets.PRESETS[name]
    cycles = bpy.context.scene.cycles
    for key, value in settings.items():
        if isinstance(value, str):
            assert getattr(cycles, key) == value, key
        else:
            assert getattr(cycles, key) == pytest.approx(value), key


def test_presets_get_cheaper_in_order(sandscape):
    presets = sandscape.blender.presets.PRESETS
    samples = [presets[name]["samples"] for name in ("DRAFT", "PREVIEW", "FINAL")]
    assert samples == sorted(samples) and samples[-1] < sandscape.blender.presets.BLENDER_DEFAULTS["samples"]
    # Measured: OIDN smears glints, so no preset denoises (bench/RESULTS.md, Quality).
    assert not any(settings["use_denoising"] for settings in presets.values())
