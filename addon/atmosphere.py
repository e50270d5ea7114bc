"""The bpy side of the atmosphere: the sun lamp, the sky world, the bounded dust volume.

A world volume would block a sun lamp completely in Cycles (the world volume is infinite), so
with a sun the scattering medium is a box around the camera's path over the frame range, out
to where the haze lets 1 % through in every horizontal direction (around the geometry without a
camera): turning the camera or changing the frame size afterwards shows no edge. Everything is
found in the scene being set up: another scene gets its own sun, sky and dust box.
"""

import math

import bpy
import numpy as np
from mathutils import Vector

from ..core import atmosphere as air
from ..core import sun as sky_sun
from ..core.clouds import layer_region as holding_region
from ..node_groups import dust_field, dust_volume
from ..node_groups import helper as h
from . import (
    drivers,
    evaluation,
    sand,
    sand_eevee,
    shot,
    sky_eevee,
    sky_eevee_clouds,
    sky_eevee_ground,
    sky_eevee_haze,
    units,
    walker_wind,
)
from . import ownership as own
from .far_haze import HAZE_KEY as FAR_HAZE_KEY
from .far_haze import box_bounds
from .far_haze import refresh as refresh_far_haze
from .sun_lamp import ensure_sun, is_ours, scene_sun  # noqa: F401 (the atmosphere's API)

# Bump when build_sky_nodes changes: a world built by an older version is rebuilt.
WORLD_NODES_KEY = "sandscape_sky_nodes"
WORLD_NODES_VERSION = 6
CLEAR = 0.01  # the haze may end where less than 1 % of the light behind it gets through
MAX_REACH_M = 20000.0  # thin air would otherwise ask for a box hundreds of kilometres wide
DEFAULT_WORLD_GREYS = (0.0508761, 0.05)  # a new file's world colour and a new world's, linear


def build_sky_nodes(tree):
    """Sky light without a sun disc for every ray but camera rays, which see the disc as well.

    The lamp lights the scene; a disc in the lighting sky would light it twice, yet without
    one the camera would see no sun at all. EEVEE gets its own output (sky_eevee.py): the same
    sky for the camera, and a lighting sky shaped for its spherical-harmonic lighting.
    """
    tree.nodes.clear()
    lighting = h.add_node(tree, "ShaderNodeTexSky", name="Sandscape Sky", label="Sky",
                          sky_type="MULTIPLE_SCATTERING", sun_disc=False)
    seen = h.add_node(tree, "ShaderNodeTexSky", name="Sandscape Sky with Sun Disc", label="Sky with Sun Disc",
                      sky_type="MULTIPLE_SCATTERING", sun_disc=True)
    lit = h.add_node(tree, "ShaderNodeBackground", name="Sandscape Sky Light")
    shown = h.add_node(tree, "ShaderNodeBackground", name="Sandscape Sky Seen")
    ray = h.add_node(tree, "ShaderNodeLightPath", name="Sandscape Light Path")
    mix = h.add_node(tree, "ShaderNodeMixShader", name="Sandscape Camera Sees the Disc",
                     label="Camera Sees the Disc")
    output = h.add_node(tree, "ShaderNodeOutputWorld", name="Sandscape World Output")
    h.link(tree, lighting.outputs["Color"], lit.inputs["Color"])
    h.link(tree, seen.outputs["Color"], shown.inputs["Color"])
    h.link(tree, ray.outputs["Is Camera Ray"], mix.inputs["Fac"])
    h.link(tree, lit.outputs[0], mix.inputs[1])
    h.link(tree, shown.outputs[0], mix.inputs[2])
    h.link(tree, mix.outputs[0], output.inputs["Surface"])
    output.target = "CYCLES"
    sky_eevee.build(tree, ray, shown)
    h.arrange(tree, set_widths=False)


