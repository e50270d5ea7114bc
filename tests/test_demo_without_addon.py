"""A .blend Sandscape writes renders the same with the extension disabled and Python auto-run off."""

import addon_utils
import bpy
import numpy as np

from devtools import readback, session


def test_demo_renders_identically_without_the_extension(tmp_path):
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 64, 36
    scene.cycles.samples = 2
    scene.frame_set(150)
    path = tmp_path / "demo.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path), compress=True)
    with_addon = readback.render(scene)

    preferences = bpy.context.preferences.filepaths
    addon_utils.disable(session.MODULE, default_set=True)
    preferences.use_scripts_auto_execute = False
    try:
        bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=False)
        assert not hasattr(bpy.types, "SANDSCAPE_OT_paint_footprints")
        scene = bpy.context.scene
        scene.frame_set(150)
        without = readback.render(scene)
    finally:
        preferences.use_scripts_auto_execute = True
        addon_utils.enable(session.MODULE, default_set=True)
    assert np.isfinite(without).all()
    assert np.abs(without - with_addon).max() <= 1e-6
