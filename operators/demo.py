"""Operators for the desert demo."""

import bpy

from ..addon import demo


class SANDSCAPE_OT_build_demo_scene(bpy.types.Operator):
    """Build the Sandscape desert demo in this (empty) file: dunes, glints, footprints, dust, god rays"""

    bl_idname = "sandscape.build_demo_scene"
    bl_label = "Build Demo Scene"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        if any(obj.type == "MESH" for obj in context.scene.objects):
            self.report({"ERROR"}, "The demo builds into an empty scene: this one has meshes (File > New)")
            return {"CANCELLED"}
        built = demo.build(context)
        self.report({"INFO"}, f"Built the demo: '{built['terrain'].name}', walker '{built['walker'].name}', "
                    f"camera '{built['camera'].name}'")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_build_demo_scene,)
