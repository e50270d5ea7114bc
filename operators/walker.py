"""The stand-in walker operator."""

import bpy

from ..addon import footprints, walker
from .base import SandscapeOperator


class SANDSCAPE_OT_add_walker(SandscapeOperator, bpy.types.Operator):
    """Add a stand-in character walking a curve path across the terrain over the frame range"""

    bl_idname = "sandscape.add_walker"
    bl_label = "Add Walker"

    def execute(self, context):
        scene = context.scene
        settings = scene.sandscape_footprints
        terrain = settings.terrain
        if terrain is None and context.active_object is not None and context.active_object.type == "MESH":
            terrain = context.active_object
        start, end = footprints.frame_range(scene, settings)
        problem = walker.frame_range_problem(start, end)
        if problem:
            return self.fail(problem)
        if terrain is not None and terrain.type == "MESH" and not terrain.evaluated_get(
                context.evaluated_depsgraph_get()).data.polygons:
            return self.fail(f"'{terrain.name}' has no faces to walk on: the walker would never move")
        settings.walker, path = walker.ensure_walker(scene, terrain, start, end)
        settings.source = "WALKER"
        if terrain is not None:
            settings.terrain = terrain
        self.report({"INFO"}, f"'{settings.walker.name}' walks '{path.name}' over frames {start}..{end}")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_walker,)
