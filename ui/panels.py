"""The Sandscape tab in the 3D viewport sidebar: a Sandscape panel with sub-panels for
Dunes, Sand, Footprints, Atmosphere, Clouds and Render. Buttons are live only when their operator's
poll() allows."""

import bpy

from ..addon import (
    atmosphere,
    cloud_shadows,
    dunes,
    ownership,
    rig_feet,
    sand,
    sand_eevee,
    sky_eevee,
    sky_eevee_ground,
)


class SandscapeTab:
    """Where every Sandscape panel lives: the Sandscape tab of the 3D viewport's sidebar."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Sandscape"


class SandscapeSubPanel(SandscapeTab):
    bl_parent_id = "SANDSCAPE_PT_main"


class SANDSCAPE_PT_main(SandscapeTab, bpy.types.Panel):
    bl_label = "Sandscape"
    bl_idname = "SANDSCAPE_PT_main"

    def draw(self, context):
        layout = self.layout
        layout.operator("sandscape.build_demo_scene", icon="WORLD")


class SANDSCAPE_PT_sand(SandscapeSubPanel, bpy.types.Panel):
    bl_label = "Sand"
    bl_idname = "SANDSCAPE_PT_sand"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        material = sand.find_sand_material(obj) if obj is not None else None
        text = "Update Sand Material" if material else "Add Sand Material"
        layout.operator("sandscape.add_sand_material", text=text, icon="MATERIAL")
        node = sand.glint_node(material)
        if node is None:
            if obj is not None and obj.type == "MESH":
                layout.label(text="No Sandscape material on this object")
            return
        built = sand.structure(material)
        look = f"{built[0].title()} look, {built[1].lower()} glints" if built else ""
        layout.label(text=f"{material.name}: {look}", icon="MATERIAL")
        if built and built[0] in ("PHYSICAL", "JOURNEY"):
            layout.label(text=SAND_IN_EEVEE[built[0]], icon="INFO")
            if not sand_eevee.follows_scene_sun(material, context.scene):
                layout.label(text=NEW_SUN, icon="ERROR")
        # The material's own node sockets: edits here are the material, no copy to keep in sync.
        for part in (node, sand.look_node(material), sand.ripple_node(material)):
            if part is None:
                continue
            layout.label(text=part.label or part.node_tree.name)
            column = layout.column(align=True)
            for socket in part.inputs:
                if not socket.is_linked and hasattr(socket, "default_value") and not socket.hide_value:
                    column.prop(socket, "default_value", text=socket.name)
        image = sand.image_node(material)
        if image is not None:
            layout.template_ID(image, "image", open="image.open")


SAND_IN_EEVEE = {"PHYSICAL": "EEVEE: its own output, balanced to Cycles' brightness",
                 "JOURNEY": "EEVEE: its own output, the contrast lit by the scene's sun"}

NEW_SUN = "EEVEE: a new sun lamp; Update Sand Material to follow it"

DUNE_SECTIONS = (
    ("Field", ("width", "depth", "cell_size", "horizon")),
    ("Dunes", ("spacing", "sand_supply", "seed", "sand_material")),
)


class SANDSCAPE_PT_dunes(SandscapeSubPanel, bpy.types.Panel):
    bl_label = "Dunes"
    bl_idname = "SANDSCAPE_PT_dunes"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.sandscape_dunes
        _sections(layout, settings, DUNE_SECTIONS)
        layout.prop(settings, "use_second_wind")
        column = layout.column(align=True)
        column.active = settings.use_second_wind
        column.prop(settings, "second_wind_angle")
        column.prop(settings, "second_wind_share")
        layout.label(text="Wind: the atmosphere's (dust, ripples, clouds)", icon="INFO")
        found = dunes.scene_dunes(context.scene)
        text = "Regrow Dunes" if found else "Add Dunes"
        layout.operator("sandscape.add_dunes", text=text, icon="MOD_OCEAN")


# (heading, settings shown under it); the operators read the same settings.
FOOTPRINT_SECTIONS = (
    ("Walk", ("stride", "stance")),
    ("Foot", ("foot_length", "foot_width", "depth", "rim", "rim_width", "variation", "noise_amount", "seed")),
    ("Map", ("resolution", "dicing_pixel_size")),
    ("Wind", ("refill_time",)),
)


class SANDSCAPE_PT_footprints(SandscapeSubPanel, bpy.types.Panel):
    bl_label = "Footprints"
    bl_idname = "SANDSCAPE_PT_footprints"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.sandscape_footprints
        layout.prop(settings, "source")
        if settings.source == "WALKER":
            layout.prop(settings, "walker")
            rig = rig_feet.armature_of(settings.walker)
            if rig is not None:  # a rig walks on its feet: which bones they are
                layout.prop_search(settings, "left_foot", rig.data, "bones")
                layout.prop_search(settings, "right_foot", rig.data, "bones")
            layout.operator("sandscape.add_walker", icon="ARMATURE_DATA")
            for index, entry in enumerate(settings.more_walkers):  # more walkers on the same sand
                row = layout.row()
                row.prop(entry, "walker", text="")
                row.operator("sandscape.footprint_walker_remove", text="", icon="X").index = index
                row = layout.row(align=True)
                row.prop(entry, "foot_scale")
                row.prop(entry, "depth_scale")
                row.prop(entry, "stride_scale")
                rig = rig_feet.armature_of(entry.walker)
                if rig is not None:
                    layout.prop_search(entry, "left_foot", rig.data, "bones")
                    layout.prop_search(entry, "right_foot", rig.data, "bones")
            layout.operator("sandscape.footprint_walker_add", icon="ADD")
        else:
            layout.prop(settings, "particle_object")
        layout.prop(settings, "terrain")
        layout.prop(settings, "use_scene_range")
        if not settings.use_scene_range:
            layout.prop(settings, "frame_start")
            layout.prop(settings, "frame_end")
        _sections(layout, settings, FOOTPRINT_SECTIONS)
        layout.operator("sandscape.emit_footprints", icon="PARTICLES")
        layout.operator("sandscape.paint_footprints", icon="BRUSH_DATA")


ATMOSPHERE_SECTIONS = (
    ("Sun and Air", ("sun_elevation", "sun_azimuth", "aim_sun", "sun_from_sky", "set_exposure",
                     "replace_world", "density", "wavelengths", "margin")),
    ("Haze", ("use_haze", "visibility")),
    ("Dust", ("dust_density", "anisotropy", "use_wind", "wind", "dust_scale", "coverage", "softness",
              "falloff")),
)
POST_SECTIONS = (
    ("Denoise", ("use_denoise",)),
    ("Gated Blur", ("use_blur", "blur_threshold")),
    ("God Rays", ("use_god_rays", "samples", "ray_density", "ray_weight", "ray_decay", "ray_exposure",
                  "disc_radius", "fade")),
    ("Sun Glow", ("use_sun_glow", "glow_strength")),
)


class SANDSCAPE_PT_atmosphere(SandscapeSubPanel, bpy.types.Panel):
    bl_label = "Atmosphere"
    bl_idname = "SANDSCAPE_PT_atmosphere"

    def draw(self, context):
        layout = self.layout
        air = context.scene.sandscape_atmosphere
        sun = atmosphere.scene_sun(context.scene)
        if sun is not None and not atmosphere.is_ours(sun):  # the angles below do not move it
            what = "Aim Your Sun turns it" if air.aim_sun else "the sky follows it"
            layout.label(text=f"Your sun '{sun.name}': {what}", icon="LIGHT_SUN")
        _sections(layout, air, ATMOSPHERE_SECTIONS)
        # Where the user sees it: why the dust is a box and not a world volume.
        layout.label(text="Dust fills a box around what the camera sees:", icon="INFO")
        layout.label(text="a world volume would block the sun lamp")
        scene = context.scene
        if scene.render.engine == "BLENDER_EEVEE" and ownership.scene_world(scene) is not None:
            layout.label(text=ground_light_text(scene), icon="INFO")
            for line in ground_moved_text(scene):
                layout.label(text=line)
            # Add Atmosphere run under Cycles said nothing of it: the engine switched since.
            if scene.eevee.clamp_surface_indirect > 0:
                layout.label(text=clamp_text(scene), icon="ERROR")
        layout.operator("sandscape.add_atmosphere", icon="LIGHT_SUN")
        _sections(layout, context.scene.sandscape_post, POST_SECTIONS)
        engine = context.scene.render.engine
        if engine == "BLENDER_EEVEE":
            layout.label(text="EEVEE: god rays and blur; denoising is Cycles only", icon="INFO")
        elif engine != "CYCLES":
            layout.label(text="Post effects need Cycles or EEVEE passes", icon="ERROR")
        layout.operator("sandscape.add_post_effects", icon="NODE_COMPOSITING")


CLOUD_SECTIONS = (
    ("Layer", ("coverage", "cloud_type", "seed", "base", "thickness", "precipitation", "density")),
    ("Shape", ("shape_scale", "detail_scale", "erosion", "curl", "skew")),
    ("Light", ("phase", "forward", "back", "back_weight", "droplet_size", "reach")),
    ("Evaluation", ("evaluation", "voxel", "step")),
)


class SANDSCAPE_PT_clouds(SandscapeSubPanel, bpy.types.Panel):
    bl_label = "Clouds"
    bl_idname = "SANDSCAPE_PT_clouds"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.sandscape_clouds
        layout.prop(settings, "weather_source")
        if settings.weather_source == "IMAGE":
            layout.template_ID(settings, "weather_image", open="image.open")
            layout.prop(settings, "map_size")
        else:
            layout.prop(settings, "map_scale")
        _sections(layout, settings, CLOUD_SECTIONS)
        layout.label(text="Wind: the atmosphere's (dust, ripples, clouds)", icon="INFO")
        if cloud_shadows.stale(context.scene, evaluated=False):
            layout.label(text=CLOUD_SHADOWS_STALE, icon="ERROR")
        elif context.scene.render.engine == "BLENDER_EEVEE":
            layout.label(text=CLOUD_SHADOWS_IN_EEVEE, icon="INFO")
        if cloud_shadows.unshaded(context.scene):
            layout.label(text=CLOUDS_UNSHADED_IN_EEVEE, icon="ERROR")
        layout.operator("sandscape.add_clouds", icon="OUTLINER_DATA_VOLUME")


class SANDSCAPE_PT_render(SandscapeSubPanel, bpy.types.Panel):
    bl_label = "Render"
    bl_idname = "SANDSCAPE_PT_render"

    def draw(self, context):
        layout = self.layout
        engine = "EEVEE" if context.scene.render.engine == "BLENDER_EEVEE" else "Cycles"
        layout.label(text=f"Quality (measured presets, {engine})")
        row = layout.row(align=True)
        for preset, text in (("DRAFT", "Draft"), ("PREVIEW", "Preview"), ("FINAL", "Final")):
            row.operator("sandscape.apply_quality_preset", text=text).preset = preset
        layout.label(text="Switch off what cannot reach the image")
        row = layout.row(align=True)
        row.operator("sandscape.optimize_scene", text="List", icon="VIEWZOOM").dry_run = True
        row.operator("sandscape.optimize_scene", text="Optimize", icon="MODIFIER").dry_run = False


def clamp_text(scene):
    """EEVEE's Clamp Surface Indirect above 0 dims the light our world gives from the ground."""
    return (f"Clamp Surface Indirect {scene.eevee.clamp_surface_indirect:g} dims the ground's light "
            "(Render presets: 0)")


