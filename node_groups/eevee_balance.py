"""Sandscape EEVEE Balance: how much brighter Cycles renders Sandscape Physical Sand than EEVEE
here, from the view, the sun and the normal, in two factors: Balance on the sun's light and
Ambient Balance on the rest. EEVEE lacks Cycles' rough diffuse and microfiber sheen, so its sand
is dim under a low sun and bright under a high one, and gets less of the sky's light at grazing
views. Ambient Tint makes the second a factor per channel (EEVEE's sky-lit sand is bluer at
grazing views). The sand material's EEVEE output applies them (Cycles' output does not).
Twin: core.eevee_balance.balance, ambient_balance and ambient_tint (fits to both engines' renders).
"""

import math

from ..core import eevee_balance as twin
from . import helper as h

NAME = "Sandscape EEVEE Balance"
VERSION = 10  # 9: the ambient balance's tint, the azimuth as an angle; 10: the fits as one vector chain
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Cycles' brightness of Sandscape sand over EEVEE's at this view, sun and normal: the "
               "factor the sand's EEVEE output applies")

INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    "Sun Direction": ("NodeSocketVector", "Towards the sun, in world space (driven by the sun lamp); "
                      "zero: no sun, a balance of 1", (0.0, 0.0, 0.0), None, None, None),
    "Normal": ("NodeSocketVector", "The surface's normal (unlinked: the shading normal)",
               (0.0, 0.0, 0.0), None, None, h.SURFACE_NORMAL),
}
OUTPUTS = {"Balance": ("NodeSocketFloat", "Cycles' brightness over EEVEE's in the sun's light (1 without a "
                       "sun)"),
           "Ambient Balance": ("NodeSocketFloat", "Cycles' brightness over EEVEE's in the light less the "
                               "sun's (the sky's, the haze's, the ground's)"),
           "Ambient Tint": ("NodeSocketColor", "The ambient balance per channel over Ambient Balance (white "
                            "without a sun)")}


def _clamped_cosine(tree, a, b, label):
    dot = h.vector_math(tree, "DOT_PRODUCT", a, b, label=label)
    held = h.math(tree, "MAXIMUM", dot.outputs["Value"], twin.MIN_COSINE, label=f"{label} ≥ Limit")
    return held, dot


def _monomials(tree, powers, made):
    """√v^i √l^j p^k for each of twin.TERMS, each made once (the three fits share them): sockets, None
    for the constant term (nodes to `made`)."""
    sockets = []
    for exponents in twin.TERMS:
        factors = [powers[axis][power] for axis, power in enumerate(exponents) if power]
        term = factors[0] if factors else None
        for factor in factors[1:]:
            node = h.math(tree, "MULTIPLY", term, factor)
            made.append(node)
            term = node.outputs[0]
        sockets.append(term)
    return sockets


def _polynomials(tree, monomials, made):
    """The three fits' sums at once, (sum c_G m, sum c_K m, sum c_w m) over the monomials, as one
    chain of vector multiply-adds (a third of the nodes, and of the shader's compile time, of
    three scalar chains): the Separate XYZ node (nodes to `made`)."""
    total = None
    for term, *coefficients in zip(monomials, twin.COEFFICIENTS, twin.AMBIENT_COEFFICIENTS,
                                   twin.AMBIENT_TINT_COEFFICIENTS, strict=True):
        label = "(" + ", ".join(f"{c:.4f}" for c in coefficients) + ")"
        if term is None:
            node = h.vector_math(tree, "ADD", tuple(coefficients), (0.0, 0.0, 0.0), label=label)
        elif total is None:
            node = h.vector_math(tree, "MULTIPLY", term, tuple(coefficients), label=f"× {label}")
        else:
            node = h.vector_math(tree, "MULTIPLY_ADD", term, tuple(coefficients), c=total,
                                 label=f"× {label} +")
        made.append(node)
        total = node.outputs[0]
    sums = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Balance, Ambient Balance, Warmth (logs)")
    h.link(tree, total, sums.inputs[0])
    made.append(sums)
    return sums


def _fitted(tree, log, limits, label, made):
    """exp(log) held in `limits`: the Clamp node (nodes to `made`)."""
    exp = h.math(tree, "EXPONENT", log, label=label)
    held = h.add_node(tree, "ShaderNodeClamp", label=f"{label} in the Fitted Range",
                      inputs={"Min": limits[0], "Max": limits[1]})
    h.link(tree, exp.outputs[0], held.inputs["Value"])
    made += [exp, held]
    return held


