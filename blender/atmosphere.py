"""The bpy side of the atmosphere: the sun lamp, the sky world, the bounded dust volume.

A world volume would block a sun lamp completely in Cycles (the world volume is
infinite), so with a sun the scattering medium is a box fitted around the scene.
"""

import math

import bpy
import numpy as np
from mathutils import Vector

from ..core import atmosphere as air
from ..core import post
from ..node_groups import dust_field, dust_volume
from ..node_groups import helper as h
from . import post as post_effects

OBJECT_KEY = "sandscape_object"
WORLD_KEY = "sandscape_world"
# Bump when build_sky_nodes changes: a world built by an older version is rebuilt.
WORLD_NODES_KEY = "sandscape_sky_nodes"
WORLD_NODES_VERSION = 2
SUN, VOLUME = "sun", "dust_volume"


def find_object(kind):
    return next((o for o in bpy.data.objects if o.get(OBJECT_KEY) == kind), None)


def scene_sun(scene):
    """Our sun, else the scene's first sun lamp, else None."""
    ours = find_object(SUN)
    if ours is not None and scene.objects.get(ours.name) is ours:
        return ours
    return next((o for o in scene.objects if o.type == "LIGHT" and o.data.type == "SUN"), None)


def sun_rotation(elevation, azimuth):
    """Euler rotation of a sun lamp that shines from (elevation, azimuth): its +Z points at the sun."""
    return (math.pi / 2 - elevation, 0.0, math.pi - azimuth)


def ensure_sun(scene, elevation, azimuth):
    sun = scene_sun(scene)
    if sun is None:
        sun = bpy.data.objects.new("Sandscape Sun", bpy.data.lights.new("Sandscape Sun", "SUN"))
        sun[OBJECT_KEY] = SUN
        sun.data.energy = 4.0
        scene.collection.objects.link(sun)
    sun.rotation_mode = "XYZ"
    sun.rotation_euler = sun_rotation(elevation, azimuth)
    return sun


def build_sky_nodes(tree):
    """Sky light without a sun disc for every ray but camera rays, which see the disc as well.

    The lamp lights the scene; a disc in the lighting sky would light it twice, yet without
    one the camera would see no sun at all.
    """
    tree.nodes.clear()
    lighting = h.add_node(tree, "ShaderNodeTexSky", (-400, 100), "Sky", sky_type="MULTIPLE_SCATTERING",
                          sun_disc=False)
    seen = h.add_node(tree, "ShaderNodeTexSky", (-400, -200), "Sky with Sun Disc",
                      sky_type="MULTIPLE_SCATTERING", sun_disc=True)
    lit = h.add_node(tree, "ShaderNodeBackground", (-100, 100))
    shown = h.add_node(tree, "ShaderNodeBackground", (-100, -200))
    ray = h.add_node(tree, "ShaderNodeLightPath", (-100, 400))
    mix = h.add_node(tree, "ShaderNodeMixShader", (150, 0), "Camera Sees the Disc")
    output = h.add_node(tree, "ShaderNodeOutputWorld", (350, 0))
    h.link(tree, lighting.outputs["Color"], lit.inputs["Color"])
    h.link(tree, seen.outputs["Color"], shown.inputs["Color"])
    h.link(tree, ray.outputs["Is Camera Ray"], mix.inputs["Fac"])
    h.link(tree, lit.outputs[0], mix.inputs[1])
    h.link(tree, shown.outputs[0], mix.inputs[2])
    h.link(tree, mix.outputs[0], output.inputs["Surface"])


def ensure_sky(scene, elevation, azimuth):
    """Our world with a Sky Texture whose sun matches the lamp; returns (world, replaced world or None).

    A user's world is kept (fake user) and named on ours as "replaced_world" to switch back.
    """
    world = scene.world
    replaced = None
    if world is None or world.get(WORLD_KEY) is None:
        replaced = world
        world = next((w for w in bpy.data.worlds if w.get(WORLD_KEY)), None)
        if world is None:
            world = bpy.data.worlds.new("Sandscape Sky")
            world[WORLD_KEY] = "sky"
        if replaced is not None:
            replaced.use_fake_user = True
            world["replaced_world"] = replaced.name
        scene.world = world
    if world.get(WORLD_NODES_KEY) != WORLD_NODES_VERSION:
        build_sky_nodes(world.node_tree)
        world[WORLD_NODES_KEY] = WORLD_NODES_VERSION
    for sky in (n for n in world.node_tree.nodes if n.bl_idname == "ShaderNodeTexSky"):
        sky.sun_elevation = elevation
        sky.sun_rotation = azimuth % (2 * math.pi)
    return world, replaced