def ground_moved_text(scene):
    """Lines for a camera over another ground than the one EEVEE's light from the ground took (it is
    chosen when an operator runs, one for the whole shot): moved since, or on another frame."""
    followed = sky_eevee.followed_ground(scene.world)
    looked_at = sky_eevee_ground.below_camera(scene) if followed is not None else None
    if looked_at is None or looked_at == followed:
        return ()
    return (f"The camera is over '{looked_at.name}' here: Add Atmosphere",
            "takes one ground for the shot, from its frame")


def ground_light_text(scene):
    """Whose colour EEVEE's light from the ground takes (addon/sky_eevee_ground.py)."""
    followed = sky_eevee.followed_ground(scene.world)
    if followed is None:
        return "EEVEE's light from the ground: Sandscape's sand colour stands in"
    found = sky_eevee_ground.colour_input(followed)
    socket = found[0].inputs[found[1]] if found is not None else None
    linked = socket is not None and socket.is_linked
    recorded = sky_eevee_ground.recorded_image(scene.world.node_tree)
    if recorded is not None and linked and sky_eevee_ground.image_behind(socket) == recorded[1]:
        return f"EEVEE's light from the ground: the mean of image '{recorded[1].name}' on '{followed.name}'"
    if found is None or linked or recorded is not None:  # a texture or another image linked, or unlinked
        return f"EEVEE's light from the ground: '{followed.name}' changed, Add Atmosphere again"
    return f"EEVEE's light from the ground: the colour of '{followed.name}'"


