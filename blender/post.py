"""The scene's compositor tree: Render Layers -> gated blur of the scattered light -> god rays.

Not a shared group but the tree on scene.compositing_node_group, rebuilt from the settings
on every run (an effect switched off is absent, not bypassed). Its parts are the versioned
groups Sandscape Gated Blur and Sandscape God Rays N.
"""

from ..node_groups import gated_blur, god_rays
from ..node_groups import helper as h

TREE_KEY = "sandscape_compositor"
SUN_COLOR = (1.0, 0.93, 0.8, 1.0)


def rays_node(tree):
    for node in tree.nodes:
        group = getattr(node, "node_tree", None)
        if group is not None and str(group.get(h.GROUP_KEY, "")).startswith("Sandscape God Rays"):
            return node
    return None


def build(tree, settings):
    """(Re)build the tree for the settings: use_blur, blur_threshold, use_god_rays, samples, ..."""
    tree.nodes.clear()
    if not tree.interface.items_tree:
        h.add_output(tree, "Image", "NodeSocketColor", "The composited frame")
    tree.description = "Sandscape post effects: gated blur of the scattered light, god rays"
    layers = h.add_node(tree, "CompositorNodeRLayers", (-1200, 0))
    output = h.add_node(tree, "NodeGroupOutput", (900, 0))
    image = layers.outputs["Image"]
    if settings.use_blur:
        passes = h.add_node(tree, "ShaderNodeVectorMath", (-1000, -300), "Volume Passes", operation="ADD")
        h.link(tree, layers.outputs["Volume Direct"], passes.inputs[0])
        h.link(tree, layers.outputs["Volume Indirect"], passes.inputs[1])
        # The passes can exceed the combined image in a pixel (751 negative pixels in a demo
        # frame; indirect sample clamping is a likely cause): never take out more than it holds.
        volume = h.add_node(tree, "ShaderNodeVectorMath", (-900, -300), "Scattered Light",
                            operation="MINIMUM")
        h.link(tree, passes.outputs[0], volume.inputs[0])
        h.link(tree, image, volume.inputs[1])
        blur = h.add_node(tree, "CompositorNodeGroup", (-650, -300), "Gated Blur",
                          node_tree=h.ensure_group(gated_blur), inputs={"Threshold": settings.blur_threshold})
        h.link(tree, volume.outputs[0], blur.inputs["Image"])
        # Geometry stays sharp: only the scattered light is swapped for its blurred self.
        without = h.add_node(tree, "ShaderNodeVectorMath", (-650, 0), "Image − Scattered",
                             operation="SUBTRACT")
        h.link(tree, image, without.inputs[0])
        h.link(tree, volume.outputs[0], without.inputs[1])
        back = h.add_node(tree, "ShaderNodeVectorMath", (-400, 0), "+ Blurred Scattered", operation="ADD")
        h.link(tree, without.outputs[0], back.inputs[0])
        h.link(tree, blur.outputs["Image"], back.inputs[1])
        image = back.outputs[0]
    if settings.use_god_rays:
        rays = h.add_node(tree, "CompositorNodeGroup", (300, -400), "God Rays",
                          node_tree=h.ensure_group(god_rays.Builder(settings.samples)),
                          inputs={"Density": settings.ray_density, "Weight": settings.ray_weight,
                                  "Decay": settings.ray_decay, "Exposure": settings.ray_exposure})
        h.link(tree, _occlusion(tree, layers, rays, settings.disc_radius), rays.inputs["Occlusion"])
        total = h.add_node(tree, "ShaderNodeVectorMath", (600, 0), "+ God Rays", operation="ADD")
        h.link(tree, image, total.inputs[0])
        h.link(tree, rays.outputs["Rays"], total.inputs[1])
        image = total.outputs[0]
    h.link(tree, image, output.inputs[0])
    return tree


def _occlusion(tree, layers, rays, radius):
    """Sun colour inside a soft disc of `radius` (frame heights) around the sun, where sky is seen."""
    coordinates = h.add_node(tree, "CompositorNodeImageCoordinates", (-900, -700))
    h.link(tree, layers.outputs["Image"], coordinates.inputs["Image"])
    # The frame's size in pixels as a float vector: (1, 1) relative to each dimension. Not Image
    # Info's Dimensions, an integer vector in 5.2 whose link Blender 5.0 drops when it opens the file.
    info = h.add_node(tree, "CompositorNodeRelativeToPixel", (-900, -900), "Frame Size",
                      data_type="VECTOR", reference_dimension="PER_DIMENSION")
    info.inputs["Vector Value"].default_value = (1.0, 1.0)
    h.link(tree, layers.outputs["Image"], info.inputs["Image"])
    size = h.add_node(tree, "ShaderNodeSeparateXYZ", (-700, -900))
    h.link(tree, info.outputs["Vector Value"], size.inputs[0])
    aspect = h.math(tree, "DIVIDE", size.outputs["X"], size.outputs["Y"], (-500, -900), "Aspect")
    offset = h.add_node(tree, "ShaderNodeVectorMath", (-700, -700), operation="SUBTRACT")
    h.link(tree, coordinates.outputs["Normalized"], offset.inputs[0])
    sun = h.add_node(tree, "ShaderNodeCombineXYZ", (-900, -1100), "Sun (keyed)")
    h.link(tree, sun.outputs[0], offset.inputs[1])
    split = h.add_node(tree, "ShaderNodeSeparateXYZ", (-500, -700))
    h.link(tree, offset.outputs[0], split.inputs[0])
    wide = h.math(tree, "MULTIPLY", split.outputs["X"], aspect.outputs[0], (-300, -700), "dx × aspect")
    square = h.add_node(tree, "ShaderNodeCombineXYZ", (-150, -700))
    h.link(tree, wide.outputs[0], square.inputs["X"])
    h.link(tree, split.outputs["Y"], square.inputs["Y"])
    distance = h.add_node(tree, "ShaderNodeVectorMath", (0, -700), operation="LENGTH")
    h.link(tree, square.outputs[0], distance.inputs[0])
    disc = h.add_node(tree, "ShaderNodeMapRange", (150, -700), "Sun Disc", interpolation_type="SMOOTHSTEP",
                      inputs={"From Min": radius, "From Max": radius * 0.5, "To Min": 0.0, "To Max": 1.0})
    h.link(tree, distance.outputs["Value"], disc.inputs["Value"])
    sky = h.add_node(tree, "CompositorNodeRGBToBW", (-700, -500))
    h.link(tree, layers.outputs["Environment"], sky.inputs[0])
    seen = h.math(tree, "GREATER_THAN", sky.outputs[0], 0.0, (-500, -500), "Sky Seen")
    both = h.math(tree, "MULTIPLY", seen.outputs[0], disc.outputs["Result"], (300, -600), "Disc × Sky")
    tint = h.add_node(tree, "ShaderNodeVectorMath", (450, -600), "Sun Colour", operation="SCALE",
                      inputs={0: SUN_COLOR[:3]})
    h.link(tree, both.outputs[0], tint.inputs["Scale"])
    # The keyed sun position drives the rays as well: one source of truth per frame.
    h.link(tree, sun.outputs[0], rays.inputs["Sun"])
    return tint.outputs[0]


def sun_key_node(tree):
    return next(n for n in tree.nodes if n.label == "Sun (keyed)")
