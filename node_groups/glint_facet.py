"""Sandscape Glint Facet: a glinting grain as a small mirror, lit by real light.

A grain whose Noise exceeds Threshold is a mirror facet (a sharp Glossy BSDF) turned from the
surface normal by a random Tilt, at most as far as Facing Power allows: the facet glints only
where a light reaches it and its mirror sends that light to the camera, so shadows, the sun's
colour and its height apply by construction. The facet's mirror comes on top of the Base shader
(the grain still scatters light as sand does: a mirror in its place showed the darker sky as dark
specks on sunlit sand). The mirror reflects the share of the light Fresnel's equations give a
quartz facet at its angle (IOR): a few percent face-on, so a facet mirroring the sky in shade
adds little to its sand, while one turning the sun to the camera still outshines it. A facet
whose mirror would send the view below the surface adds nothing: the grains around it hide what
it mirrors (EEVEE would show the world under the horizon there).
Twins: core.sand.glint_facets (mask and facet normal), core.sand.facet_fresnel (the mirror's
share).
"""

from ..core import sand
from . import helper as h

NAME = "Sandscape Glint Facet"
VERSION = 6
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("A glinting grain's mirror facet: Noise above Threshold adds a sharp glossy facet, tilted "
               "by Tilt within the spread Facing Power allows, on top of Base")

INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    "Base": ("NodeSocketShader", "The sand (the facets' mirrors come on top)", None, None, None, None),
    "Noise": ("NodeSocketFloat", "Per-grain random value in 0..1: above Threshold the grain is a facet",
              0.0, 0.0, 1.0, None),
    "Tilt": ("NodeSocketColor", "Per-grain random colour in 0..1: which way the facet leans",
             (0.5, 0.5, 0.5, 1.0), None, None, None),
    "Threshold": ("NodeSocketFloat", "Grains whose noise exceeds this can glint: 0 all, 1 none; about "
                  "(1 - threshold) of them", 0.97, 0.0, 1.0, "FACTOR"),
    "Facing Power": ("NodeSocketFloat", "Higher keeps facets near the surface normal (fewer directions "
                     "glint); the facets tilt up to the angle where (N.V)^power is 1/2",
                     8.0, 0.0, None, None),
    "Color": ("NodeSocketColor", "Reflectance of a facet", (1.0, 0.95, 0.85, 1.0), None, None, None),
    "Roughness": ("NodeSocketFloat", "Roughness of a facet's mirror: 0 images the sun disc sharply, and "
                  "only facets turned to within a fraction of a degree glint; 0.3 lets a facet glint over "
                  "about 5 degrees, so glints hold still when the camera moves", 0.3, 0.0, 1.0, "FACTOR"),
    "Normal": ("NodeSocketVector", "Surface normal the facets lean from (unlinked: the shading normal)",
               (0.0, 0.0, 0.0), None, None, h.SURFACE_NORMAL),
    "Coverage": ("NodeSocketFloat", "Share of a glinting grain's area that is mirror (a coarse cell that "
                 "stands for many grains is mostly sand)", 1.0, 0.0, 1.0, "FACTOR"),
    "IOR": ("NodeSocketFloat", "Index of refraction of a facet: its mirror reflects the Fresnel share of "
            "the light at its angle (quartz 1.54: about 5 % face-on, all of it at grazing)",
            sand.QUARTZ_IOR, 1.0, 10.0, None),
}
OUTPUTS = {
    "Shader": ("NodeSocketShader", "Base, with the mirror facets of glinting grains on top"),
    "Mask": ("NodeSocketFloat", "1 on grains that can glint, 0 elsewhere"),
    "Facet Normal": ("NodeSocketVector", "The facet's normal (the surface normal on other grains too)"),
    "Mirror": ("NodeSocketFloat", "Share of the surface the facet's mirror shows: Coverage on a grain "
               "that can glint and mirrors the view above the surface, else 0"),
    "Facets": ("NodeSocketShader", "The mirror facets alone, without Base (an EEVEE output adds them to "
               "its own sand)"),
}


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    normal, normal_nodes = h.normal_or_geometry(tree, inputs["Normal"])

    lit = h.math(tree, "GREATER_THAN", inputs["Noise"], inputs["Threshold"], label="Can Glint")
    # Spread: tan of the half-power angle, cos = 0.5^(1/power), at least MIN_FACET_COS.
    power = h.math(tree, "MAXIMUM", inputs["Facing Power"], 1e-6, label="Power > 0")
    inverse = h.math(tree, "DIVIDE", 1.0, power.outputs[0], label="1 / Power")
    half_cos = h.math(tree, "POWER", 0.5, inverse.outputs[0], label="cos at Half Power")
    cosine = h.math(tree, "MAXIMUM", half_cos.outputs[0], sand.MIN_FACET_COS, label="cos ≥ Limit")
    squared = h.math(tree, "MULTIPLY", cosine.outputs[0], cosine.outputs[0], label="cos²")
    sine_sq = h.math(tree, "SUBTRACT", 1.0, squared.outputs[0], label="sin²")
    sine = h.math(tree, "SQRT", sine_sq.outputs[0], label="sin")
    spread = h.math(tree, "DIVIDE", sine.outputs[0], cosine.outputs[0], label="Spread = tan")
    centred = h.vector_math(tree, "MULTIPLY_ADD", inputs["Tilt"], (2.0, 2.0, 2.0), label="2 Tilt − 1")
    centred.inputs[2].default_value = (-1.0, -1.0, -1.0)
    # Only the part along the surface: a facet leans, it never turns into the ground.
    up = h.vector_math(tree, "DOT_PRODUCT", centred.outputs[0], normal, label="Along the Normal")
    upright = h.vector_math(tree, "SCALE", normal, label="× Normal")
    h.link(tree, up.outputs["Value"], upright.inputs["Scale"])
    sideways = h.vector_math(tree, "SUBTRACT", centred.outputs[0], upright.outputs[0], label="In the Surface")
    lean = h.vector_math(tree, "SCALE", sideways.outputs[0], label="× Spread")
    h.link(tree, spread.outputs[0], lean.inputs["Scale"])
    tilted = h.vector_math(tree, "ADD", normal, lean.outputs[0], label="Normal + Lean")
    facet = h.vector_math(tree, "NORMALIZE", tilted.outputs[0], label="Facet Normal")

    # A dielectric's reflectance at the facet's angle to the view (its mirror's angle to the light).
    fresnel = h.add_node(tree, "ShaderNodeFresnel", label="Facet Fresnel")
    h.link(tree, inputs["IOR"], fresnel.inputs["IOR"])
    h.link(tree, facet.outputs[0], fresnel.inputs["Normal"])
    reflectance = h.vector_math(tree, "SCALE", inputs["Color"], label="Color × Fresnel")
    h.link(tree, fresnel.outputs["Fac"], reflectance.inputs["Scale"])
    mirror = h.add_node(tree, "ShaderNodeBsdfGlossy", label="Facet Mirror", distribution="GGX")
    h.link(tree, reflectance.outputs[0], mirror.inputs["Color"])
    h.link(tree, inputs["Roughness"], mirror.inputs["Roughness"])
    h.link(tree, facet.outputs[0], mirror.inputs["Normal"])
    above, above_nodes = _mirrors_above(tree, facet.outputs[0], normal)
    can = h.math(tree, "MULTIPLY", lit.outputs[0], above, label="Can Glint, Seen")
    covered = h.math(tree, "MULTIPLY", can.outputs[0], inputs["Coverage"], label="× Coverage")
    # Coverage × the mirror (a Mix Shader with nothing as its first shader), on top of the base.
    shown = h.add_node(tree, "ShaderNodeMixShader", label="Mirror × Coverage")
    h.link(tree, covered.outputs[0], shown.inputs["Fac"])
    h.link(tree, mirror.outputs[0], shown.inputs[2])
    mix = h.add_node(tree, "ShaderNodeAddShader", label="Base + Mirror")
    h.link(tree, inputs["Base"], mix.inputs[0])
    h.link(tree, shown.outputs[0], mix.inputs[1])

    h.link(tree, mix.outputs[0], group_out.inputs["Shader"])
    h.link(tree, lit.outputs[0], group_out.inputs["Mask"])
    h.link(tree, facet.outputs[0], group_out.inputs["Facet Normal"])
    h.link(tree, covered.outputs[0], group_out.inputs["Mirror"])
    h.link(tree, shown.outputs[0], group_out.inputs["Facets"])
    h.frame(tree, "Surface Normal", normal_nodes)
    h.frame(tree, "Which Grains", (lit,))
    h.frame(tree, "How Far a Facet Leans", (power, inverse, half_cos, cosine, squared, sine_sq, sine, spread))
    h.frame(tree, "Facet", (centred, up, upright, sideways, lean, tilted, facet, fresnel, reflectance,
                            mirror))
    h.frame(tree, "Mirrors the View Above the Surface", above_nodes)
    h.frame(tree, "Mirror on the Grain", (can, covered, shown, mix))
    h.arrange(tree)


def _mirrors_above(tree, facet, normal):
    """1 where the view mirrored by the facet leaves the surface: R·N = 2 (F·V)(F·N) − V·N > 0,
    V the direction to the camera. Returns the socket and the nodes."""
    geometry = h.add_node(tree, "ShaderNodeNewGeometry")
    view = geometry.outputs["Incoming"]
    f_v = h.vector_math(tree, "DOT_PRODUCT", facet, view, label="F·V")
    f_n = h.vector_math(tree, "DOT_PRODUCT", facet, normal, label="F·N")
    v_n = h.vector_math(tree, "DOT_PRODUCT", view, normal, label="V·N")
    twice = h.math(tree, "MULTIPLY", f_v.outputs["Value"], f_n.outputs["Value"], label="(F·V)(F·N)")
    negate = h.math(tree, "MULTIPLY", v_n.outputs["Value"], -1.0, label="−V·N")
    r_n = h.math(tree, "MULTIPLY_ADD", twice.outputs[0], 2.0, c=negate.outputs[0], label="R·N")
    above = h.math(tree, "GREATER_THAN", r_n.outputs[0], 0.0, label="Above the Surface")
    return above.outputs[0], (geometry, f_v, f_n, v_n, twice, negate, r_n, above)
