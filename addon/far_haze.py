"""The bpy side of the far haze (core.far_haze): one object, "Sandscape Far Haze", filling the
cloud layer's sky from the ground to the clouds' base outside the dust box, seen by camera rays
only (the lamp already carries the sky's extinction; the sand's sky light is the world's).

It is there when the scene has all three: a cloud layer, a dust box whose haze is on, and
Sandscape's sky (the haze glows with the sky's colour, which only our sky gives a material). Add
Clouds and Add Atmosphere both remake it, since it spans the one and hollows out the other.
"""

import math

import bpy
import numpy as np
from mathutils import Vector

from ..core import atmosphere as air
from ..core import far_haze as twin
from ..node_groups import helper as h
from . import drivers, units
from . import ownership as own

# The world's sky without its disc: a Sky Texture with a disc takes no direction, and in a
# material it draws no disc. So the disc the camera sees is dimmed as what lies behind (it stays
# far past white: 1e6 at a 6 degree sun); the sky round it is left as it was.
SKY_NODE = "Sandscape Sky"
SEEN_NODE = "Sandscape Sky Seen"  # its Background, whose strength the camera sees
REGION_KEY = "sandscape_region"  # on the cloud layer: (xmin, ymin, xmax, ymax) of its sky
BASE_KEY = "sandscape_base"  # on the cloud layer: the clouds' base
FOLLOWED = ("sun_elevation", "sun_rotation")  # the world's sky follows the lamp: the haze follows it
# The hollow is this share of the box's size wider than the box, and the haze stops this share of
# its height under the clouds' base: faces of two volumes in one place let a ray miss the second
# (it never entered the haze, and the haze changed nothing; at unit scale 0.01 Cycles drew the
# clouds overhead only in a wedge of the sky).
CAVITY_GAP = 1e-3
STEP_SHARE = 10.0  # the shell's step rate: its haze is even along a ray, a few steps integrate it
# On the dust box: the haze's extinction (per scene unit) Add Atmosphere gave it. The far haze takes
# the box's, not the settings': a visibility typed since (or out of range) has not reached the box.
HAZE_KEY = "sandscape_haze_extinction"


def box_bounds(box):
    """World-space (low, high) corners of the dust box (a unit cube, placed and scaled)."""
    corners = np.array([box.matrix_world @ Vector(c) for c in box.bound_box])
    return corners.min(axis=0), corners.max(axis=0)


def box_extinction(scene, box):
    """The haze's extinction in the dust box, per scene unit (0: no haze)."""
    stored = box.get(HAZE_KEY)
    if stored is not None:
        return float(stored)
    settings = scene.sandscape_atmosphere  # a box from before the key: the settings, if they are sound
    visibility = settings.visibility
    usable = settings.use_haze and math.isfinite(visibility) and visibility > 0
    return air.haze_extinction(visibility) if usable else 0.0


def stale_visibility(scene):
    """What to tell the artist when the Visibility setting is not the dust box's (typed since Add
    Atmosphere ran, which alone applies it), or None."""
    box = own.scene_object(scene, own.DUST_VOLUME)
    beta = box_extinction(scene, box) if box is not None else 0.0
    typed = scene.sandscape_atmosphere.visibility
    if not beta > 0 or (math.isfinite(typed) and typed > 0 and math.isclose(
            air.haze_extinction(typed), beta, rel_tol=1e-6)):
        return None
    shown = units.length_text(scene, air.haze_extinction(beta))  # V = 3.912 / beta, and back
    return f"at the dust box's {shown} visibility (Visibility was changed since: Add Atmosphere applies it)"


def why_not(scene):
    """Why the scene gets no far haze, or None: it needs clouds, a hazy dust box and our sky."""
    layer = own.scene_object(scene, own.CLOUDS)
    if layer is None:
        return "no cloud layer"
    if REGION_KEY not in layer or BASE_KEY not in layer:  # made by a Sandscape without the far haze
        return "the cloud layer predates the far haze: run Add Clouds again"
    box = own.scene_object(scene, own.DUST_VOLUME)
    if box is None or not box_extinction(scene, box) > 0:
        return "no haze (Add Atmosphere with Haze on)"
    world = own.scene_world(scene)
    if world is None or own.node(world.node_tree, SKY_NODE) is None:
        return "the world is not Sandscape's sky, whose colour the haze takes"
    return None


def remove(scene):
    shell = own.scene_object(scene, own.FAR_HAZE)
    if shell is not None:
        own.remove_with_data(shell)


