"""Sandscape Dust Field against its numpy twin (core/dust.py) by bake: the group's factor where
Cycles shaded planes at several heights, the wind having carried the field for a few seconds."""

import bpy
import numpy as np
import pytest

from core import dust
from devtools import readback, scenes

RES = 48
# Float32 noise of coordinates up to ~10, through the patch edge's smoothstep (slope 1.5 / (2 x
# softness) = 7.5 at its steepest): the cloud twins' 2e-5 noise tolerance, times that.
TOLERANCE = 2e-4
VALUES = {"Frame": 60.0, "FPS": 24.0, "Wind": (3.0, -1.5, 0.0), "Scale": 8.0, "Coverage": 0.5,
          "Softness": 0.1, "Ground": 0.2, "Falloff": 1.5}


@pytest.mark.parametrize("height", [0.0, 0.2, 1.7])
def test_the_dust_field_is_its_twin(sandscape, height):
    group = sandscape.node_groups.helper.ensure_group(sandscape.node_groups.dust_field)
    material = scenes.group_material(group, VALUES, output="Factor")
    plane = readback.uv_plane(24.0)
    plane.location = (3.0, -5.0, height)
    bpy.context.view_layer.update()
    plane.data.materials.append(material)
    baked, world = readback.bake_emit_with_positions(plane, material, RES)
    expected = dust.dust_field(world, VALUES["Frame"], VALUES["FPS"], VALUES["Wind"], VALUES["Scale"],
                               VALUES["Coverage"], VALUES["Softness"], VALUES["Ground"], VALUES["Falloff"])
    assert np.isfinite(baked).all()
    assert 0.05 < (expected > 0.5).mean() < 0.95 or height > 1.0  # both dust and clear ground in view
    assert np.abs(baked[..., 0] - expected).max() < TOLERANCE
