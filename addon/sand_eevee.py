"""The sand's own output for EEVEE: the same surface, balanced to Cycles' brightness.

EEVEE renders Physical Sand's rough diffuse as Lambert and its sheen like a diffuse: under a low
sun the sand came out a third as bright as in Cycles seen with the sun behind, under a high sun
brighter. The material gets a second Material Output that only EEVEE uses, whose surface is the
Cycles surface scaled by Sandscape EEVEE Balance where Cycles is dimmer (the light less the sun's
given back, so only the sun's is dimmed), and the sand's colour times the sun's light times
(balance - 1) added where it is brighter. The sun's direction reaches the group by simple-
expression drivers on the scene's sun lamp (no Python needed on a farm). Cycles' output is
untouched. The Journey look's EEVEE output is its own EEVEE Shader (its contrast through one
diffuse, the driven sun undoing Lambert's cosine) with the glints on top.
"""

import math

from ..node_groups import eevee_balance
from ..node_groups import helper as h
from . import drivers
from . import ownership as own
from .sun_lamp import scene_sun

CYCLES_OUTPUT = "Sandscape Output"
OUTPUT, BALANCE, SUN = "Sandscape EEVEE Output", "Sandscape EEVEE Balance", "Sandscape EEVEE Sun"
SCALE, BOOST, BOOST_COLOR, BOTH = ("Sandscape EEVEE Scale", "Sandscape EEVEE Boost",
                                   "Sandscape EEVEE Boost Color", "Sandscape EEVEE Surface")
DOWN, UP = "Sandscape EEVEE Dimmer", "Sandscape EEVEE Brighter"
DOWN_HELD, UP_HELD = "Sandscape EEVEE Dimmer ≥ 0", "Sandscape EEVEE Brighter ≥ 0"
FRAME = "Sandscape EEVEE Frame"
JOURNEY_SURFACE = "Sandscape EEVEE Journey Surface"
# The sun's light alone on a white Lambert surface here (shadow and all): EEVEE's lighting of a
# diffuse at the normal, less its lighting at the normal turned square to the sun (no sunlight,
# nearly the same sky and haze).
SUN_LIGHT_PREFIX, BOOST_LIGHT = "Sandscape EEVEE Sun Light ", "Sandscape EEVEE Boost Light"
SUN_LIGHT = tuple(f"{SUN_LIGHT_PREFIX}{part}" for part in (
    "Geometry", "Sun", "N·L", "Along Sun", "Off Sun", "Square to Sun", "Lit", "Unlit", "Lit RGB", "Unlit RGB",
    "Difference", "Held"))
# How much of the sun's light arrives (EEVEE's shadow): the sun's light here over the lamp's
# unshadowed light at this normal; lit glints blend in by it.
SUN_IRRADIANCE, GLINTS_WHERE_LIT = "Sandscape EEVEE Sun Irradiance", "Sandscape EEVEE Glints Where Lit"
SUN_REACH = tuple(f"Sandscape EEVEE Sun Reach {part}" for part in (
    "Lamp Total", "Lit Total", "Cosine", "Lamp at Normal", "Over Pi", "Held", "Share"))
# Where the balance dims (below 1) it scales the whole surface: the ambient's share it took is
# given back, the sand's colour times (1 − balance) times the light with the sun's taken out.
AMBIENT_KEPT, SUN_BOOSTED, LIGHT_CORRECTION = ("Sandscape EEVEE Ambient Kept", "Sandscape EEVEE Sun Boosted",
                                               "Sandscape EEVEE Light Correction")
NODES = (OUTPUT, BALANCE, SUN, SCALE, BOOST, BOOST_COLOR, BOTH, DOWN, UP, DOWN_HELD, UP_HELD, FRAME,
         JOURNEY_SURFACE, BOOST_LIGHT, SUN_IRRADIANCE, GLINTS_WHERE_LIT, AMBIENT_KEPT, SUN_BOOSTED,
         LIGHT_CORRECTION) + SUN_LIGHT + SUN_REACH
