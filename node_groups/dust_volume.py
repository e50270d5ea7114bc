"""Sandscape Dust Volume: Rayleigh scattering with per-channel coefficients.

Seed 000, section 4.3: scattering by small particles goes as 1/lambda^4 with the phase
3/(16 pi) (1 + cos^2 theta). Cycles scatters sigma_s = Color x Density; the volume has no
absorption, so the extinction equals the scattering and a ray through thickness d keeps
exp(-sigma_s d) per channel. Twin: core.atmosphere (rayleigh_coefficients, slab_transmittance).
"""

from . import helper as h

NAME = "Sandscape Dust Volume"
VERSION = 2
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = (
    "Rayleigh-scattering air and dust: Color x Density is the scattering "
    "coefficient per channel, in 1/m")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Color", "NodeSocketColor", "Per-channel scattering relative to the strongest "
                "channel: (lambda_max_scatter / lambda)^4, so 0..1", (1.0, 1.0, 1.0, 1.0))
    h.add_input(tree, "Density", "NodeSocketFloat", "Scattering coefficient of the strongest channel, 1/m",
                0.02, 0.0, None)
    h.add_output(tree, "Volume", "NodeSocketShader", "The scattering volume")
    group_in, group_out = h.group_io(tree)
    scatter = h.add_node(tree, "ShaderNodeVolumeScatter", (0, 0), "Rayleigh", phase="RAYLEIGH")
    h.link(tree, group_in.outputs["Color"], scatter.inputs["Color"])
    h.link(tree, group_in.outputs["Density"], scatter.inputs["Density"])
    h.link(tree, scatter.outputs[0], group_out.inputs["Volume"])
    h.arrange(tree)