CLOUD_SHADOWS_IN_EEVEE = "EEVEE: the clouds' ground shadows from Add Clouds"
CLOUDS_UNSHADED_IN_EEVEE = ("Unshaded in EEVEE: Add Clouds again (Voxel Grid) to bake their sunlight, "
                            "or turn on Render ▸ Shadows ▸ Volume Shadows")
CLOUD_SHADOWS_STALE = "EEVEE's cloud shadows are out of date (the sun moved): Add Clouds again"


# Section heading -> the settings under it that do not reach Cycles and EEVEE alike (the others do).
ENGINE_NOTES = {
    "Map": "Dicing Pixel Size: Cycles (EEVEE displaces the patch's vertices)",
    "Sun and Air": "Density: Rayleigh's phase is Cycles only",
    "Denoise": "Cycles only: it reads Cycles' denoising passes",
    "Light": "Mie: Cycles only; EEVEE merges the dual lobes",
    "Evaluation": "Step: Cycles' marching; in EEVEE only the grid's march to the sun",
}


def _sections(layout, settings, sections):
    for heading, names in sections:
        layout.label(text=heading)
        column = layout.column(align=True)
        for name in names:
            column.prop(settings, name)
        if heading in ENGINE_NOTES:
            layout.label(text=ENGINE_NOTES[heading], icon="INFO")


classes = (SANDSCAPE_PT_main, SANDSCAPE_PT_dunes, SANDSCAPE_PT_sand, SANDSCAPE_PT_footprints,
           SANDSCAPE_PT_atmosphere, SANDSCAPE_PT_clouds, SANDSCAPE_PT_render)
