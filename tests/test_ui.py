"""What the artist sees: the sidebar's panels, the Add menus, buttons live only when they can run,
and Update Sand Material starting from the material as it is."""

import types

import bpy
import pytest

from devtools import operators, readback


class RecordingLayout:
    """Records what a draw() puts in the layout, and refuses what Blender's layout would not draw:
    an operator, menu or property that does not exist."""

    def __init__(self):
        self.calls = []

    def operator(self, idname, **kwargs):
        module, name = idname.split(".")
        assert name in dir(getattr(bpy.ops, module)), f"no operator {idname}"
        self.calls.append(("operator", idname, kwargs.get("text")))
        rna = getattr(getattr(bpy.ops, module), name).get_rna_type()

        def set_property(button, key, value):  # a button takes only its operator's properties
            assert key in rna.properties.keys(), f"{idname} has no property {key}"
            object.__setattr__(button, key, value)
        return type("Button", (), {"__setattr__": set_property})()

    def menu(self, idname, **kwargs):
        assert hasattr(bpy.types, idname), f"no menu {idname}"
        self.calls.append(("menu", idname, kwargs.get("text")))

    def separator(self, **kwargs):
        pass

    def row(self, **kwargs):
        return self

    def prop(self, data, name, text=None, **kwargs):
        assert name in data.bl_rna.properties.keys(), f"{data!r} has no property {name}"
        self.calls.append(("prop", data, name, text))

    def label(self, text="", **kwargs):
        self.calls.append(("label", text))

    def prop_search(self, data, name, search_data, search_name, **kwargs):
        assert name in data.bl_rna.properties.keys(), f"{data!r} has no property {name}"
        assert search_name in search_data.bl_rna.properties.keys(), f"{search_data!r} has no {search_name}"
        self.calls.append(("prop", data, name, None))

    def template_ID(self, data, name, **kwargs):
        assert name in data.bl_rna.properties.keys(), f"{data!r} has no property {name}"
        self.calls.append(("template_ID", data, name))

    def column(self, **kwargs):
        return self


def draw_panel():
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_sand.draw(types.SimpleNamespace(layout=layout), bpy.context)
    return layout.calls


def test_sub_panels_in_the_sandscape_tab(sandscape):
    for name in ("sand", "footprints", "atmosphere", "render"):
        panel = getattr(bpy.types, f"SANDSCAPE_PT_{name}")
        where = (panel.bl_space_type, panel.bl_region_type, panel.bl_category)
        assert where == ("VIEW_3D", "UI", "Sandscape")
        assert panel.bl_parent_id == "SANDSCAPE_PT_main"


def test_render_panel_offers_the_presets_and_the_optimizer():
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_render.draw(types.SimpleNamespace(layout=layout), bpy.context)
    operators = [c[1] for c in layout.calls if c[0] == "operator"]
    assert operators.count("sandscape.apply_quality_preset") == 3
    assert operators.count("sandscape.optimize_scene") == 2


def test_panel_offers_add_then_shows_live_inputs(sandscape):
    readback.uv_plane()
    calls = draw_panel()
    assert ("operator", "sandscape.add_sand_material", "Add Sand Material") in calls
    assert not [c for c in calls if c[0] == "prop"]

    bpy.ops.sandscape.add_sand_material(threshold=0.6)
    calls = draw_panel()
    assert ("operator", "sandscape.add_sand_material", "Update Sand Material") in calls
    props = [(c[3], c[1]) for c in calls if c[0] == "prop"]
    names = [name for name, _ in props]
    # The glints, then the look, then the ripples: every input the artist can tune, none linked.
    assert names[:6] == ["Threshold", "Glint Size", "Facing Power", "Color", "Roughness", "Seed"]
    assert {"Diffuse Roughness", "IOR", "Sheen", "Wavelength", "Amplitude", "Steep Fraction"} <= set(names)
    assert "Normal" not in names and "Base" not in names
    props = dict(props[:6])
    # The panel edits the material's own node sockets: live, no copy to keep in sync.
    node = sandscape.addon.sand.glint_node(bpy.context.active_object.active_material)
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
    assert operators == ["sandscape.add_walker", "sandscape.footprint_walker_add",
                         "sandscape.emit_footprints", "sandscape.paint_footprints"]
    settings = bpy.context.scene.sandscape_footprints
    names = {p.identifier for p in settings.bl_rna.properties if p.identifier not in ("rna_type", "name")}
    # Everything but the other source's object, the range the scene supplies and a rig's feet.
    assert names - shown == {"particle_object", "frame_start", "frame_end", "left_foot", "right_foot",
                             "more_walkers"}  # a list, drawn row by row
    settings.walker = bpy.data.objects.new("Rig", bpy.data.armatures.new("Rig"))
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_footprints.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert {"left_foot", "right_foot"} <= {c[2] for c in layout.calls if c[0] == "prop"}
    settings.walker = None
    settings.more_walkers.add()
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_footprints.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert {"foot_scale", "depth_scale"} <= {c[2] for c in layout.calls if c[0] == "prop"}
    assert "sandscape.footprint_walker_remove" in [c[1] for c in layout.calls if c[0] == "operator"]
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


