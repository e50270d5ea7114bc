"""The desert demo operator."""

import bpy

from ..addon import demo
from .base import SandscapeOperator


def _no_meshes(context):
    return not any(obj.type == "MESH" for obj in context.scene.objects)


class SANDSCAPE_OT_build_demo_scene(SandscapeOperator, bpy.types.Operator):
    """Build the Sandscape desert demo in this (empty) scene: dunes, glints, footprints, dust, god rays"""

    bl_idname = "sandscape.build_demo_scene"
    bl_label = "Build Demo Scene"
    POLL = ((_no_meshes, "The demo builds into an empty scene: this one has meshes (File > New, or a new "
                         "scene)"),)

    def execute(self, context):
        built = demo.build(context)
        self.report({"INFO"}, f"Built the demo: '{built['terrain'].name}', walker '{built['walker'].name}', "
                    f"camera '{built['camera'].name}'")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_build_demo_scene,)