REACH_MIN_COSINE = 0.02  # below it the sun's light and the lamp's are both near 0: held


def attach(material, scene, look_node, look, glint=None):
    """Give our sand material its EEVEE output, or take it away. PHYSICAL: the Cycles surface
    balanced; JOURNEY: the look's EEVEE Shader with the glints' facets (or emission) on top; none
    where the look is the artist's own group (the balance was measured on ours)."""
    tree = material.node_tree
    cycles = own.node(tree, CYCLES_OUTPUT)
    if cycles is None:
        return
    journey = look == "JOURNEY" and look_node is not None and glint is not None and \
        "EEVEE Shader" in look_node.outputs and "Sun Direction" in look_node.inputs
    if not (journey or (look == "PHYSICAL" and look_node is not None)):
        _remove(tree)
        cycles.target = "ALL"
        return
    # Before 2026-11-29: the boost a diffuse (it brightened the sky's light too), lit glints in the
    # shade (both looks), the dimming balance scaling the ambient.
    older = own.node(tree, GLINTS_WHERE_LIT) is None or (not journey and own.node(tree, AMBIENT_KEPT) is None)
    if own.node(tree, OUTPUT) is not None and ((own.node(tree, JOURNEY_SURFACE) is None) == journey or older):
        _remove(tree)  # built for the other look, or an older build
    if journey:
        _ensure_journey_nodes(tree, look_node, glint)
    else:
        _ensure_nodes(tree, look_node)
        color = own.node(tree, BOOST_COLOR).inputs[0]
        colour_links = look_node.inputs["Color"].links
        if colour_links:
            h.link(tree, colour_links[0].from_socket, color)
        else:  # the look's own colour, as it is now (a re-run brings an edited one over)
            color.default_value = tuple(look_node.inputs["Color"].default_value)[:3]
    cycles.target = "CYCLES"
    sync(tree)
    follow_sun(material, scene)


def _remove(tree):
    for name in NODES:
        if own.node(tree, name) is not None:
            tree.nodes.remove(own.node(tree, name))


def sync(tree):
    """The EEVEE output shows what the Cycles output shows: its surface (balanced) and its
    displacement (painted prints, ripples), relinked after either changed."""
    cycles, output = own.node(tree, CYCLES_OUTPUT), own.node(tree, OUTPUT)
    if cycles is None or output is None:
        return
    scale = own.node(tree, SCALE)  # none for Journey: its EEVEE surface is its own
    where_lit = own.node(tree, GLINTS_WHERE_LIT)
    surface = cycles.inputs["Surface"].links
    base = _glint_base(surface[0].from_socket) if surface else None
    targets = (("Displacement", output.inputs["Displacement"]),)
    if scale is not None and where_lit is not None and base is not None:  # lit glints where the sun reaches
        h.link(tree, base, where_lit.inputs[1])
        h.link(tree, surface[0].from_socket, where_lit.inputs[2])
        h.link(tree, where_lit.outputs[0], scale.inputs[1])
    elif scale is not None:
        targets += (("Surface", scale.inputs[1]),)
    for name, target in targets:
        links = cycles.inputs[name].links
        if links:
            h.link(tree, links[0].from_socket, target)
        else:
            for link in target.links:
                tree.links.remove(link)


def _glint_base(socket):
    """The sand under the lit glints when `socket` is their group's surface (its Base's source)."""
    node = socket.node
    if node.bl_idname == "ShaderNodeGroup" and "Facets" in node.outputs and "Base" in node.inputs \
            and node.inputs["Base"].links:
        return node.inputs["Base"].links[0].from_socket
    return None


def follow_sun(material, scene):
    """Drive the balance's sun and the lamp's light the glints' reach is measured against from the
    scene's sun lamp (none: no balance, no lit glints)."""
    sun_node = own.node(material.node_tree, SUN)
    if sun_node is None:
        return
    sun = scene_sun(scene)
    drivers.follow_lamp_axis(sun_node.inputs[:3], sun)
    irradiance = own.node(material.node_tree, SUN_IRRADIANCE)
    if irradiance is not None:
        drivers.follow_lamp_light(irradiance.inputs[:3], sun)


