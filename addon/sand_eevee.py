"""The sand's own output for EEVEE: the same surface, balanced to Cycles' brightness.

EEVEE renders Physical Sand's rough diffuse as Lambert and its sheen like a diffuse: under a low
sun the sand came out a third as bright as in Cycles seen with the sun behind, under a high sun
brighter, and its sky light at grazing views dimmer. The material gets a second Material Output
that only EEVEE uses, balanced by Sandscape EEVEE Balance's two factors: the balance on the sun's
light (the Cycles surface scaled by it where Cycles is dimmer; where it is brighter the sand's own
sun's part, EEVEE's sand less its ambient, times (balance - 1) added where the sun reaches) and
the ambient balance on the rest (the sand's ambient, the ambient light at the normal times its
colour plus what its sheen adds, times the ambient balance less what the scale kept of it,
added; an emission draws no negative light, so what that takes away comes off the scale). The
sun's direction reaches the group by simple-expression drivers on the scene's sun lamp (no
Python needed on a farm). Cycles' output is untouched. The Journey look's EEVEE output is its own
EEVEE Shader (its contrast through one diffuse, the driven sun undoing Lambert's cosine) with the
glints on top.
"""

import math

from ..node_groups import eevee_balance
from ..node_groups import helper as h
from . import drivers
from . import ownership as own
from . import sand_eevee_light as light_probes
from .sand_eevee_light import AMBIENT, SAND_AMBIENT, SUN_LIGHT, SUN_LIGHT_PREFIX
from .sun_lamp import scene_sun

CYCLES_OUTPUT = "Sandscape Output"
OUTPUT, BALANCE, SUN = "Sandscape EEVEE Output", "Sandscape EEVEE Balance", "Sandscape EEVEE Sun"
SCALE, BOOST, BOOST_COLOR, BOTH = ("Sandscape EEVEE Scale", "Sandscape EEVEE Boost",
                                   "Sandscape EEVEE Boost Color", "Sandscape EEVEE Surface")
DOWN, UP = "Sandscape EEVEE Dimmer", "Sandscape EEVEE Brighter"
DOWN_HELD, UP_HELD = "Sandscape EEVEE Dimmer ≥ 0", "Sandscape EEVEE Brighter ≥ 0"
FRAME = "Sandscape EEVEE Frame"
JOURNEY_SURFACE = "Sandscape EEVEE Journey Surface"
BOOST_LIGHT = "Sandscape EEVEE Boost Light"  # before 2026-12-07: the sand's colour times the light added
SAND_RGB, SUN_PART = "Sandscape EEVEE Sand RGB", "Sandscape EEVEE Sun Part"
SUN_PART_HELD, BOOST_REACH = "Sandscape EEVEE Sun Part ≥ 0", "Sandscape EEVEE Boost Reach"
# How much of the sun's light arrives (EEVEE's shadow): the sun's light here over the lamp's
# unshadowed light at this normal; lit glints blend in by it.
SUN_IRRADIANCE, GLINTS_WHERE_LIT = "Sandscape EEVEE Sun Irradiance", "Sandscape EEVEE Glints Where Lit"
SUN_REACH = tuple(f"Sandscape EEVEE Sun Reach {part}" for part in (
    "Lamp Total", "Lit Total", "Cosine", "Lamp at Normal", "Over Pi", "Held", "Share"))
# Where the balance dims (below 1) it scales the whole surface: the ambient's share it took is
# given back, and the ambient balanced: the sand's colour times the ambient light at the normal
# times (ambient balance − min(balance, 1)).
AMBIENT_KEPT, SUN_BOOSTED, LIGHT_CORRECTION = ("Sandscape EEVEE Ambient Kept", "Sandscape EEVEE Sun Boosted",
                                               "Sandscape EEVEE Light Correction")
