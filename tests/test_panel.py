"""The sidebar panel shows the operator and the live glint inputs of the object's sand material."""

import types

import bpy

from devtools import readback


class RecordingLayout:
    def __init__(self):
        self.calls = []

    def operator(self, idname, **kwargs):
        self.calls.append(("operator", idname, kwargs.get("text")))

    def prop(self, data, name, text=None, **kwargs):
        self.calls.append(("prop", data, name, text))

    def label(self, text="", **kwargs):
        self.calls.append(("label", text))

    def template_ID(self, data, name, **kwargs):
        self.calls.append(("template_ID", data, name))

    def column(self, **kwargs):
        return self


def draw_panel():
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_sand.draw(types.SimpleNamespace(layout=layout), bpy.context)
    return layout.calls


def test_panel_registered_in_the_sandscape_tab(sandscape):
    panel = bpy.types.SANDSCAPE_PT_sand
    assert (panel.bl_space_type, panel.bl_region_type, panel.bl_category) == ("VIEW_3D", "UI", "Sandscape")


def test_panel_offers_add_then_shows_live_inputs(sandscape):
    readback.uv_plane()
    calls = draw_panel()
    assert ("operator", "sandscape.add_sand_material", "Add Sand Material") in calls
    assert not [c for c in calls if c[0] == "prop"]

    bpy.ops.sandscape.add_sand_material(threshold=0.6)
    calls = draw_panel()
    assert ("operator", "sandscape.add_sand_material", "Update Sand Material") in calls
    props = {c[3]: c[1] for c in calls if c[0] == "prop"}
    assert list(props) == ["Threshold", "Glint Size", "Facing Power", "Color", "Strength", "Seed"]
    # The panel edits the material's own node sockets: live, no copy to keep in sync.
    node = sandscape.blender.sand.glint_node(bpy.context.active_object.active_material)
    assert props["Threshold"] == node.inputs["Threshold"]


def test_panel_shows_the_glint_image(sandscape):
    readback.uv_plane()
    bpy.ops.sandscape.add_sand_material(source="IMAGE", image_resolution=8)
    calls = draw_panel()
    assert any(c[0] == "template_ID" and c[2] == "image" for c in calls)
    assert "Noise" not in {c[3] for c in calls if c[0] == "prop"}  # linked inputs are not shown


def test_footprints_panel_shows_every_setting_and_the_buttons():
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_footprints.draw(types.SimpleNamespace(layout=layout), bpy.context)
    shown = {call[2] for call in layout.calls if call[0] == "prop"}
    operators = [call[1] for call in layout.calls if call[0] == "operator"]
    assert operators == ["sandscape.add_walker", "sandscape.emit_footprints", "sandscape.paint_footprints"]
    settings = bpy.context.scene.sandscape_footprints
    names = {p.identifier for p in settings.bl_rna.properties if p.identifier not in ("rna_type", "name")}
    # Everything but the other source's object and the range the scene supplies.
    assert names - shown == {"particle_object", "frame_start", "frame_end"}
    settings.source, settings.use_scene_range = "PARTICLES", False
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_footprints.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert {"particle_object", "frame_start", "frame_end"} <= {c[2] for c in layout.calls if c[0] == "prop"}


def test_atmosphere_panel_shows_its_settings_and_button():
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_atmosphere.draw(types.SimpleNamespace(layout=layout), bpy.context)
    shown = {call[2] for call in layout.calls if call[0] == "prop"}
    for settings in (bpy.context.scene.sandscape_atmosphere, bpy.context.scene.sandscape_post):
        names = {p.identifier for p in settings.bl_rna.properties} - {"rna_type", "name"}
        assert names <= shown
    operators = [c[1] for c in layout.calls if c[0] == "operator"]
    assert operators == ["sandscape.add_atmosphere", "sandscape.add_post_effects"]