def follows_scene_sun(material, scene):
    """False when the EEVEE output's driven sun is not the scene's sun lamp (one added or swapped
    after the material was made): Update Sand Material or Add Atmosphere points it there."""
    tree = material.node_tree if material is not None else None
    if own.node(tree, SUN) is None:
        return True
    sun = scene_sun(scene)
    path = f'nodes["{SUN}"].inputs[0].default_value'
    curves = tree.animation_data.drivers if tree.animation_data is not None else ()
    driver = next((c.driver for c in curves if c.data_path == path), None)
    if driver is None or not driver.variables:
        return sun is None
    return sun is not None and driver.variables[0].targets[0].id == sun


def follow_scene_sun(scene):
    """Every balanced sand material in the scene follows the scene's sun (Add Atmosphere made or
    found one). Returns how many."""
    materials = {slot.material for obj in scene.objects for slot in getattr(obj, "material_slots", ())
                 if slot.material is not None and slot.material.node_tree is not None}
    followed = [m for m in materials if own.node(m.node_tree, SUN) is not None]
    for material in followed:
        follow_sun(material, scene)
    return len(followed)


def _ensure_journey_nodes(tree, look_node, glint):
    """Journey's EEVEE output: the look's EEVEE Shader (its contrast through one diffuse, lit by
    the driven sun) with the glints' facets, or their emission, added where the sun reaches."""
    output = own.node(tree, OUTPUT)
    if output is None:
        output = h.add_node(tree, "ShaderNodeOutputMaterial", name=OUTPUT, label="EEVEE Output",
                            target="EEVEE")
        sun = h.add_node(tree, "ShaderNodeCombineXYZ", name=SUN, label="Sun Direction (driven)")
        both = h.add_node(tree, "ShaderNodeAddShader", name=JOURNEY_SURFACE, label="Sand + Glints (EEVEE)")
        # The glints where the sun reaches, as on the physical sand (EEVEE's world light has no shadow).
        links = look_node.inputs["Normal"].links if "Normal" in look_node.inputs else ()
        normal = links[0].from_socket if links else None
        _, where_lit, made = _glints_where_lit(tree, normal, sun.outputs[0])
        h.link(tree, where_lit.outputs[0], both.inputs[1])
        frame = h.frame(tree, "EEVEE: Journey's Contrast as a Diffuse", (sun, both, *made, output))
        frame.name = FRAME
    both, where_lit = own.node(tree, JOURNEY_SURFACE), own.node(tree, GLINTS_WHERE_LIT)
    h.link(tree, own.node(tree, SUN).outputs[0], look_node.inputs["Sun Direction"])
    h.link(tree, look_node.outputs["EEVEE Shader"], both.inputs[0])
    on_top = glint.outputs["Facets"] if "Facets" in glint.outputs else glint.outputs.get("Emission")
    if on_top is not None:
        h.link(tree, on_top, where_lit.inputs[2])
    h.link(tree, both.outputs[0], output.inputs["Surface"])
    return output