AMBIENT_SCALE, AMBIENT_GIVEN = "Sandscape EEVEE Ambient Scale", "Sandscape EEVEE Ambient Given"
AMBIENT_TINTED = "Sandscape EEVEE Ambient Tinted"  # the ambient balance per channel
# What keeps the light added positive: what the ambient balance takes comes off the surface's scale.
POSITIVE = tuple(f"Sandscape EEVEE Light Added ≥ 0 {index}" for index in range(9))
NODES = (OUTPUT, BALANCE, SUN, SCALE, BOOST, BOOST_COLOR, BOTH, DOWN, UP, DOWN_HELD, UP_HELD, FRAME,
         JOURNEY_SURFACE, BOOST_LIGHT, SUN_IRRADIANCE, GLINTS_WHERE_LIT, AMBIENT_KEPT, SUN_BOOSTED,
         LIGHT_CORRECTION, AMBIENT_SCALE, AMBIENT_GIVEN, SAND_RGB, SUN_PART, SUN_PART_HELD,
         BOOST_REACH, AMBIENT_TINTED) + POSITIVE + SUN_LIGHT + SAND_AMBIENT + SUN_REACH
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
    # shade (both looks), the dimming balance scaling the ambient; before 2026-12-07 the ambient
    # from one probe and not balanced; before 2026-12-08 its balance one factor for all channels,
    # and what it took away an emission's negative light, drawn as none.
    older = own.node(tree, GLINTS_WHERE_LIT) is None or own.node(tree, AMBIENT) is None or (
        not journey and any(own.node(tree, name) is None
                            for name in (AMBIENT_KEPT, AMBIENT_SCALE, SAND_RGB, AMBIENT_TINTED, POSITIVE[0])))
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
    displacement (painted prints, ripples), relinked after either changed; Shader to RGB reads the
    sand under the glints."""
    cycles, output = own.node(tree, CYCLES_OUTPUT), own.node(tree, OUTPUT)
    if cycles is None or output is None:
        return
    scale = own.node(tree, SCALE)  # none for Journey: its EEVEE surface is its own
    where_lit = own.node(tree, GLINTS_WHERE_LIT)
    surface = cycles.inputs["Surface"].links
    base = _glint_base(surface[0].from_socket) if surface else None
    sand_rgb = own.node(tree, SAND_RGB)  # the sand under any glints: its sun's part is what the balance lifts
    if sand_rgb is not None and (base or surface):
        h.link(tree, base or surface[0].from_socket, sand_rgb.inputs["Shader"])
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
    # Where it is brighter: the sand's own sun's part (EEVEE's sand less its ambient) times
    # (balance − 1), where the sun reaches.
    up = h.math(tree, "SUBTRACT", ratio, 1.0, label="Balance − 1")
    up.name = UP
    extra = h.math(tree, "MAXIMUM", up.outputs[0], 0.0)
    extra.name = UP_HELD
    # The balance corrects the sun's light (it was fitted to it); the light less the sun's (the
    # sky's, the haze's, the ground's), which reaches the shade too, has its own ambient balance.
    _, where_lit, made = _glints_where_lit(tree, normal[0].from_socket if normal else None, sun.outputs[0])
    color = h.add_node(tree, "ShaderNodeVectorMath", name=BOOST_COLOR, label="Sand Colour", operation="SCALE",
                       inputs={"Scale": 1.0})
    ambient, ambient_nodes = light_probes.sand_ambient(tree, normal[0].from_socket if normal else None,
                                                       tree.nodes[AMBIENT].outputs[0], color.outputs[0])
    sand_rgb = h.add_node(tree, "ShaderNodeShaderToRGB", name=SAND_RGB, label="EEVEE's Sand")  # fed by sync()
    sun_part = h.vector_math(tree, "SUBTRACT", sand_rgb.outputs["Color"], ambient, label="Its Sun's Part")
    sun_part.name = SUN_PART
    held = h.vector_math(tree, "MAXIMUM", sun_part.outputs[0], (0.0, 0.0, 0.0), label="≥ 0")
    held.name = SUN_PART_HELD
    reach = where_lit.inputs["Fac"].links[0].from_socket
    reached = h.math(tree, "MULTIPLY", extra.outputs[0], reach, label="(Balance − 1) Where the Sun Reaches")
    reached.name = BOOST_REACH
    boosted = h.vector_math(tree, "SCALE", held.outputs[0], label="Sun Part × (Balance − 1)")
    boosted.name = SUN_BOOSTED
    h.link(tree, reached.outputs[0], boosted.inputs["Scale"])
    # The ambient's own balance per channel (K times its tint), less what the scale kept of it:
    # (1 − min(balance, 1)) + (K tint − 1).
    tinted = h.vector_math(tree, "SCALE", balance.outputs["Ambient Tint"], label="K × Tint")
    tinted.name = AMBIENT_TINTED
    h.link(tree, balance.outputs["Ambient Balance"], tinted.inputs["Scale"])
    ambient_scale = h.vector_math(tree, "ADD", clamped.outputs[0], tinted.outputs[0])
    ambient_scale.name = AMBIENT_SCALE
    given = h.vector_math(tree, "SUBTRACT", ambient_scale.outputs[0], (1.0, 1.0, 1.0),
                          label="K × Tint − min(Balance, 1)")
    given.name = AMBIENT_GIVEN
    # An emission's negative channels draw as none (EEVEE and Cycles): what the ambient balance
    # takes away (t, its most negative channel's) comes off the surface's scale instead, and t
    # times the sand (its ambient and its sun's part) goes back into the light added.
    taken, taken_nodes = _taken(tree, given.outputs[0])
    given_back = h.vector_math(tree, "ADD", given.outputs[0], taken, label="+ t")
    kept = h.vector_math(tree, "MULTIPLY", ambient, given_back.outputs[0],
                         label="Sand's Ambient × (K × Tint − min(Balance, 1) + t)")
    kept.name = AMBIENT_KEPT
    sun_back = h.vector_math(tree, "SCALE", held.outputs[0], label="Sun Part × t")
    h.link(tree, taken, sun_back.inputs["Scale"])
    scale_fac = h.math(tree, "ADD", clamped.outputs[0], taken, label="Surface Taken")
    scale_fac.use_clamp = True
    h.link(tree, scale_fac.outputs[0], scale.inputs["Fac"])
    kept_and_sun = h.vector_math(tree, "ADD", kept.outputs[0], sun_back.outputs[0])
    correction = h.vector_math(tree, "ADD", boosted.outputs[0], kept_and_sun.outputs[0], label="Light to Add")
    correction.name = LIGHT_CORRECTION
    positive = (given_back, sun_back, scale_fac, kept_and_sun, *taken_nodes)
    for name, node in zip(POSITIVE, positive, strict=True):
        node.name = name
    boost = h.add_node(tree, "ShaderNodeEmission", name=BOOST, label="As Cycles (light added)",
                       inputs={"Strength": 1.0})
    h.link(tree, correction.outputs[0], boost.inputs["Color"])
    h.link(tree, where_lit.outputs[0], scale.inputs[1])  # sync() links the mix's two sides
    both = h.add_node(tree, "ShaderNodeAddShader", name=BOTH)
    h.link(tree, scale.outputs[0], both.inputs[0])
    h.link(tree, boost.outputs[0], both.inputs[1])
    h.link(tree, both.outputs[0], output.inputs["Surface"])
    frame = h.frame(tree, "EEVEE: Balanced to Cycles", (sun, balance, down, clamped, scale, up, extra, color,
                                                         *made, *ambient_nodes, sand_rgb, sun_part, held,
                                                         reached, boosted, tinted, ambient_scale,
                                                         given, kept, *positive, correction, boost,
                                                         both, output))
    frame.name = FRAME
    return output


def _glints_where_lit(tree, normal, sun):
    """Lit glints where the sun reaches: EEVEE's world light has no shadow, so facets in the shade
    mirrored the bright sky round the sun, which Cycles' dunes hide. A Mix Shader by the share of
    the sun's light that arrives (its two sides linked by the caller). Returns (the sun's light
    socket, the mix, the nodes made)."""
    lit, lit_nodes = light_probes.sun_light(tree, normal, sun)
    reach, reach_nodes = _sun_reach(tree, lit, tree.nodes[f"{SUN_LIGHT_PREFIX}N·L"].outputs["Value"])
    where_lit = h.add_node(tree, "ShaderNodeMixShader", name=GLINTS_WHERE_LIT,
                           label="Glints Where the Sun Reaches")
    h.link(tree, reach, where_lit.inputs["Fac"])
    return lit, where_lit, (*lit_nodes, *reach_nodes, where_lit)


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


def _taken(tree, given):
    """t = max(0, −(the lowest channel of `given`)): what the ambient balance takes away. Returns
    (the socket, the nodes)."""
    channels = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, given, channels.inputs[0])
    lower = h.math(tree, "MINIMUM", channels.outputs[0], channels.outputs[1])
    lowest = h.math(tree, "MINIMUM", lower.outputs[0], channels.outputs[2])
    negated = h.math(tree, "MULTIPLY", lowest.outputs[0], -1.0)
    held = h.math(tree, "MAXIMUM", negated.outputs[0], 0.0, label="t")
    return held.outputs[0], (channels, lower, lowest, negated, held)