def test_dunes_panel_shows_its_settings_and_button():
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_dunes.draw(types.SimpleNamespace(layout=layout), bpy.context)
    shown = {call[2] for call in layout.calls if call[0] == "prop"}
    settings = bpy.context.scene.sandscape_dunes
    assert {p.identifier for p in settings.bl_rna.properties} - {"rna_type", "name"} == shown
    assert [c[1:] for c in layout.calls if c[0] == "operator"] == [("sandscape.add_dunes", "Add Dunes")]


def test_every_operator_polls_through_the_shared_mixin(sandscape):
    names = [name for name in dir(bpy.types) if name.startswith("SANDSCAPE_OT_")]
    assert len(names) >= 10
    for name in names:
        cls = getattr(bpy.types, name)
        assert issubclass(cls, sandscape.operators.base.SandscapeOperator), name
        assert cls.__doc__ and cls.bl_options == {"REGISTER", "UNDO"}, name


@pytest.mark.parametrize("glints, source, edits", [
    ("EMISSION", "PROCEDURAL", {"Strength": 60.0, "Seed": 7.0}),
    ("EMISSION", "IMAGE", {"Strength": 60.0, "Threshold": 0.5}),
    ("LIT", "PROCEDURAL", {"Roughness": 0.2, "Seed": 7.0}),
])
def test_update_sand_material_starts_from_the_material(sandscape, glints, source, edits):
    plane = readback.uv_plane()
    bpy.ops.sandscape.add_sand_material(look="JOURNEY", glints=glints, source=source, image_resolution=8,
                                        strength=30.0, seed=0)
    node = sandscape.addon.sand.glint_node(plane.active_material)
    for name, value in edits.items():  # edited in the sidebar
        node.inputs[name].default_value = value
    result, _ = operators.run_invoke("sandscape.add_sand_material")  # the Update button
    assert result == {"FINISHED"}
    node = sandscape.addon.sand.glint_node(plane.active_material)
    for name, value in edits.items():
        assert node.inputs[name].default_value == pytest.approx(value), name
    image = sandscape.addon.sand.image_node(plane.active_material)
    assert (image is not None) == (source == "IMAGE")  # the source as it was
    assert sandscape.addon.sand.structure(plane.active_material)[:2] == ("JOURNEY", glints)  # the look


def test_shift_a_offers_sandscape(sandscape):
    assert sandscape.ui.menus.draw_view3d_add in bpy.types.VIEW3D_MT_add._dyn_ui_initialize()
    layout = RecordingLayout()
    bpy.types.VIEW3D_MT_sandscape_add.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert [c[1] for c in layout.calls] == ["sandscape.add_dunes", "sandscape.add_walker",
                                           "sandscape.add_atmosphere", "sandscape.add_clouds",
                                           "sandscape.build_demo_scene"]


@pytest.mark.parametrize("tree_type, expected", [
    ("ShaderNodeTree", {"Sandscape Glints", "Sandscape Glint Shade", "Sandscape Footprint Height",
                        "Sandscape Dust Volume", "Sandscape Dust Field", "Sandscape Physical Sand",
                        "Sandscape Journey Sand", "Sandscape Lit Glints", "Sandscape Glint Facet",
                        "Sandscape Glint Cells", "Sandscape Glint Splat",
                        "Sandscape Sand Normal", "Sandscape Ripples", "Sandscape Cloud Density",
                        "Sandscape Weather Map"}),
    ("CompositorNodeTree", {"Sandscape Gated Blur", "Sandscape God Rays", "Sandscape Sun Place"}),
    ("GeometryNodeTree", {"Sandscape Cloud Density Field", "Sandscape Weather Map Field"}),
])
def test_node_editors_add_menus_list_our_groups(sandscape, tree_type, expected):
    context = types.SimpleNamespace(space_data=types.SimpleNamespace(tree_type=tree_type))
    menu = bpy.types.NODE_MT_sandscape_groups
    assert menu.poll(context) == bool(expected)
    layout = RecordingLayout()
    menu.draw(types.SimpleNamespace(layout=layout), context)
    shown = {"Sandscape " + c[2] for c in layout.calls if c[0] == "operator"}
    assert shown == expected
    assert sandscape.ui.menus.draw_node_add in bpy.types.NODE_MT_add._dyn_ui_initialize()