def _ensure_nodes(tree, look_node):
    output = own.node(tree, OUTPUT)
    if output is not None:
        return output
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name=OUTPUT, label="EEVEE Output", target="EEVEE")
    sun = h.add_node(tree, "ShaderNodeCombineXYZ", name=SUN, label="Sun Direction (driven)")
    balance = h.add_node(tree, "ShaderNodeGroup", name=BALANCE, label="EEVEE Balance",
                         node_tree=h.ensure_group(eevee_balance))
    h.link(tree, sun.outputs[0], balance.inputs["Sun Direction"])
    normal = look_node.inputs["Normal"].links
    if normal:
        h.link(tree, normal[0].from_socket, balance.inputs["Normal"])
    ratio = balance.outputs["Balance"]
    # Where Cycles is dimmer: the surface times the balance (a Mix Shader with nothing).
    down = h.math(tree, "SUBTRACT", 1.0, ratio, label="1 − Balance")
    down.name = DOWN
    scale = h.add_node(tree, "ShaderNodeMixShader", name=SCALE, label="× Balance (below 1)")
    clamped = h.math(tree, "MAXIMUM", down.outputs[0], 0.0)
    clamped.name = DOWN_HELD
    h.link(tree, clamped.outputs[0], scale.inputs["Fac"])
    # Where it is brighter: the sand's colour times the sun's light times (balance − 1).
    up = h.math(tree, "SUBTRACT", ratio, 1.0, label="Balance − 1")
    up.name = UP
    extra = h.math(tree, "MAXIMUM", up.outputs[0], 0.0)
    extra.name = UP_HELD
    # The balance corrects the sun's light (it was fitted to it): the sky's and the haze's, which
    # reach the shade too, are neither brightened where it lifts nor dimmed where it scales.
    lit, where_lit, made = _glints_where_lit(tree, normal[0].from_socket if normal else None, sun.outputs[0])
    boosted = h.vector_math(tree, "SCALE", lit, label="Sun's Light × (Balance − 1)")
    boosted.name = SUN_BOOSTED
    h.link(tree, extra.outputs[0], boosted.inputs["Scale"])
    unlit = tree.nodes[f"{SUN_LIGHT_PREFIX}Unlit RGB"].outputs["Color"]
    kept = h.vector_math(tree, "SCALE", unlit, label="Light Less the Sun's × (1 − Balance)")
    kept.name = AMBIENT_KEPT
    h.link(tree, clamped.outputs[0], kept.inputs["Scale"])
    correction = h.vector_math(tree, "ADD", boosted.outputs[0], kept.outputs[0], label="Light to Add")
    correction.name = LIGHT_CORRECTION
    color = h.add_node(tree, "ShaderNodeVectorMath", name=BOOST_COLOR, label="Sand Colour", operation="SCALE",
                       inputs={"Scale": 1.0})
    light = h.vector_math(tree, "MULTIPLY", color.outputs[0], correction.outputs[0], label="× Light to Add")
    boost = h.add_node(tree, "ShaderNodeEmission", name=BOOST, label="As Cycles (the sun's light alone)",
                       inputs={"Strength": 1.0})
    h.link(tree, light.outputs[0], boost.inputs["Color"])
    light.name = BOOST_LIGHT
    h.link(tree, where_lit.outputs[0], scale.inputs[1])  # sync() links the mix's two sides
    both = h.add_node(tree, "ShaderNodeAddShader", name=BOTH)
    h.link(tree, scale.outputs[0], both.inputs[0])
    h.link(tree, boost.outputs[0], both.inputs[1])
    h.link(tree, both.outputs[0], output.inputs["Surface"])
    frame = h.frame(tree, "EEVEE: Balanced to Cycles", (sun, balance, down, clamped, scale, up, extra, color,
                                                         *made, boosted, kept, correction, light, boost,
                                                         both, output))
    frame.name = FRAME
    return output


def _glints_where_lit(tree, normal, sun):
    """Lit glints where the sun reaches: EEVEE's world light has no shadow, so facets in the shade
    mirrored the bright sky round the sun, which Cycles' dunes hide. A Mix Shader by the share of
    the sun's light that arrives (its two sides linked by the caller). Returns (the sun's light
    socket, the mix, the nodes made)."""
    lit, lit_nodes = _sun_light(tree, normal, sun)
    reach, reach_nodes = _sun_reach(tree, lit, tree.nodes[f"{SUN_LIGHT_PREFIX}N·L"].outputs["Value"])
    where_lit = h.add_node(tree, "ShaderNodeMixShader", name=GLINTS_WHERE_LIT,
                           label="Glints Where the Sun Reaches")
    h.link(tree, reach, where_lit.inputs["Fac"])
    return lit, where_lit, (*lit_nodes, *reach_nodes, where_lit)


