"""EEVEE's depth range: a camera whose Clip End is over MOST_DEPTH_RATIO times its Clip Start
renders haze and clouds brighter and blocky in EEVEE (a helper's centimetre scene kept Blender's
Clip Start of 0.1 units, 1 mm; README). The EEVEE preset, Add Atmosphere and Add Clouds say so
and what Clip Start to set; Cycles is not warned."""

import math

import bpy

from devtools import operators, scenes


def _warnings(reports):
    return [text for kinds, text in reports if kinds == {"WARNING"} and "Clip Start" in text]


def test_a_centimetre_camera_reaching_kilometres_is_warned_in_eevee():
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.scale_length = 0.01
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 300.0), rotation=(math.radians(96.0), 0.0, 0.0))
    camera.data.clip_start, camera.data.clip_end = 0.1, 1e7  # 1 mm to 100 km
    scene.render.engine = "BLENDER_EEVEE"
    for name, arguments in (("sandscape.apply_quality_preset", {"preset": "DRAFT"}),
                            ("sandscape.add_atmosphere", {})):
        result, reports = operators.run_execute(name, **arguments)
        assert result == {"FINISHED"}
        warned = _warnings(reports)
        assert len(warned) == 1 and "1 : 100,000,000" in warned[0] and warned[0].endswith("to 1 cm"), reports
    camera.data.clip_start = 1.0  # the 1 cm it asks for
    assert not _warnings(operators.run_execute("sandscape.apply_quality_preset", preset="DRAFT")[1])
    camera.data.clip_start = 0.1
    scene.render.engine = "CYCLES"  # Cycles' rays have no depth buffer
    assert not _warnings(operators.run_execute("sandscape.add_atmosphere")[1])