def scene_bounds(scene, margin):
    """World-space box around the scene's renderable geometry (ours excluded), plus margin."""
    kinds = {"MESH", "CURVE", "SURFACE", "META", "FONT", "POINTCLOUD", "VOLUME"}
    corners = [obj.matrix_world @ Vector(corner) for obj in scene.objects
               if obj.type in kinds and obj.get(OBJECT_KEY) is None and not obj.hide_render
               for corner in obj.bound_box]
    if not corners:
        return np.array([-10.0, -10.0, 0.0]) - margin, np.array([10.0, 10.0, 10.0]) + margin
    points = np.array([[c.x, c.y, c.z] for c in corners])
    return points.min(0) - margin, points.max(0) + margin


def volume_color(coefficients):
    """(Color, Density) for Volume Scatter: the coefficients over their largest, and that largest."""
    strongest = float(np.max(coefficients))
    if strongest <= 0:
        return (1.0, 1.0, 1.0, 1.0), 0.0
    ratio = np.asarray(coefficients) / strongest
    return (*map(float, ratio), 1.0), strongest


def ensure_volume(scene, coefficients, low, high, dust=None):
    """Our dust box over low..high; removed when nothing scatters.

    dust: None for homogeneous air (cheap), or a dict with "scatter" (1/m of grey,
    forward-scattering dust, Henyey-Greenstein "anisotropy") and "field" (Dust Field inputs,
    or None for no wind-lifted patches). The material holds only the branches in use.
    """
    box = find_object(VOLUME)
    dust = dust or {}
    if float(np.max(coefficients)) <= 0.0 and not dust.get("scatter", 0.0) > 0.0:
        if box is not None:
            mesh, material = box.data, box.active_material
            bpy.data.objects.remove(box)
            bpy.data.meshes.remove(mesh)
            if material is not None and material.users == 0:
                bpy.data.materials.remove(material)
        return None
    if box is None:
        mesh = bpy.data.meshes.new("Sandscape Dust")
        verts = [(x, y, z) for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)]
        faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
        mesh.from_pydata(verts, [], faces)
        box = bpy.data.objects.new("Sandscape Dust", mesh)
        box[OBJECT_KEY] = VOLUME
        scene.collection.objects.link(box)
        material = bpy.data.materials.new("Sandscape Dust")
        material["sandscape_material"] = "dust"
        mesh.materials.append(material)
        box.display_type = "BOUNDS"  # see through it in the viewport
    box.location = tuple((np.asarray(low) + np.asarray(high)) / 2)
    box.scale = tuple(np.asarray(high) - np.asarray(low))
    _build_volume_material(box.active_material, coefficients, dust, scene)
    return box


def _build_volume_material(material, coefficients, dust, scene):
    tree = material.node_tree
    if tree.animation_data is not None:
        tree.animation_data_clear()
    tree.nodes.clear()
    output = h.add_node(tree, "ShaderNodeOutputMaterial", (600, 0))
    factor = None
    if dust.get("field") is not None:
        field = h.add_node(tree, "ShaderNodeGroup", (-600, -300), "Dust Field",
                           node_tree=h.ensure_group(dust_field), inputs=dust["field"])
        field.inputs["FPS"].default_value = scene.render.fps / scene.render.fps_base
        driver = field.inputs["Frame"].driver_add("default_value").driver
        driver.type = "SCRIPTED"
        driver.expression = "frame"  # a simple expression: evaluated without Python auto-run
        factor = field.outputs["Factor"]

    def set_density(socket, value, location):
        if factor is None:
            socket.default_value = value
        else:
            h.link(tree, h.math(tree, "MULTIPLY", factor, value, location, "× Dust Field").outputs[0], socket)

    color, strongest = volume_color(coefficients)
    shaders = []
    if strongest > 0:
        air_node = h.add_node(tree, "ShaderNodeGroup", (0, 100), "Rayleigh",
                              node_tree=h.ensure_group(dust_volume), inputs={"Color": color})
        set_density(air_node.inputs["Density"], strongest, (-200, 100))
        shaders.append(air_node.outputs["Volume"])
    if dust.get("scatter", 0.0) > 0:
        grains = h.add_node(tree, "ShaderNodeVolumeScatter", (0, -200), "Dust (Henyey-Greenstein)",
                            phase="HENYEY_GREENSTEIN", inputs={"Color": (1.0, 1.0, 1.0, 1.0),
                                                               "Anisotropy": dust["anisotropy"]})
        set_density(grains.inputs["Density"], dust["scatter"], (-200, -200))
        shaders.append(grains.outputs[0])
    volume = shaders[0]
    if len(shaders) == 2:
        add = h.add_node(tree, "ShaderNodeAddShader", (300, 0))
        h.link(tree, shaders[0], add.inputs[0])
        h.link(tree, shaders[1], add.inputs[1])
        volume = add.outputs[0]
    h.link(tree, volume, output.inputs["Volume"])


