"""Sandscape Physical Sand: sand as a physical surface, for Cycles' path tracer.

A rough diffuse base (Principled BSDF with its diffuse roughness, the Oren-Nayar-like response
of a grainy surface), sand's Fresnel (quartz, IOR about 1.54), a sheen rim at grazing angles, and
the normal nudged per grain (Sandscape Sand Normal). Glints come on top, as mirror facets
(Sandscape Lit Glints) or as emission. Twin: core.sand.sand_normal for the grains; the rest is
Blender's own Principled BSDF.
"""

from ..core import sand
from . import helper as h
from . import sand_normal

NAME = "Sandscape Physical Sand"
VERSION = 1
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Physical sand: rough diffuse, quartz Fresnel (IOR 1.54), a sheen rim and grainy normals, "
               "as a Principled BSDF")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Color", "NodeSocketColor", "Albedo of the sand", sand.SAND_COLOR)
    h.add_input(tree, "Roughness", "NodeSocketFloat", "Roughness of the grains' sheen of reflection",
                0.85, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Diffuse Roughness", "NodeSocketFloat", "0 is Lambert; towards 1 the flatter, "
                "back-scattering look of rough powder", 0.8, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "IOR", "NodeSocketFloat", "Index of refraction of the grains (quartz: 1.54)",
                sand.QUARTZ_IOR, 1.0, 3.0)
    h.add_input(tree, "Sheen", "NodeSocketFloat", "Weight of the dusty rim seen at grazing angles", 0.3,
                0.0, 1.0, "FACTOR")
    sand_normal.add_grain_inputs(tree)
    h.add_output(tree, "BSDF", "NodeSocketShader", "The sand")
    h.add_output(tree, "Normal", "NodeSocketVector", "The grainy normal the BSDF uses")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    grains = sand_normal.grain_node(tree, inputs)
    bsdf = h.add_node(tree, "ShaderNodeBsdfPrincipled", label="Sand",
                      inputs={"Sheen Roughness": 0.5, "Sheen Tint": (1.0, 0.95, 0.85, 1.0)})
    for name in ("Color", "Roughness", "Diffuse Roughness", "IOR", "Sheen"):
        h.link(tree, inputs[name], bsdf.inputs["Base Color" if name == "Color" else
                                              "Sheen Weight" if name == "Sheen" else name])
    h.link(tree, grains.outputs["Normal"], bsdf.inputs["Normal"])
    h.link(tree, bsdf.outputs["BSDF"], group_out.inputs["BSDF"])
    h.link(tree, grains.outputs["Normal"], group_out.inputs["Normal"])
    h.frame(tree, "Grains", (grains,))
    h.frame(tree, "Rough Diffuse, Quartz Fresnel, Sheen", (bsdf,))
    h.arrange(tree)
