"""Adding Sandscape's node groups from the node editors' Add menus."""

import bpy
from bpy.props import StringProperty

from ..node_groups import catalog, helper
from .base import SandscapeOperator


def _in_node_tree(context):
    space = context.space_data
    return getattr(space, "type", None) == "NODE_EDITOR" and space.edit_tree is not None


class SANDSCAPE_OT_add_node_group(SandscapeOperator, bpy.types.Operator):
    """Add one of Sandscape's node groups to the node tree being edited"""

    bl_idname = "sandscape.add_node_group"
    bl_label = "Add Sandscape Group"
    POLL = ((_in_node_tree, "Open a shader or compositor node tree to add a Sandscape group to"),)

    group: StringProperty(name="Group", description="Name of the Sandscape node group to add")

    @classmethod
    def description(cls, _context, properties):
        builder = catalog.builder_named(properties.group)
        return builder.DESCRIPTION if builder else cls.__doc__

    def invoke(self, context, _event):
        result = self.execute(context)
        if result == {"FINISHED"}:  # then follow the mouse, as Blender's own Add menu does
            bpy.ops.node.translate_attach_remove_on_cancel("INVOKE_DEFAULT")
        return result

    def execute(self, context):
        tree = context.space_data.edit_tree
        builder = catalog.builder_named(self.group)
        if builder is None:
            return self.fail(f"No Sandscape group named '{self.group}'")
        if builder.TREE_TYPE != tree.bl_idname:
            return self.fail(f"'{self.group}' belongs in a {builder.TREE_TYPE}, not a {tree.bl_idname}")
        if tree.library is not None:
            return self.fail(f"'{tree.name}' is linked from a library")
        node = helper.insert_group_node(tree, builder, context.space_data.cursor_location)
        self.report({"INFO"}, f"Added '{node.node_tree.name}'")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_node_group,)