def _sun_light(tree, normal, sun):
    """The sun's light on a white Lambert surface at the shading normal (`normal`, None: the
    geometry's), shadowed as EEVEE shadows it: Shader to RGB of a diffuse there, less that of a
    diffuse whose normal is turned square to the sun (N - (N·L) L: no sunlight, nearly the same
    ambient light). Returns (the colour socket, the nodes made)."""
    made = []

    def named(node, part):
        node.name = f"{SUN_LIGHT_PREFIX}{part}"
        made.append(node)
        return node

    if normal is None:
        normal = named(h.add_node(tree, "ShaderNodeNewGeometry"), "Geometry").outputs["Normal"]
    to_sun = named(h.vector_math(tree, "NORMALIZE", sun, label="Sun"), "Sun").outputs[0]
    cosine = named(h.vector_math(tree, "DOT_PRODUCT", normal, to_sun, label="N·L"), "N·L")
    along = named(h.vector_math(tree, "SCALE", to_sun, label="(N·L) L"), "Along Sun")
    h.link(tree, cosine.outputs["Value"], along.inputs["Scale"])
    off = named(h.vector_math(tree, "SUBTRACT", normal, along.outputs[0], label="N − (N·L) L"), "Off Sun")
    square = named(h.vector_math(tree, "NORMALIZE", off.outputs[0], label="Square to the Sun"),
                   "Square to Sun")
    colours = []
    for part, facing in (("Lit", normal), ("Unlit", square.outputs[0])):
        diffuse = named(h.add_node(tree, "ShaderNodeBsdfDiffuse", label=f"White Diffuse ({part})",
                                   inputs={"Color": (1.0, 1.0, 1.0, 1.0)}), part)
        h.link(tree, facing, diffuse.inputs["Normal"])
        rgb = named(h.add_node(tree, "ShaderNodeShaderToRGB", label=f"{part} Light"), f"{part} RGB")
        h.link(tree, diffuse.outputs[0], rgb.inputs["Shader"])
        colours.append(rgb.outputs["Color"])
    difference = named(h.vector_math(tree, "SUBTRACT", *colours, label="The Sun's Light"), "Difference")
    held = named(h.vector_math(tree, "MAXIMUM", difference.outputs[0], (0.0, 0.0, 0.0), label="≥ 0"), "Held")
    return held.outputs[0], made


def _sun_reach(tree, lit, cosine):
    """The share of the lamp's light that reaches here (0 in EEVEE's shadow, 1 in full sun): the
    sun's light on a white Lambert surface (`lit`) over the lamp's unshadowed light at the normal,
    E max(N·L, REACH_MIN_COSINE) / pi, summed over the channels. Returns (the socket, the nodes)."""
    irradiance = h.add_node(tree, "ShaderNodeCombineXYZ", name=SUN_IRRADIANCE,
                            label="Sun Irradiance (driven)")
    parts = iter(SUN_REACH)

    def named(node):
        node.name = next(parts)
        return node

    lamp = named(h.vector_math(tree, "DOT_PRODUCT", irradiance.outputs[0], (1.0, 1.0, 1.0), label="Lamp"))
    arrived = named(h.vector_math(tree, "DOT_PRODUCT", lit, (1.0, 1.0, 1.0), label="Sun's Light"))
    held = named(h.math(tree, "MAXIMUM", cosine, REACH_MIN_COSINE, label="N·L ≥ Limit"))
    at_normal = named(h.math(tree, "MULTIPLY", lamp.outputs["Value"], held.outputs[0], label="Lamp at N"))
    lambert = named(h.math(tree, "MULTIPLY", at_normal.outputs[0], 1.0 / math.pi, label="÷ π"))
    floor = named(h.math(tree, "MAXIMUM", lambert.outputs[0], 1e-9, label="> 0"))
    share = named(h.math(tree, "DIVIDE", arrived.outputs["Value"], floor.outputs[0], label="Sun Reaches"))
    share.use_clamp = True
    return share.outputs[0], (irradiance, lamp, arrived, held, at_normal, lambert, floor, share)
