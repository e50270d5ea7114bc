"""The sun's glow in the compositor: a camera's (and an eye's) soft glare round the sun's disc,
where a render alone shows the sun as a small hard dot.

The compositor's Fog Glow on light above GLOW_THRESHOLD times the display white: the sun's disc
only. The bright sky round it stays below, and so do the sand's glints, which stay pinpoints.
The threshold follows the exposure by a simple-expression driver, as the god rays' display white
does, so a render farm without Sandscape renders the same.
"""

from ..node_groups import helper as h
from . import drivers

GLOW = "Sandscape Sun Glow"
THRESHOLD = "Sandscape Glow Threshold"
GLOW_THRESHOLD = 100.0  # display whites: far above the sky and the glints, far below the sun's disc
GLOW_SIZE = 0.6  # the Glare node's size: the glow's reach, as a share of the frame
THRESHOLD_EXPRESSION = f"{GLOW_THRESHOLD:g} * {drivers.WHITE_EXPRESSION}"


def add_glow(tree, image, strength, white=1.0, scene=None):
    """Add the glow after `image` (a socket); returns the glowing image's socket."""
    glare = h.add_node(tree, "CompositorNodeGlare", name=GLOW, label="Sun Glow",
                       inputs={"Type": "Fog Glow", "Quality": "Medium", "Size": GLOW_SIZE,
                               "Strength": float(strength)})
    threshold = h.add_node(tree, "ShaderNodeValue", name=THRESHOLD, label="Glow Threshold (driven)")
    threshold.outputs[0].default_value = GLOW_THRESHOLD * white
    if scene is not None:  # follows the exposure, whatever it becomes
        drivers.drive(threshold.outputs[0], "default_value", THRESHOLD_EXPRESSION,
                      [("exposure", "SCENE", scene, "view_settings.exposure")])
    h.link(tree, threshold.outputs[0], glare.inputs["Threshold"])
    h.link(tree, image, glare.inputs["Image"])
    return glare.outputs["Image"]