def _tint(tree, warmth_sum, weight, made):
    """exp(w axis) per channel, w the tint's polynomial held in its range and eased by `weight`
    (the sun on the face): the Combine Color node (nodes to `made`)."""
    warmth = h.add_node(tree, "ShaderNodeClamp", label="Warmth in the Fitted Range",
                        inputs={"Min": twin.TINT_RANGE[0], "Max": twin.TINT_RANGE[1]})
    h.link(tree, warmth_sum, warmth.inputs["Value"])
    eased = h.math(tree, "MULTIPLY", warmth.outputs["Result"], weight, label="Warmth or 0")
    combine = h.add_node(tree, "ShaderNodeCombineColor", label="Ambient Tint")
    made += [warmth, eased, combine]
    for channel, along in zip(combine.inputs[:3], twin.AMBIENT_TINT_AXIS, strict=True):
        exp = h.math(tree, "MULTIPLY", eased.outputs[0], along, label=f"× {along:g}")
        power = h.math(tree, "EXPONENT", exp.outputs[0])
        h.link(tree, power.outputs[0], channel)
        made += [exp, power]
    return combine


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    normal, normal_nodes = h.normal_or_geometry(tree, inputs["Normal"])
    geometry = h.add_node(tree, "ShaderNodeNewGeometry")
    view = geometry.outputs["Incoming"]
    light = h.vector_math(tree, "NORMALIZE", inputs["Sun Direction"], label="Sun")
    v, v_dot = _clamped_cosine(tree, view, normal, "N·V")
    l_, l_dot = _clamped_cosine(tree, light.outputs[0], normal, "N·L")
    # The azimuth between view and sun about the normal: their parts across the normal.
    across = []
    for vector, label, along in ((view, "V", v_dot), (light.outputs[0], "L", l_dot)):  # unclamped N·V, N·L
        back = h.vector_math(tree, "SCALE", normal, label=f"N (N·{label})")
        h.link(tree, along.outputs["Value"], back.inputs["Scale"])
        part = h.vector_math(tree, "SUBTRACT", vector, back.outputs[0], label=f"{label} Across")
        across.append((part, (back, part)))
    dot = h.vector_math(tree, "DOT_PRODUCT", across[0][0].outputs[0], across[1][0].outputs[0])
    lengths = [h.vector_math(tree, "LENGTH", part.outputs[0]) for part, _ in across]
    product = h.math(tree, "MULTIPLY", lengths[0].outputs["Value"], lengths[1].outputs["Value"])
    bounded = h.math(tree, "MAXIMUM", product.outputs[0], 1e-6)
    ratio = h.math(tree, "DIVIDE", dot.outputs["Value"], bounded.outputs[0])
    ahead = h.math(tree, "MULTIPLY", ratio.outputs[0], -1.0, label="cos Azimuth (1: Sun Ahead)")
    a = h.add_node(tree, "ShaderNodeClamp", label="−1..1", inputs={"Min": -1.0, "Max": 1.0})
    h.link(tree, ahead.outputs[0], a.inputs["Value"])
    # The azimuth as an angle over pi (0: sun ahead): the fits change fastest near 0, where its
    # cosine hardly moves.
    angle = h.math(tree, "ARCCOSINE", a.outputs["Result"], label="Azimuth")
    azimuth = h.math(tree, "MULTIPLY", angle.outputs[0], 1.0 / math.pi, label="Azimuth ÷ π (0: Sun Ahead)")
    angle_nodes = [*normal_nodes, geometry, light, v, v_dot, l_, l_dot, dot, *lengths, product, bounded,
                   ratio, ahead, a, angle, azimuth]
    for _, made in across:
        angle_nodes += made

    # exp(sum c √v^i √l^j p^k), held in the fitted range; each variable's powers made once.
    fit_nodes = []
    powers = []
    roots = [h.math(tree, "SQRT", cosine.outputs[0], label=f"√{name}")
             for cosine, name in ((v, "N·V"), (l_, "N·L"))]
    fit_nodes += roots
    for variable, highest in ((roots[0].outputs[0], twin.DEGREE), (roots[1].outputs[0], twin.DEGREE),
                              (azimuth.outputs[0], twin.AZIMUTH_POWERS)):
        made = [None, variable]
        for _ in range(2, highest + 1):
            node = h.math(tree, "MULTIPLY", made[-1], variable)
            fit_nodes.append(node)
            made.append(node.outputs[0])
        powers.append(made)
    monomials = _monomials(tree, powers, fit_nodes)
    sums = _polynomials(tree, monomials, fit_nodes)
    held = _fitted(tree, sums.outputs["X"], twin.BALANCE_RANGE, "Balance", fit_nodes)
    ambient = _fitted(tree, sums.outputs["Y"], twin.AMBIENT_RANGE, "Ambient Balance", fit_nodes)
    # No sun (a zero direction): 1.
    length = h.vector_math(tree, "LENGTH", inputs["Sun Direction"], label="|Sun|")
    sun = h.math(tree, "GREATER_THAN", length.outputs["Value"], 1e-6, label="A Sun")
    # Faces turned from the sun get no sun to correct: the fit eases to 1 as N·L falls to 0.
    facing = h.math(tree, "DIVIDE", l_dot.outputs["Value"], twin.MIN_COSINE, label="N·L ÷ Limit")
    reached = h.add_node(tree, "ShaderNodeClamp", label="Sun Reaches (0..1)", inputs={"Min": 0.0, "Max": 1.0})
    h.link(tree, facing.outputs[0], reached.inputs["Value"])
    weight = h.math(tree, "MULTIPLY", sun.outputs[0], reached.outputs["Result"], label="Sun on the Face")
    minus_one = h.math(tree, "SUBTRACT", held.outputs["Result"], 1.0)
    result = h.math(tree, "MULTIPLY_ADD", minus_one.outputs[0], weight.outputs[0], c=1.0,
                    label="Balance or 1")
    h.link(tree, result.outputs[0], group_out.inputs["Balance"])
    # The ambient balance too: faces turned from the sun see no bright sky round it.
    ambient_less_one = h.math(tree, "SUBTRACT", ambient.outputs["Result"], 1.0)
    ambient_or_one = h.math(tree, "MULTIPLY_ADD", ambient_less_one.outputs[0], weight.outputs[0], c=1.0,
                            label="Ambient Balance or 1")
    h.link(tree, ambient_or_one.outputs[0], group_out.inputs["Ambient Balance"])
    tint = _tint(tree, sums.outputs["Z"], weight.outputs[0], fit_nodes)
    h.link(tree, tint.outputs[0], group_out.inputs["Ambient Tint"])
    h.frame(tree, "View, Sun and Azimuth about the Normal", angle_nodes)
    h.frame(tree, "Fitted Ratios", fit_nodes)
    h.frame(tree, "Without a Sun, or Turned from It",
            (length, sun, facing, reached, weight, minus_one, result, ambient_less_one, ambient_or_one))
    h.arrange(tree)
