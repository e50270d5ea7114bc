"""Sandscape God Rays: screen-space light scattering after GPU Gems 3, chapter 13 (seed 002).

For every pixel, N samples of the occlusion image on the line towards the sun:
    exposure * intensity * sum_{i=1..N} weight * decay^(i-1) * occlusion(L + (1 - i density / N)(uv - L))
Bilinear Map UV samples read 0 outside the frame. The sample count shapes the tree, so each
count is its own group ("Sandscape God Rays 32"). Twin: core.post.god_rays.
"""

from . import helper as h

VERSION = 2
TREE_TYPE = "CompositorNodeTree"
DEFAULT_SAMPLES = 32


def description(samples):
    return (f"God rays, {samples} samples: radial accumulation of Occlusion towards the sun, each sample "
            "weighted by Weight × Decay^(i−1), times Exposure and Intensity")


class Builder:
    """A builder for a given sample count, shaped like a builder module for ensure_group."""

    VERSION = VERSION
    TREE_TYPE = TREE_TYPE

    def __init__(self, samples):
        self.samples = int(samples)
        self.NAME = f"Sandscape God Rays {self.samples}"
        self.DESCRIPTION = description(self.samples)

    def build(self, tree):
        build(tree, self.samples)


def build(tree, samples):
    tree.description = description(samples)
    h.add_input(tree, "Occlusion", "NodeSocketColor", "Bright where the sun's light is seen (sky, sun "
                "disc), black where geometry hides it", (0.0, 0.0, 0.0, 1.0))
    h.add_input(tree, "Sun", "NodeSocketVector", "Sun position on screen, 0..1 in x and y",
                (0.5, 0.5, 0.0))
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
    coordinates = h.add_node(tree, "CompositorNodeImageCoordinates", (-1200, 0))
    h.link(tree, inputs["Occlusion"], coordinates.inputs["Image"])
    towards = h.add_node(tree, "ShaderNodeVectorMath", (-1000, 0), "uv − Sun", operation="SUBTRACT")
    h.link(tree, coordinates.outputs["Normalized"], towards.inputs[0])
    h.link(tree, inputs["Sun"], towards.inputs[1])
    split = h.add_node(tree, "ShaderNodeSeparateXYZ", (-1200, -300))
    h.link(tree, inputs["Sun"], split.inputs[0])
    # Map UV reads z as the sample's alpha: the anchor carries z = 1.
    anchor = h.add_node(tree, "ShaderNodeCombineXYZ", (-1000, -300), "Sun, z = 1", inputs={"Z": 1.0})
    h.link(tree, split.outputs["X"], anchor.inputs["X"])
    h.link(tree, split.outputs["Y"], anchor.inputs["Y"])
    total, per_sample, sums = None, [], []
    for i in range(1, samples + 1):
        y = -200 * i
        scale = h.add_node(tree, "ShaderNodeMath", (-800, y), f"1 − {i}·D/N", operation="MULTIPLY_ADD",
                           inputs={1: -i / samples, 2: 1.0})
        h.link(tree, inputs["Density"], scale.inputs[0])
        scaled = h.add_node(tree, "ShaderNodeVectorMath", (-600, y), operation="SCALE")
        h.link(tree, towards.outputs[0], scaled.inputs[0])
        h.link(tree, scale.outputs[0], scaled.inputs["Scale"])
        uv = h.add_node(tree, "ShaderNodeVectorMath", (-400, y), operation="ADD")
        h.link(tree, scaled.outputs[0], uv.inputs[0])
        h.link(tree, anchor.outputs[0], uv.inputs[1])
        sample = h.add_node(tree, "CompositorNodeMapUV", (-200, y), inputs={
            "Interpolation": "Bilinear", "Extension X": "Clip", "Extension Y": "Clip"})
        h.link(tree, inputs["Occlusion"], sample.inputs["Image"])
        h.link(tree, uv.outputs[0], sample.inputs["UV"])
        falloff = h.math(tree, "POWER", inputs["Decay"], float(i - 1), (0, y), f"Decay^{i - 1}")
        weight = h.math(tree, "MULTIPLY", falloff.outputs[0], inputs["Weight"], (150, y))
        weighted = h.add_node(tree, "ShaderNodeVectorMath", (300, y), operation="SCALE")
        h.link(tree, sample.outputs[0], weighted.inputs[0])
        h.link(tree, weight.outputs[0], weighted.inputs["Scale"])
        per_sample += [scale, scaled, uv, sample, falloff, weight, weighted]
        if total is None:
            total = weighted
        else:
            added = h.add_node(tree, "ShaderNodeVectorMath", (450, y), operation="ADD")
            h.link(tree, total.outputs[0], added.inputs[0])
            h.link(tree, weighted.outputs[0], added.inputs[1])
            total = added
            sums.append(added)
    gain = h.math(tree, "MULTIPLY", inputs["Exposure"], inputs["Intensity"], (600, 0), "Exposure × Intensity")
    rays = h.add_node(tree, "ShaderNodeVectorMath", (800, 0), operation="SCALE")
    h.link(tree, total.outputs[0], rays.inputs[0])
    h.link(tree, gain.outputs[0], rays.inputs["Scale"])
    h.link(tree, rays.outputs[0], group_out.inputs["Rays"])
    h.frame(tree, "Towards the Sun", (coordinates, towards, split, anchor))
    h.frame(tree, "Samples along the Ray", per_sample)
    h.frame(tree, "Sum", sums)
    h.frame(tree, "Exposure × Intensity", (gain, rays))
    h.arrange(tree)
