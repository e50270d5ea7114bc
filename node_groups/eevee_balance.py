"""Sandscape EEVEE Balance: how much brighter Cycles renders Sandscape Physical Sand than EEVEE
here, from the view, the sun and the normal: EEVEE lacks Cycles' rough diffuse and microfiber
sheen, so its sand is dim under a low sun and bright under a high one. The sand material's
EEVEE output scales its surface by this (Cycles' output does not use it).
Twin: core.eevee_balance.balance (a fit to both engines' renders).
"""

from ..core import eevee_balance as twin
from . import helper as h

NAME = "Sandscape EEVEE Balance"
VERSION = 6
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Cycles' brightness of Sandscape sand over EEVEE's at this view, sun and normal: the "
               "factor the sand's EEVEE output applies")

INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    "Sun Direction": ("NodeSocketVector", "Towards the sun, in world space (driven by the sun lamp); "
                      "zero: no sun, a balance of 1", (0.0, 0.0, 0.0), None, None, None),
    "Normal": ("NodeSocketVector", "The surface's normal (unlinked: the shading normal)",
               (0.0, 0.0, 0.0), None, None, h.SURFACE_NORMAL),
}
OUTPUTS = {"Balance": ("NodeSocketFloat", "Cycles' brightness over EEVEE's (1 without a sun)")}


def _clamped_cosine(tree, a, b, label):
    dot = h.vector_math(tree, "DOT_PRODUCT", a, b, label=label)
    held = h.math(tree, "MAXIMUM", dot.outputs["Value"], twin.MIN_COSINE, label=f"{label} ≥ Limit")
    return held, dot


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
    angle_nodes = [*normal_nodes, geometry, light, v, v_dot, l_, l_dot, dot, *lengths, product, bounded,
                   ratio, ahead, a]
    for _, made in across:
        angle_nodes += made

    # exp(sum c v^i l^j a^k), held in the fitted range; each variable's powers made once.
    fit_nodes = []
    powers = []
    for variable in (v.outputs[0], l_.outputs[0], a.outputs[0]):
        made = [None, variable]
        for _ in range(2, twin.DEGREE + 1):
            node = h.math(tree, "MULTIPLY", made[-1], variable)
            fit_nodes.append(node)
            made.append(node.outputs[0])
        powers.append(made)
    total = None
    for exponents, coefficient in zip(twin.TERMS, twin.COEFFICIENTS, strict=True):
        factors = [powers[axis][power] for axis, power in enumerate(exponents) if power]
        term = factors[0] if factors else None
        for factor in factors[1:]:
            node = h.math(tree, "MULTIPLY", term, factor)
            fit_nodes.append(node)
            term = node.outputs[0]
        if term is None:
            node = h.math(tree, "ADD", coefficient, 0.0, label=f"{coefficient:.4f}")
        elif total is None:
            node = h.math(tree, "MULTIPLY", term, coefficient, label=f"× {coefficient:.4f}")
        else:
            node = h.math(tree, "MULTIPLY_ADD", term, coefficient, c=total, label=f"× {coefficient:.4f} +")
        fit_nodes.append(node)
        total = node.outputs[0]
    exp = h.math(tree, "EXPONENT", total, label="Balance")
    low, high = twin.BALANCE_RANGE
    held = h.add_node(tree, "ShaderNodeClamp", label="In the Fitted Range", inputs={"Min": low, "Max": high})
    h.link(tree, exp.outputs[0], held.inputs["Value"])
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
    h.frame(tree, "View, Sun and Azimuth about the Normal", angle_nodes)
    h.frame(tree, "Fitted Ratio", (*fit_nodes, exp, held))
    h.frame(tree, "Without a Sun, or Turned from It",
            (length, sun, facing, reached, weight, minus_one, result))
    h.arrange(tree)
