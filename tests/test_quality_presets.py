"""Quality presets: each sets exactly its measured settings, denoising in the compositor; the CLI
takes --preset."""

import pathlib
import re

import bpy
import pytest

README = pathlib.Path(__file__).resolve().parent.parent / "README.md"


def readme_preset(name):
    """(samples, volumes) of a preset as the README's preset table states them: volumes the step
    rate of ray-marched volumes, or "unbiased"."""
    volumes = r"(?:ray marched, step rate ([\d.]+)|(unbiased))"
    row = re.search(rf"^\| {name.title()} \| (\d+)[^|]*\| {volumes}[^|]*\|", README.read_text(), re.MULTILINE)
    assert row, f"no {name.title()} row in the README's preset table"
    return int(row.group(1)), float(row.group(2)) if row.group(2) else row.group(3)


@pytest.mark.parametrize("name", ["DRAFT", "PREVIEW", "FINAL"])
def test_preset_sets_its_settings(sandscape, name):
    presets = sandscape.addon.presets
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"  # a new file's: Cycles' preset asked for switches it
    assert bpy.ops.sandscape.apply_quality_preset(preset=name, engine="CYCLES") == {"FINISHED"}
    assert scene.render.engine == "CYCLES"
    settings = presets.PRESETS[name]
    for key, value in settings.items():
        if key == presets.DENOISE:
            continue
        if isinstance(value, str):
            assert getattr(scene.cycles, key) == value, key
        else:
            assert getattr(scene.cycles, key) == pytest.approx(value), key
    # What the README tells artists, not only the dict the operator reads.
    samples, volumes = readme_preset(name)
    assert scene.cycles.samples == samples
    if volumes == "unbiased":
        assert not scene.cycles.volume_biased
    else:
        assert scene.cycles.volume_biased and scene.cycles.volume_step_rate == pytest.approx(volumes)
    assert scene.sandscape_post.use_denoise
    tree = sandscape.addon.ownership.scene_compositor(scene)
    assert tree is not None and scene.compositing_node_group == tree
    denoiser = sandscape.addon.ownership.node(tree, sandscape.addon.post.DENOISE)
    if scene.cycles.use_denoising:
        # Cycles denoises the image; the tree takes the sparkles from its Noisy Image, once.
        assert denoiser is None and tree["built_for"] == "CYCLES denoised"
    else:
        # The compositor denoises all but the glints; Cycles' denoiser would smear them first.
        assert denoiser is not None
    # A scene without post effects gets only the denoising: no god rays without a sun.
    assert sandscape.addon.sun_screen.rays_node(tree) is None
    layer = scene.view_layers[0]
    assert layer.cycles.denoising_store_passes and layer.use_pass_glossy_direct
    assert any(aov.name == sandscape.addon.post.GLINT_AOV for aov in layer.aovs)


def test_sharp_pixel_filter_is_an_option_and_is_reported(sandscape):
    """Off by default: the artist's own pixel filter stays, and the report does not name one. On: a
    half-pixel Blackman-Harris, named in the report, the rest as the preset."""
    from devtools import operators

    cycles = bpy.context.scene.cycles
    bpy.context.scene.render.engine = "CYCLES"
    cycles.pixel_filter_type, cycles.filter_width = "GAUSSIAN", 2.5  # the artist's own
    result, reports = operators.run_execute("sandscape.apply_quality_preset", preset="DRAFT")
    assert result == {"FINISHED"} and cycles.samples == sandscape.addon.presets.PRESETS["DRAFT"]["samples"]
    assert (cycles.pixel_filter_type, cycles.filter_width) == ("GAUSSIAN", pytest.approx(2.5))
    assert "filter" not in reports[-1][1]
    result, reports = operators.run_execute("sandscape.apply_quality_preset", preset="PREVIEW",
                                            sharp_pixels=True)
    assert result == {"FINISHED"} and cycles.samples == sandscape.addon.presets.PRESETS["PREVIEW"]["samples"]
    assert (cycles.pixel_filter_type, cycles.filter_width) == ("BLACKMAN_HARRIS", pytest.approx(0.5))
    assert reports[-1][0] == {"INFO"}
    assert "pixel_filter_type BLACKMAN_HARRIS" in reports[-1][1] and "filter_width 0.5" in reports[-1][1]


def test_presets_get_cheaper_in_order(sandscape):
    presets = sandscape.addon.presets.PRESETS
    samples = [presets[name]["samples"] for name in ("DRAFT", "PREVIEW", "FINAL")]
    assert samples == sorted(samples) and samples[-1] < sandscape.addon.presets.BLENDER_DEFAULTS["samples"]
    # Cycles' denoiser only with unbiased volumes and adaptive sampling, where the bench put it.
    assert [name for name, settings in presets.items() if settings["use_denoising"]] == ["FINAL"]
    assert not presets["FINAL"]["volume_biased"] and presets["FINAL"]["use_adaptive_sampling"]


@pytest.mark.parametrize("name", ["DRAFT", "PREVIEW", "FINAL"])
def test_an_eevee_scene_gets_eevees_preset_and_stays_in_eevee(sandscape, name):
    """Issue 27: EEVEE's own presets (bench/eevee_quality.py); Cycles' settings are left alone, and
    the report says which engine's preset it was. Workbench is switched to Cycles, saying so."""
    from devtools import operators

    presets = sandscape.addon.presets
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    cycles_before = scene.cycles.samples
    result, reports = operators.run_execute("sandscape.apply_quality_preset", preset=name, sharp_pixels=True)
    assert result == {"FINISHED"} and scene.render.engine == "BLENDER_EEVEE"
    for key, value in presets.EEVEE_PRESETS[name].items():
        assert getattr(scene.eevee, key) == value, key
    assert scene.cycles.samples == cycles_before
    assert reports[-1][0] == {"INFO"} and "(EEVEE)" in reports[-1][1] and "left out" in reports[-1][1]
    scene.render.engine = "BLENDER_WORKBENCH"
    result, reports = operators.run_execute("sandscape.apply_quality_preset", preset=name)
    assert result == {"FINISHED"} and scene.render.engine == "CYCLES"
    assert "Workbench → Cycles" in reports[-1][1]
    result, reports = operators.run_execute("sandscape.apply_quality_preset", preset=name, engine="EEVEE")
    assert result == {"FINISHED"} and scene.render.engine == "BLENDER_EEVEE"
    assert "Cycles → EEVEE" in reports[-1][1] and scene.eevee.taa_render_samples == \
        presets.EEVEE_PRESETS[name]["taa_render_samples"]
    result, reports = operators.run_execute("sandscape.apply_quality_preset", preset=name, engine="CYCLES")
    assert result == {"FINISHED"} and "EEVEE → Cycles" in reports[-1][1]  # Blender's spelling, not "Eevee"


def test_eevee_presets_get_finer_in_order(sandscape):
    presets = sandscape.addon.presets.EEVEE_PRESETS
    order = [presets[name] for name in ("DRAFT", "PREVIEW", "FINAL")]
    samples = [p["taa_render_samples"] for p in order]
    tiles = [int(p["volumetric_tile_size"]) for p in order]
    assert samples == sorted(samples) and tiles == sorted(tiles, reverse=True)
