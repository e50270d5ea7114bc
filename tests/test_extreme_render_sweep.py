"""Render sweep at extreme settings across every operator: no NaN or Inf reaches a pixel.

The demo scene is built once per settings group. Each numeric setting then goes, alone, to
each end of its slider range (or to +-1e4 where the slider is unbounded), the group's operator
reruns, and a tiny frame renders through the compositor. Last, every setting of the group
goes to its lower ends at once, then to its upper ends. An operator may refuse a value
(an ERROR report and CANCELLED); it may not fail with a traceback, and the frame must stay finite.
"""

import bpy
import numpy as np
import pytest

from devtools import operators, readback

pytestmark = pytest.mark.stress  # make stress, not make test

UNBOUNDED = 1e4  # stands for "as far as a user can type" where the slider has no end
# Map sizes whose memory is tested alone (tests/test_footprint_stress.py: 16384 texels) stay
# at 1024 here, so the sweep runs in seconds.
CAPS = {"resolution": 1024, "image_resolution": 1024}
FRAME = 200  # the demo still: walker, prints, low sun in view


def ends(prop):
    """The two extreme values of a numeric RNA property: slider ends, capped and made finite."""
    low, high = prop.soft_min, prop.soft_max
    low = low if abs(low) < 1e9 else -UNBOUNDED
    high = high if abs(high) < 1e9 else UNBOUNDED
    high = min(high, CAPS.get(prop.identifier, high))
    if prop.type == "INT":
        low, high = int(low), int(high)
    return low, high


def numeric(rna_type):
    return [p for p in rna_type.properties if p.type in {"INT", "FLOAT"} and p.identifier != "rna_type"]


def typed(prop, value):
    return (value,) * prop.array_length if prop.array_length else value


def settings_cases(rna_type):
    """(label, {identifier: value}) for each end of each setting, then all lows and all highs."""
    props = numeric(rna_type)
    cases = [(f"{p.identifier}={value:g}", {p.identifier: typed(p, value)})
             for p in props for value in ends(p)]
    booleans = [p.identifier for p in rna_type.properties if p.type == "BOOLEAN"]
    for side, label in ((0, "all low"), (1, "all high")):
        values = {p.identifier: typed(p, ends(p)[side]) for p in props}
        values.update({name: bool(side) for name in booleans})
        cases.append((label, values))
    return cases


@pytest.fixture
def desert(demo_scene):
    scene = demo_scene
    scene.render.resolution_x, scene.render.resolution_y = 48, 27
    scene.render.resolution_percentage = 100
    scene.cycles.samples = 2
    # Keep the render's evaluated scene between the sweep's renders (only what a case changed is
    # evaluated again): otherwise every render would rebuild the demo's cloud grid.
    scene.render.use_persistent_data = True
    scene.frame_set(FRAME)
    return scene


def render_is_finite(scene):
    # Rendered as a one-frame range: the god rays' keys are then one step, not the film's 240.
    # The walk keeps the film's range (the prints are painted over it).
    kept = scene.frame_start, scene.frame_end
    scene.frame_start = scene.frame_end = FRAME
    try:
        pixels = readback.render(scene)
    finally:
        scene.frame_start, scene.frame_end = kept
    return bool(np.isfinite(pixels).all())


def sweep(scene, cases, run):
    """Run every case; the labels whose frame was not finite, and how many the operator refused."""
    bad, refused = [], 0
    for label, values in cases:
        try:
            outcome = run(values)
        except RuntimeError as error:  # bpy.ops raises an operator's ERROR report
            assert operators.is_refusal(error), (label, str(error))
            outcome = {"CANCELLED"}
        assert outcome in ({"FINISHED"}, {"CANCELLED"}), (label, outcome)
        refused += outcome == {"CANCELLED"}
        if not render_is_finite(scene):
            bad.append(label)
    # Mostly carried out, not refused: otherwise the sweep would only render the demo again.
    assert refused < len(cases) / 2, f"{refused} of {len(cases)} cases refused"
    return bad


@pytest.mark.parametrize("group, operator", [("sandscape_footprints", "paint_footprints"),
                                             ("sandscape_atmosphere", "add_atmosphere"),
                                             ("sandscape_post", "add_post_effects")])
def test_scene_settings_at_their_extremes_render_finite(desert, group, operator):
    if group != "sandscape_footprints":  # only the walk needs the film's range; the rays key one frame
        desert.frame_start = desert.frame_end = FRAME
    settings = getattr(desert, group)
    demo_values = {p.identifier: getattr(settings, p.identifier) for p in settings.bl_rna.properties
                   if p.type in {"INT", "FLOAT", "BOOLEAN"} and p.identifier != "rna_type"}
    demo_values = {k: tuple(v) if hasattr(v, "__len__") else v for k, v in demo_values.items()}

    def run(values):
        for name, value in {**demo_values, **values}.items():
            setattr(settings, name, value)
        return getattr(bpy.ops.sandscape, operator)()

    cases = settings_cases(settings.bl_rna)
    bad = sweep(desert, cases, run)
    assert not bad, f"non-finite pixels after {operator} with: {bad}"


def test_sand_operator_at_its_extremes_renders_finite(desert, sandscape):
    bpy.context.view_layer.objects.active = desert.sandscape_footprints.terrain
    # The demo's glint values, as the operator's properties.
    demo_sand = {name.lower().replace(" ", "_"): value for name, value in sandscape.addon.demo.SAND.items()}
    demo_sand["seed"] = int(demo_sand["seed"])
    rna = bpy.ops.sandscape.add_sand_material.get_rna_type()
    cases = settings_cases(rna)
    cases += [(f"image {label}", dict(values, source="IMAGE")) for label, values in cases
              if "image_resolution" in values]

    def run(values):
        return bpy.ops.sandscape.add_sand_material(**{**demo_sand, **values})

    bad = sweep(desert, cases, run)
    assert not bad, f"non-finite pixels after add_sand_material with: {bad}"