def refresh(scene):
    """Make, update or remove the far haze; returns (the object or None, why not or None)."""
    reason = why_not(scene)
    layer = own.scene_object(scene, own.CLOUDS)
    box = own.scene_object(scene, own.DUST_VOLUME)
    mesh = None
    if reason is None:
        bpy.context.view_layer.update()  # the box's matrix after Add Atmosphere moved it
        low, high = box_bounds(box)
        gap = CAVITY_GAP * float(np.max(high - low))
        hollow = (*(low[:2] - gap), *(high[:2] + gap), high[2] + gap)
        base = float(layer[BASE_KEY])
        top = base - CAVITY_GAP * (base - float(low[2]))
        mesh = twin.shell_mesh(tuple(layer[REGION_KEY]), float(low[2]), top, tuple(map(float, hollow)))
        if mesh is None:
            reason = "the dust box holds all of the clouds' sky"
    if reason is not None:
        remove(scene)
        return None, reason
    shell = ensure_object(scene)
    own.set_mesh(shell, *mesh)
    beta = box_extinction(scene, box)
    build_material(shell.active_material, own.scene_world(scene), beta)
    return shell, None


def ensure_object(scene):
    shell = own.scene_object(scene, own.FAR_HAZE)
    if shell is None:
        shell = own.new_volume_object(scene, "Sandscape Far Haze", own.FAR_HAZE)
        shell.hide_select = True  # kilometres wide round the scene: not picked by a click
        material = own.mark(bpy.data.materials.new("Sandscape Far Haze"), own.MATERIAL_KEY, own.FAR_HAZE)
        shell.data.materials.append(material)
    # Camera rays only: the lamp carries the sky's extinction, the world lights the sand.
    shell.visible_camera = True
    shell.visible_diffuse = shell.visible_glossy = shell.visible_transmission = False
    shell.visible_volume_scatter = shell.visible_shadow = False
    return shell


def follow_like(sky, source):
    """Where the world's sky follows a lamp by drivers, the haze's sky gets the same drivers."""
    animation = source.id_data.animation_data
    for name in FOLLOWED:
        sky.driver_remove(name)
        path = source.path_from_id(name)
        curve = next((c for c in animation.drivers if c.data_path == path), None) if animation else None
        if curve is not None:
            variables = [(v.name, v.targets[0].id_type, v.targets[0].id, v.targets[0].data_path)
                         for v in curve.driver.variables]
            drivers.drive(sky, name, curve.driver.expression, variables)


def copied_sky(tree, source, name):
    """A Sky Texture with the world's sky's settings, following its lamp as it does."""
    sky = h.add_node(tree, "ShaderNodeTexSky", name=name, label="The Sky's Colour",
                     sky_type=source.sky_type)
    copied = ("sun_", "air", "aerosol", "ozone", "altitude")  # the sky model's settings
    for prop in source.bl_rna.properties:
        if prop.identifier.startswith(copied) and not prop.is_readonly:
            setattr(sky, prop.identifier, getattr(source, prop.identifier))
    follow_like(sky, source)
    return sky


def build_material(material, world, beta):
    """Volume Absorption (beta) + Emission (beta x the sky in the ray's direction, at least
    HORIZON_RISE up): T behind + (1 - T) sky along any ray."""
    tree = material.node_tree
    if tree.animation_data is not None:
        tree.animation_data_clear()
    tree.nodes.clear()
    geometry = h.add_node(tree, "ShaderNodeNewGeometry", name="Sandscape Ray")
    outward = h.vector_math(tree, "SCALE", geometry.outputs["Incoming"], label="Along the Ray", Scale=-1.0)
    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, outward.outputs[0], split.inputs[0])
    rise = h.math(tree, "MAXIMUM", split.outputs["Z"], twin.HORIZON_RISE, label="Not Below the Horizon")
    direction = h.add_node(tree, "ShaderNodeCombineXYZ")
    for axis in ("X", "Y"):
        h.link(tree, split.outputs[axis], direction.inputs[axis])
    h.link(tree, rise.outputs[0], direction.inputs["Z"])
    sky = copied_sky(tree, own.node(world.node_tree, SKY_NODE), "Sandscape Haze Sky")
    h.link(tree, direction.outputs[0], sky.inputs["Vector"])
    seen = own.node(world.node_tree, SEEN_NODE)
    strength = seen.inputs["Strength"].default_value if seen is not None else 1.0
    glow = h.add_node(tree, "ShaderNodeEmission", name="Sandscape Haze Glow", label="Glows with the Sky",
                      inputs={"Strength": beta * strength})
    h.link(tree, sky.outputs["Color"], glow.inputs["Color"])
    dims = h.add_node(tree, "ShaderNodeVolumeAbsorption", name="Sandscape Haze Extinction",
                      label="Dims What Lies Behind", inputs={"Color": (0.0, 0.0, 0.0, 1.0), "Density": beta})
    both = h.add_node(tree, "ShaderNodeAddShader")
    h.link(tree, dims.outputs[0], both.inputs[0])
    h.link(tree, glow.outputs[0], both.inputs[1])
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Output")
    h.link(tree, both.outputs[0], output.inputs["Volume"])
    material.cycles.volume_step_rate = STEP_SHARE
    h.arrange(tree, set_widths=False)