def is_untouched_default(world):
    """Blender's own new-file world, as it comes: a grey Background and its output, nothing else.
    Not the artist's choice, so the sky may take its place without asking."""
    tree = world.node_tree
    if tree is None or world.animation_data is not None or len(tree.nodes) != 2:
        return False
    background = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeBackground"), None)
    if background is None or not any(n.bl_idname == "ShaderNodeOutputWorld" for n in tree.nodes):
        return False
    color, strength = background.inputs["Color"], background.inputs["Strength"]
    return (not color.is_linked and not strength.is_linked and strength.default_value == 1.0
            and any(all(abs(c - grey) < 1e-6 for c in color.default_value[:3])
                    for grey in DEFAULT_WORLD_GREYS))


def ensure_sky(scene, elevation, azimuth, replace_theirs=False, follow=None):
    """This scene's world with a Sky Texture whose sun matches the lamp: (world, replaced), world
    None when the scene keeps the artist's own world (replace_theirs off). follow: the artist's
    sun, which the sky's sun then follows on every frame through drivers (simple expressions:
    they run without Python, on a farm too).

    A replaced world is kept (fake user) and named on ours as "replaced_world" to switch back.
    Our world shared with another scene is copied first, so that scene's sun stays where it is.
    """
    world = own.scene_world(scene)
    replaced = None
    if world is None:
        if scene.world is not None and not replace_theirs and not is_untouched_default(scene.world):
            return None, None
        replaced = scene.world
        world = own.mark(bpy.data.worlds.new("Sandscape Sky"), own.WORLD_KEY, own.SKY)
        if replaced is not None:
            replaced.use_fake_user = True
            world["replaced_world"] = replaced.name
        scene.world = world
    elif any(other.world == world for other in bpy.data.scenes if other != scene):
        world = world.copy()
        scene.world = world
    if world.get(WORLD_NODES_KEY) != WORLD_NODES_VERSION:
        build_sky_nodes(world.node_tree)
        world[WORLD_NODES_KEY] = WORLD_NODES_VERSION
        # EEVEE would turn the lit ground's light (brighter than its threshold) into a sun
        # shining up from below, which the ground shadows: our sky has the lamp for a sun.
        world.sun_threshold = 0.0
    for sky in (n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky"):
        for name in ("sun_elevation", "sun_rotation"):
            sky.driver_remove(name)
        sky.sun_elevation = elevation
        sky.sun_rotation = azimuth % (2 * math.pi)
        if follow is not None:
            _follow(sky, follow)
    return world, replaced


def _follow(sky, sun):
    """Drivers that point the sky's sun along the lamp's world +Z (matrix_world's third column)."""
    # The axis over its length: a scaled lamp or parent lengthens it (asin of 2 failed the driver).
    elevation = "asin(min(max(z / max(sqrt(x * x + y * y + z * z), 1e-12), -1), 1))"
    for name, expression, axes in (("sun_elevation", elevation, "xyz"),
                                   ("sun_rotation", "atan2(x, y) + (2 * pi if x < 0 else 0)", "xy")):
        drivers.drive(sky, name, expression, drivers.lamp_axis(sun, axes))


def followed_sun(sky):
    """The sun whose axis the sky's drivers follow, or None."""
    tree = sky.id_data
    path = sky.path_from_id("sun_elevation")
    for curve in tree.animation_data.drivers if tree.animation_data is not None else ():
        if curve.data_path == path and curve.driver.variables:
            return curve.driver.variables[0].targets[0].id
    return None


def follow_scene_sun(scene):
    """Point our sky at the artist's sun where it is another now (theirs deleted and a new one
    added, or ours replaced by theirs), and EEVEE's ground light at the scene's sun; True when
    the sky's drivers changed."""
    world = own.scene_world(scene)
    if world is None or world.node_tree is None or world.library is not None:  # linked: not ours to edit
        return False
    skies = [n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky"]
    if not skies:
        return False
    sun = scene_sun(scene)
    changed = sky_eevee.followed_sun(world) != sun
    if changed:  # the ground's light in EEVEE follows our lamp too
        sky_eevee.follow_sun(world, sun)
    if sun is None or is_ours(sun):
        return changed
    for sky in skies:
        if followed_sun(sky) != sun:
            _follow(sky, sun)
            changed = True
    return changed


def scene_bounds(scene, margin):
    """World-space box around the scene's renderable geometry (ours excluded but a dune field;
    its horizon ring reaches kilometres), plus margin."""
    kinds = {"MESH", "CURVE", "SURFACE", "META", "FONT", "POINTCLOUD", "VOLUME"}
    corners = [obj.matrix_world @ Vector(corner) for obj in scene.objects
               if obj.type in kinds and obj.get(own.OBJECT_KEY) in (None, *own.SCENERY)
               and not obj.hide_render
               for corner in obj.bound_box]
    if not corners:
        half = units.to_units(scene, 10.0)
        return np.array([-half, -half, 0.0]) - margin, np.array([half, half, half]) + margin
    points = np.array([[c.x, c.y, c.z] for c in corners])
    return points.min(0) - margin, points.max(0) + margin


def haze_reach(scene, extinction):
    """Scene units after which the clearest channel lets less than CLEAR through; capped at
    MAX_REACH_M and at the camera's clip end (nothing beyond it is rendered)."""
    cap = units.to_units(scene, MAX_REACH_M)
    camera = shot.scene_camera(scene)
    if camera is not None:
        cap = min(cap, camera.data.clip_end)
    clearest = float(np.min(extinction))
    if not clearest > 0.0:
        return cap
    return min(cap, math.log(1.0 / CLEAR) / clearest)


def shot_bounds(scene, reach, margin, floor):
    """The box the camera looks through over the frame range: `reach` out from wherever the
    camera stands, in every horizontal direction (a turned camera or another frame size stays
    inside), up to the highest point any view reaches, no lower than `floor` (the rays stop at
    the ground). None without a camera."""
    camera = shot.scene_camera(scene)
    if camera is None:
        return None
    views = shot.camera_views(scene, camera)
    points = shot.reach_points(views, reach)
    cameras = np.array([view["matrix"][:2, 3] for view in views])
    region = np.asarray(holding_region(cameras, points[:, :2], reach, margin))
    low = np.r_[region[:2], points[:, 2].min() - margin]
    high = np.r_[region[2:], points[:, 2].max() + margin]
    low[2] = max(low[2], floor)
    high[2] = max(high[2], low[2] + margin)
    return low, high


def volume_color(coefficients):
    """(Color, Density) for Volume Scatter: the coefficients over their largest, and that largest."""
    strongest = float(np.max(coefficients))
    if strongest <= 0:
        return (1.0, 1.0, 1.0, 1.0), 0.0
    ratio = np.asarray(coefficients) / strongest
    return (*map(float, ratio), 1.0), strongest


def ensure_volume(scene, coefficients, low, high, dust=None):
    """This scene's dust box over low..high; removed when nothing scatters.

    coefficients: per scene unit. dust: None for homogeneous air (cheap), or a dict with
    "scatter" (per unit, grey forward-scattering dust, Henyey-Greenstein "anisotropy") and
    "field" (Dust Field inputs, or None for no wind-lifted patches) and "haze" (per unit, the
    same grains everywhere alike, Koschmieder's aerial perspective). The material holds only
    the branches in use.
    """
    box = own.scene_object(scene, own.DUST_VOLUME)
    dust = dust or {}
    scatters = dust.get("scatter", 0.0) > 0.0 or dust.get("haze", 0.0) > 0.0
    if float(np.max(coefficients)) <= 0.0 and not scatters:
        if box is not None:
            own.remove_with_data(box)
        return None
    if box is None:
        mesh = bpy.data.meshes.new("Sandscape Dust")
        verts = [(x, y, z) for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)]
        faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
        mesh.from_pydata(verts, [], faces)
        box = own.new_volume_object(scene, "Sandscape Dust", own.DUST_VOLUME, mesh)
        material = own.mark(bpy.data.materials.new("Sandscape Dust"), own.MATERIAL_KEY, own.DUST)
        mesh.materials.append(material)
    # The sun lamp carries the whole sky's extinction already (the sky model's own sun): the box
    # dims what the camera sees through it, not the light again (its haze took the 6 degree sun
    # through kilometres of box down to a few per cent, and the sand went grey).
    box.visible_shadow = False
    box.location = tuple((np.asarray(low) + np.asarray(high)) / 2)
    box.scale = tuple(np.asarray(high) - np.asarray(low))
    _build_volume_material(box.active_material, coefficients, dust, scene)
    return box


def _build_volume_material(material, coefficients, dust, scene):
    tree = material.node_tree
    if tree.animation_data is not None:
        tree.animation_data_clear()
    tree.nodes.clear()
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Output")
    factor = None
    if dust.get("field") is not None:
        field = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Dust Field", label="Dust Field",
                           node_tree=h.ensure_group(dust_field), inputs=dust["field"])
        field.inputs["FPS"].default_value = shot.frames_per_second(scene)
        evaluation.drive_by_frame(field.inputs["Frame"])
        factor = field.outputs["Factor"]

    def set_density(socket, value, name):
        if factor is None:
            socket.default_value = value
        else:
            h.link(tree, h.math(tree, "MULTIPLY", factor, value, label=name).outputs[0], socket)

    color, strongest = volume_color(coefficients)
    shaders = []
    if strongest > 0:
        air_node = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Rayleigh", label="Rayleigh",
                              node_tree=h.ensure_group(dust_volume), inputs={"Color": color})
        set_density(air_node.inputs["Density"], strongest, "Air × Dust Field")
        shaders.append(air_node.outputs["Volume"])
    haze = dust.get("haze", 0.0)
    if dust.get("scatter", 0.0) > 0 or haze > 0:
        # The haze is the same grains everywhere alike (the wind's patches do not carry it), in
        # the dust's own node: Cycles counts a volume's closures 32 times over, and a third one in
        # this material went past its 64 and dropped closures from the frame (the glints went).
        grains = h.add_node(tree, "ShaderNodeVolumeScatter", name="Sandscape Dust Grains",
                            label="Dust and Haze (Henyey-Greenstein)", phase="HENYEY_GREENSTEIN",
                            inputs={"Color": (1.0, 1.0, 1.0, 1.0), "Anisotropy": dust["anisotropy"]})
        scatter = dust.get("scatter", 0.0)
        if factor is None or scatter <= 0:
            grains.inputs["Density"].default_value = scatter + haze
        else:
            patches = h.math(tree, "MULTIPLY", factor, scatter, label="Dust × Dust Field").outputs[0]
            if haze > 0:
                patches = h.math(tree, "ADD", patches, haze, label="+ Haze").outputs[0]
            h.link(tree, patches, grains.inputs["Density"])
        shaders.append(grains.outputs[0])
    volume = shaders[0]
    if len(shaders) == 2:
        add = h.add_node(tree, "ShaderNodeAddShader", name="Sandscape Air + Dust")
        h.link(tree, shaders[0], add.inputs[0])
        h.link(tree, shaders[1], add.inputs[1])
        volume = add.outputs[0]
    h.link(tree, volume, output.inputs["Volume"])
    h.arrange(tree, set_widths=False)


