"""Add menus: a Sandscape submenu in the 3D viewport's Add menu (Shift+A), and Sandscape groups
in the shader and compositor editors' Add menus, drawn from node_groups.catalog (one table,
one menu class; Molecular Nodes' node menus are the model)."""

import bpy

from ..node_groups import catalog

# (operator, label, icon) of the 3D viewport's Sandscape submenu.
SCENE_ENTRIES = (
    ("sandscape.add_dunes", "Dunes", "MOD_OCEAN"),
    ("sandscape.add_walker", "Walker", "ARMATURE_DATA"),
    ("sandscape.add_atmosphere", "Atmosphere", "LIGHT_SUN"),
    ("sandscape.add_clouds", "Clouds", "OUTLINER_DATA_VOLUME"),
    ("sandscape.build_demo_scene", "Demo Scene", "WORLD"),
)


class VIEW3D_MT_sandscape_add(bpy.types.Menu):
    bl_label = "Sandscape"
    bl_idname = "VIEW3D_MT_sandscape_add"

    def draw(self, _context):
        for operator, text, icon in SCENE_ENTRIES:
            self.layout.operator(operator, text=text, icon=icon)


class NODE_MT_sandscape_groups(bpy.types.Menu):
    """Sandscape's node groups for this editor, by category"""

    bl_label = "Sandscape"
    bl_idname = "NODE_MT_sandscape_groups"

    @classmethod
    def poll(cls, context):
        return bool(_entries(context))

    def draw(self, context):
        layout = self.layout
        category = None
        for group_category, builder in _entries(context):
            if group_category != category:
                if category is not None:
                    layout.separator()
                layout.label(text=group_category)
                category = group_category
            entry = layout.operator("sandscape.add_node_group", text=builder.NAME.removeprefix("Sandscape "))
            entry.group = builder.NAME


def _entries(context):
    return catalog.menu_entries(getattr(context.space_data, "tree_type", None))


def draw_view3d_add(self, _context):
    self.layout.separator()
    self.layout.menu(VIEW3D_MT_sandscape_add.bl_idname, icon="WORLD")


def draw_node_add(self, context):
    if _entries(context):
        self.layout.separator()
        self.layout.menu(NODE_MT_sandscape_groups.bl_idname)


classes = (VIEW3D_MT_sandscape_add, NODE_MT_sandscape_groups)
MENUS = ((bpy.types.VIEW3D_MT_add, draw_view3d_add), (bpy.types.NODE_MT_add, draw_node_add))


def register():
    for menu, draw in MENUS:
        menu.append(draw)


def unregister():
    for menu, draw in MENUS:
        menu.remove(draw)