def test_adding_a_group_from_the_menu_ensures_it_first(sandscape):
    material = bpy.data.materials.new("Theirs")
    tree = material.node_tree
    space = types.SimpleNamespace(type="NODE_EDITOR", edit_tree=tree, cursor_location=(100.0, 50.0))
    context = types.SimpleNamespace(space_data=space, scene=bpy.context.scene)
    result, _ = operators.run_execute("sandscape.add_node_group", context, group="Sandscape Footprint Height")
    assert result == {"FINISHED"}
    node = tree.nodes.active
    assert node.node_tree.get("sandscape_group") == "Sandscape Footprint Height"
    assert tuple(node.location) == (100.0, 50.0) and node.select
    result, reports = operators.run_execute("sandscape.add_node_group", context, group="Sandscape Gated Blur")
    assert result == {"CANCELLED"} and "CompositorNodeTree" in reports[0][1]  # not in a shader tree


def test_the_sidebar_says_which_engine_a_setting_reaches(sandscape):
    """Issue 27: where a setting reaches only Cycles (or EEVEE renders it otherwise), its section
    says so; the sand says what EEVEE renders of each look."""
    panels = sandscape.ui.panels
    bpy.context.scene.render.engine = "CYCLES"
    seen = []
    for name in ("footprints", "atmosphere", "clouds"):
        layout = RecordingLayout()
        getattr(bpy.types, f"SANDSCAPE_PT_{name}").draw(types.SimpleNamespace(layout=layout), bpy.context)
        seen += [c[1] for c in layout.calls if c[0] == "label"]
    assert set(panels.ENGINE_NOTES.values()) <= set(seen)
    assert panels.CLOUD_SHADOWS_IN_EEVEE not in seen  # Cycles shadows through the clouds
    bpy.context.scene.render.engine = "BLENDER_EEVEE"
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_clouds.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert ("label", panels.CLOUD_SHADOWS_IN_EEVEE) in [c[:2] for c in layout.calls]
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_atmosphere.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert ("label", panels.ground_light_text(bpy.context.scene)) in [c[:2] for c in layout.calls]
    bpy.context.scene.render.engine = "CYCLES"
    readback.uv_plane()
    for look in ("PHYSICAL", "JOURNEY"):
        assert bpy.ops.sandscape.add_sand_material(look=look) == {"FINISHED"}
        assert ("label", panels.SAND_IN_EEVEE[look]) in draw_panel()


def test_the_sand_panel_says_when_eevee_does_not_follow_a_new_sun(sandscape):
    """A sun lamp added after the sand material drives nothing yet: the panel says so until Update
    Sand Material points the EEVEE output's sun at it."""
    import math

    readback.uv_plane()
    assert bpy.ops.sandscape.add_sand_material(look="JOURNEY") == {"FINISHED"}
    assert ("label", sandscape.ui.panels.NEW_SUN) not in draw_panel()  # no sun, none driven
    plane = bpy.context.active_object
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(40), 0.0, 0.0))
    bpy.context.view_layer.objects.active = plane
    assert ("label", sandscape.ui.panels.NEW_SUN) in draw_panel()
    assert bpy.ops.sandscape.add_sand_material(look="JOURNEY") == {"FINISHED"}
    assert ("label", sandscape.ui.panels.NEW_SUN) not in draw_panel()


def test_the_atmosphere_panel_names_eevees_clamp_after_a_switch_from_cycles(sandscape):
    """Add Atmosphere run while the scene renders in Cycles names no EEVEE clamp; switched to EEVEE
    with Blender's Clamp Surface Indirect (10), the sidebar says it dims the ground's light; at 0
    (the EEVEE presets') it says nothing."""
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.eevee.clamp_surface_indirect = 10.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    clamp = sandscape.ui.panels.clamp_text(scene)
    assert "10" in clamp

    def labels():
        layout = RecordingLayout()
        bpy.types.SANDSCAPE_PT_atmosphere.draw(types.SimpleNamespace(layout=layout), bpy.context)
        return [c[1] for c in layout.calls if c[0] == "label"]

    assert clamp not in labels()
    scene.render.engine = "BLENDER_EEVEE"
    assert clamp in labels()
    scene.eevee.clamp_surface_indirect = 0.0
    assert not any("Clamp Surface Indirect" in text for text in labels())