def apply(scene, settings):
    """Sun, sky and volume from the settings; returns what was done, for the report.

    Densities are per metre in the settings and per scene unit in the volume.
    """
    sun, elevation, azimuth, followed, changes = ensure_sun(
        scene, settings.sun_elevation, settings.sun_azimuth, settings.sun_from_sky, settings.aim_sun)
    world, replaced = ensure_sky(scene, elevation, azimuth, settings.replace_world,
                                 follow=sun if followed else None)
    if replaced is not None:
        changes.append(f"world '{replaced.name}' replaced by '{world.name}' (kept with a fake user: "
                       "switch back in World properties)")
    # What level grey ground asks for under this lamp, and the sky where it is ours.
    lamp = (sun.data.energy, tuple(sun.data.color))
    exposure = round(sky_sun.exposure(elevation, lamp, sky=world is not None), 2)
    if settings.set_exposure and round(scene.view_settings.exposure, 2) != exposure:
        changes.append(f"exposure {scene.view_settings.exposure:+.2f} → {exposure:+.2f}")
        scene.view_settings.exposure = exposure
    per_metre = air.rayleigh_coefficients(settings.density, tuple(settings.wavelengths))
    coefficients = np.asarray(per_metre) * units.metres_per_unit(scene)
    geometry_low, geometry_high = scene_bounds(scene, 0.0)
    ground = geometry_low[2]
    field = None
    if settings.use_wind:
        field = {"Wind": tuple(settings.wind), "Scale": settings.dust_scale, "Coverage": settings.coverage,
                 "Softness": settings.softness, "Ground": float(ground), "Falloff": settings.falloff}
    haze = 0.0
    if settings.use_haze:
        haze = air.haze_extinction(settings.visibility)  # per scene unit: the visibility is in them
    dust = {"scatter": settings.dust_density * units.metres_per_unit(scene),
            "anisotropy": settings.anisotropy, "field": field, "haze": haze}
    # Sized to the shot: a box fitted to the geometry ended in a visible edge (a 4 m slab over
    # the demo's dunes, a glowing square round a lone cube). Wind-lifted dust covers about
    # Coverage of the air, so its haze reaches that much further.
    extinction = (coefficients + dust["scatter"]) * (settings.coverage if field else 1.0) + haze
    bounds = shot_bounds(scene, haze_reach(scene, extinction), settings.margin, ground - settings.margin)
    low, high = bounds or (geometry_low - settings.margin, geometry_high + settings.margin)
    box = ensure_volume(scene, coefficients, low, high, dust)
    if box is not None:
        box[FAR_HAZE_KEY] = haze  # what the far haze beyond the box takes
    # EEVEE's lighting world takes the haze's scattered sunlight (its volumes light no surface).
    # The wind's dust hugs the ground (metres), so the haze alone: it fills the box.
    if box is not None and haze > 0:
        sky_eevee_haze.follow(world, haze, settings.anisotropy, float(high[2] - ground),
                              float(np.min(high[:2] - low[:2])) / 2)
    else:
        sky_eevee_haze.follow(world)
    sand.set_wind(scene, settings.wind)  # one wind for the dust and the sand's ripples
    walker_wind.set_wind(scene, settings.wind)  # and for the walker's scarf
    sand_eevee.follow_scene_sun(scene)
    sky_eevee.follow_sun(world, sun)
    sky_eevee.follow_clamp(world, scene)
    sky_eevee_clouds.follow_scene(scene)
    ground, ground_image, ground_read = sky_eevee_ground.refresh(scene)  # the sand, else the artist's ground
    haze_shell, _ = refresh_far_haze(scene)  # hollowed round the box as it is now
    # Volume sampling, like the exposure, is the artist's: the quality presets set it.
    return {"sun": sun, "followed": followed, "elevation": elevation, "azimuth": azimuth, "world": world,
            "volume": box, "coefficients": per_metre, "exposure": exposure, "changes": changes,
            "far_haze": haze_shell,
            "ground": ground, "ground_image": ground_image, "ground_read": ground_read}


def clip_warning(scene, box):
    """Why the camera sees the bare sky short of the haze, and what to change; or None. The haze
    reaches at least the box's nearest side; Cycles ends a ray at the camera's Clip End."""
    camera = scene.camera
    if box is None or camera is None or camera.type != "CAMERA" or not box.get(FAR_HAZE_KEY, 0.0) > 0:
        return None
    bpy.context.view_layer.update()
    where = np.array(camera.matrix_world.translation)
    low, high = box_bounds(box)
    reach = float(np.min(np.concatenate([where[:2] - low[:2], high[:2] - where[:2]])))
    if reach <= 0 or camera.data.clip_end >= reach:
        return None
    clips, reaches = units.distinct_length_texts(scene, [camera.data.clip_end, reach])
    return (f"Camera '{camera.name}' clips at {clips}, short of the haze, which reaches {reaches}: past its "
            f"Clip End it sees the bare sky. Raise its Clip End (Camera ▸ Lens) to at least "
            f"{units.length_text(scene, units.round_up(reach))}")