def apply(scene, settings):
    """Sun, sky and volume from the settings; returns what was done, for the report."""
    elevation, azimuth = settings.sun_elevation, settings.sun_azimuth
    sun = ensure_sun(scene, elevation, azimuth)
    world, replaced = ensure_sky(scene, elevation, azimuth)
    coefficients = air.rayleigh_coefficients(settings.density, tuple(settings.wavelengths))
    low, high = scene_bounds(scene, settings.margin)
    field = None
    if settings.use_wind:
        field = {"Wind": tuple(settings.wind), "Scale": settings.dust_scale, "Coverage": settings.coverage,
                 "Softness": settings.softness, "Ground": float(low[2] + settings.margin),
                 "Falloff": settings.falloff}
    dust = {"scatter": settings.dust_density, "anisotropy": settings.anisotropy, "field": field}
    box = ensure_volume(scene, coefficients, low, high, dust)
    if box is not None and field is not None:
        # Ray marching: 1.8-5.8x faster than the default at equal error (bench/atmosphere.py).
        scene.cycles.volume_biased = True
    return {"sun": sun, "world": world, "replaced": replaced, "volume": box, "coefficients": coefficients}


# ---------------------------------------------------------------- post effects

def view_projection(scene, camera):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    render = scene.render
    width = render.resolution_x * render.resolution_percentage // 100
    height = render.resolution_y * render.resolution_percentage // 100
    projection = np.array(camera.calc_matrix_camera(depsgraph, x=width, y=height))
    return projection @ np.array(camera.matrix_world.inverted())


def key_sun(scene, tree, sun, fade):
    """Key the sun's screen position and the rays' intensity on every frame of the range.

    Keyframes, not a driver: a render farm needs no scripts. Returns [(frame, u, v, intensity)].
    """
    sun_node = post_effects.sun_key_node(tree)
    rays = post_effects.rays_node(tree)
    if tree.animation_data is not None:
        tree.animation_data_clear()
    kept = scene.frame_current
    curve = []
    try:
        for frame in range(scene.frame_start, scene.frame_end + 1):
            scene.frame_set(frame)
            direction = np.array(sun.matrix_world.col[2][:3])
            (u, v), in_front = post.screen_position(view_projection(scene, scene.camera), direction)
            intensity = post.sun_intensity((u, v), in_front, fade)
            if not in_front:
                u, v = 0.5, 0.5  # any finite place: the intensity is 0
            sun_node.inputs["X"].default_value, sun_node.inputs["Y"].default_value = u, v
            rays.inputs["Intensity"].default_value = intensity
            for socket in (sun_node.inputs["X"], sun_node.inputs["Y"], rays.inputs["Intensity"]):
                socket.keyframe_insert("default_value", frame=frame)
            curve.append((frame, u, v, intensity))
    finally:
        scene.frame_set(kept)
    return curve


def apply_post_effects(scene, settings):
    """Our compositor tree on the scene, built for the settings; a user's tree is kept aside."""
    current = scene.compositing_node_group
    ours = next((g for g in bpy.data.node_groups if g.get(post_effects.TREE_KEY)), None)
    replaced = None
    if current is not None and not current.get(post_effects.TREE_KEY):
        replaced = current
        current.use_fake_user = True
    if not (settings.use_blur or settings.use_god_rays):
        if ours is not None:
            previous = bpy.data.node_groups.get(ours.get("replaced_tree", ""))
            bpy.data.node_groups.remove(ours)
            scene.compositing_node_group = previous if replaced is None else replaced
        return {"tree": None, "replaced": replaced, "curve": [], "switched_engine": False}
    if ours is None:
        ours = bpy.data.node_groups.new("Sandscape Post Effects", "CompositorNodeTree")
        ours[post_effects.TREE_KEY] = True
    if replaced is not None:
        ours["replaced_tree"] = replaced.name
    # The volume and environment passes are Cycles passes.
    switched_engine = scene.render.engine != "CYCLES"
    scene.render.engine = "CYCLES"
    view_layer = scene.view_layers[0]
    view_layer.cycles.use_pass_volume_direct = settings.use_blur
    view_layer.cycles.use_pass_volume_indirect = settings.use_blur
    view_layer.use_pass_environment = settings.use_god_rays
    post_effects.build(ours, settings)
    scene.compositing_node_group = ours
    scene.render.use_compositing = True
    curve = []
    if settings.use_god_rays:
        sun = scene_sun(scene)
        curve = key_sun(scene, ours, sun, settings.fade)
    return {"tree": ours, "replaced": replaced, "curve": curve, "switched_engine": switched_engine}
