"""Sandscape God Rays: screen-space light scattering after GPU Gems 3, chapter 13 (seed 002), in
a fixed number of passes whatever the sample count.

The seed sums N samples of the occlusion on the line towards the sun, at scales
1 - i·Density/N, each weighted Weight × Decay^(i−1). This group sums M = 2^PASSES taps instead,
at the scales r^j (j = 1..M, r^M = 1 − Density: the seed's span), so that pass k doubles the taps
by adding the image so far, sampled at the scale r^(2^k), times c^(2^k). The tap weights c^(j−1)
with c = r·Decay^(N/M) carry the seed's decay over its span and, through the factor r, the closer
spacing of geometric taps near the sun; their sum is scaled to the seed's total weight,
Weight·(1 − Decay^N)/(1 − Decay). Bilinear Map UV samples read 0 outside the frame. Twin:
core.post.god_rays; the seed's own sum is core.post.god_rays_seed.
"""

from ..core import post
from . import helper as h

NAME = "Sandscape God Rays"
VERSION = 3
TREE_TYPE = "CompositorNodeTree"
DESCRIPTION = (f"God rays: the seed's Samples along the line to the sun, as {2 ** post.RAY_PASSES} "
               f"geometric taps in {post.RAY_PASSES} passes, weighted Weight × Decay^(i−1) and scaled by "
               "Exposure and Intensity")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Occlusion", "NodeSocketColor", "Bright where the sun's light is seen (sky, sun "
                "disc), black where geometry hides it", (0.0, 0.0, 0.0, 1.0))
    h.add_input(tree, "Sun", "NodeSocketVector", "Sun position on screen, 0..1 in x and y",
                (0.5, 0.5, 0.0))
    h.add_input(tree, "Samples", "NodeSocketFloat", "The seed's sample count: with Decay, how fast the "
                "rays fall off (the taps are always the same)", 32.0, 1.0, None)
    h.add_input(tree, "Density", "NodeSocketFloat", "Fraction of the way to the sun the samples span",
                0.9, 0.0, 1.0)
    h.add_input(tree, "Weight", "NodeSocketFloat", "Weight of one sample", 0.05, 0.0, None)
    h.add_input(tree, "Decay", "NodeSocketFloat", "Falloff per sample away from the pixel, at most 1",
                0.97, 0.0, 1.0)
    h.add_input(tree, "Exposure", "NodeSocketFloat", "Overall scale of the rays", 1.0, 0.0, None)
    h.add_input(tree, "Intensity", "NodeSocketFloat", "Fade: 1 with the sun in frame, 0 behind the camera",
                1.0, 0.0, None)
    h.add_output(tree, "Rays", "NodeSocketColor", "The god rays, to add over the image")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    taps = 2 ** post.RAY_PASSES
    stages = _Stages(tree)
    coordinates = h.add_node(tree, "CompositorNodeImageCoordinates")
    h.link(tree, inputs["Occlusion"], coordinates.inputs["Image"])
    towards = h.vector_math(tree, "SUBTRACT", coordinates.outputs["Normalized"], inputs["Sun"],
                            label="uv − Sun")
    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, inputs["Sun"], split.inputs[0])
    # Map UV reads z as the sample's alpha: the anchor carries z = 1.
    anchor = h.add_node(tree, "ShaderNodeCombineXYZ", label="Sun, z = 1", inputs={"Z": 1.0})
    h.link(tree, split.outputs["X"], anchor.inputs["X"])
    h.link(tree, split.outputs["Y"], anchor.inputs["Y"])
    stages.close("Towards the Sun")
    # r = (1 − Density)^(1/M), at most MAX_DENSITY of the way; c = r · Decay^(N/M).
    density = h.math(tree, "MINIMUM", inputs["Density"], post.MAX_DENSITY, label="Density ≤ max")
    rest = h.math(tree, "SUBTRACT", 1.0, density.outputs[0], label="1 − Density")
    ratio = h.math(tree, "POWER", rest.outputs[0], 1.0 / taps, label="r = (1 − D)^(1/M)").outputs[0]
    per_tap = h.math(tree, "DIVIDE", inputs["Samples"], float(taps), label="N / M")
    fall = h.math(tree, "POWER", inputs["Decay"], per_tap.outputs[0], label="Decay^(N/M)")
    decay = h.math(tree, "MULTIPLY", ratio, fall.outputs[0], label="c = r · Decay^(N/M)").outputs[0]
    stages.close("Tap Spacing and Decay")

    def sample(image, scale, label):
        scaled = h.vector_math(tree, "SCALE", towards.outputs[0], label=f"(uv − Sun) × {label}")
        h.link(tree, scale, scaled.inputs["Scale"])
        uv = h.vector_math(tree, "ADD", scaled.outputs[0], anchor.outputs[0], label="+ Sun")
        node = h.add_node(tree, "CompositorNodeMapUV", label=f"Sample at {label}", inputs={
            "Interpolation": "Bilinear", "Extension X": "Clip", "Extension Y": "Clip"})
        h.link(tree, image, node.inputs["Image"])
        h.link(tree, uv.outputs[0], node.inputs["UV"])
        return node.outputs[0]

    image = sample(inputs["Occlusion"], ratio, "r")  # tap 1
    norm = None  # the sum of the weights c^(j−1), j = 1..M: the product of (1 + c^(2^k))
    for k in range(post.RAY_PASSES):
        step = 2 ** k
        scale = h.math(tree, "POWER", ratio, float(step), label=f"r^{step}").outputs[0]
        weight = h.math(tree, "POWER", decay, float(step), label=f"c^{step}").outputs[0]
        weighted = h.vector_math(tree, "SCALE", sample(image, scale, f"r^{step}"), label=f"× c^{step}")
        h.link(tree, weight, weighted.inputs["Scale"])
        image = h.vector_math(tree, "ADD", image, weighted.outputs[0], label=f"Pass {k + 1}").outputs[0]
        factor = h.math(tree, "ADD", weight, 1.0, label=f"1 + c^{step}").outputs[0]
        norm = factor if norm is None else h.math(tree, "MULTIPLY", norm, factor, label="Σ c^j").outputs[0]
    stages.close("Passes: Each Doubles the Taps")
    # The seed's total weight: Weight × (1 − Decay^N) / (1 − Decay), Weight × N at Decay 1.
    flat = h.math(tree, "GREATER_THAN", inputs["Decay"], 1.0 - 1e-6, label="Decay = 1")
    power = h.math(tree, "POWER", inputs["Decay"], inputs["Samples"], label="Decay^N")
    numerator = h.math(tree, "SUBTRACT", 1.0, power.outputs[0], label="1 − Decay^N")
    gap = h.math(tree, "SUBTRACT", 1.0, inputs["Decay"], label="1 − Decay")
    safe_gap = h.math(tree, "MAXIMUM", gap.outputs[0], 1e-9, label="> 0")
    geometric = h.math(tree, "DIVIDE", numerator.outputs[0], safe_gap.outputs[0], label="Σ Decay^i")
    series = h.add_node(tree, "ShaderNodeMix", label="Σ Decay^i (N at Decay 1)", data_type="FLOAT")
    h.link(tree, flat.outputs[0], series.inputs["Factor"])
    h.link(tree, geometric.outputs[0], h.socket(series.inputs, "A"))
    h.link(tree, inputs["Samples"], h.socket(series.inputs, "B"))
    total = h.math(tree, "MULTIPLY", inputs["Weight"], series.outputs["Result"], label="Seed's Total Weight")
    first = h.math(tree, "DIVIDE", total.outputs[0], norm, label="First Tap's Weight")
    stages.close("The Seed's Total Weight")
    gain = h.math(tree, "MULTIPLY", inputs["Exposure"], inputs["Intensity"], label="Exposure × Intensity")
    scale = h.math(tree, "MULTIPLY", first.outputs[0], gain.outputs[0], label="× Exposure × Intensity")
    rays = h.vector_math(tree, "SCALE", image, label="Rays")
    h.link(tree, scale.outputs[0], rays.inputs["Scale"])
    h.link(tree, rays.outputs[0], group_out.inputs["Rays"])
    stages.close("Exposure × Intensity")
    h.arrange(tree)


class _Stages:
    """Frames the nodes made since the last close() (the Group Input and Output stay out)."""

    def __init__(self, tree):
        self.tree = tree
        self.seen = {node.name for node in tree.nodes}

    def close(self, label):
        made = [node for node in self.tree.nodes if node.name not in self.seen]
        box = h.frame(self.tree, label, made)
        self.seen |= {node.name for node in made} | ({box.name} if box else set())
