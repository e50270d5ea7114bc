"""The cloud grid's sunlight for EEVEE: the light let through towards the sun, baked per voxel.

EEVEE's own volume shadows march towards a sun only until the view's frustum ends, so a cloud
layer lit from behind the camera, or from the side, was hardly shaded (README, *The clouds shade
themselves in EEVEE*). Here geometry nodes march each voxel's optical depth towards the scene's
sun lamp through the density grid once per evaluation (core.cloud_shadows.voxel_transmittance is
the twin) and store it as a grid, T. The sun's direction is driven by the lamp, so the light
follows a turned sun without Python. Built, as the clouds' shadow mesh is, only for a scene that
renders with EEVEE when Add Clouds runs: a Cycles render would evaluate the march for nothing.

The material's EEVEE output then splits the extinction: a share T scatters as in Cycles (EEVEE
lights it with the sun and the world), the rest absorbs and, in place of the world's light it
would have scattered, emits seed 001's ambient term from EEVEE's lighting world's two
hemispheres (addon/sky_eevee.py): the lit ground's light below at the cloud's base, the sky's
above at its top. That is single scattering with the sun's light let through exactly (EEVEE
clamps a volume's emission at zero, so the sun's light cannot be taken away from a scatterer).
With EEVEE's Volume Shadows on (the artist's), a driver sets T to 1: EEVEE shades the clouds
itself, as before, not twice.

EEVEE holds one order of scattering, and over a dark ground its clouds near the horizon hardly
stood out from the sky (the sand's warm light from below had stood in for the rest). The higher
orders are emitted as octaves of the baked T (core.cloud_shadows.many_scatterings; Wrenninge
2015), isotropic: the light deep in a cloud and on its faces turned from the sun.
"""

import math

from ..core import cloud_shadows as shadow_twin
from ..node_groups import helper as h
from . import drivers, sky_eevee, sky_eevee_ground
from . import ownership as own

GRID = "sun_transmittance"
SUN_DIRECTION = "Sandscape Cloud Sun Direction"
SHADOWS_SWITCH = "Sandscape Cloud EEVEE Shadows"
OUTPUT = "Sandscape EEVEE Output"
MANY_SCATTERINGS = "Sandscape EEVEE Many Scatterings"


def march(tree, volume, sun, thickness, step, density, wet):
    """Geometry nodes: the layer's volume socket -> the volume with GRID, exp(-optical depth)
    from each voxel's centre towards the sun through `thickness` (midpoint steps of the density
    clamp(cloudiness, 0, wet) x density, at most MAX_STEPS as for the shadow map); the density
    grid stored again after it, as EEVEE draws nothing of a volume whose last grid came from Field
    to Grid."""
    to_sun = sun.matrix_world.to_3x3().col[2]
    steps = shadow_twin.steps_for(thickness, (to_sun[0], to_sun[1], max(to_sun[2], shadow_twin.LOWEST_SINE)),
                                  step)
    direction, unit, sine, _ = sky_eevee.sun_nodes(tree, SUN_DIRECTION, lowest=shadow_twin.LOWEST_SINE,
                                                   with_light=False)
    drivers.follow_lamp_axis(direction.inputs[:3], sun)
    across = h.math(tree, "DIVIDE", thickness / steps, sine.outputs[0], label="Step Along the Ray")
    grid = h.add_node(tree, "GeometryNodeGetNamedGrid", inputs={"Name": "density"}, label="Cloudiness")
    h.link(tree, volume, grid.inputs["Volume"])
    position = h.position(tree)
    total = None
    for k in range(steps):
        reach = h.math(tree, "MULTIPLY", across.outputs[0], k + 0.5)
        offset = h.vector_math(tree, "SCALE", unit, Scale=0.0)
        h.link(tree, reach.outputs[0], offset.inputs["Scale"])
        point = h.vector_math(tree, "ADD", position.outputs["Position"], offset.outputs[0])
        sample = h.add_node(tree, "GeometryNodeSampleGrid", label=f"Step {k + 1}")
        h.link(tree, grid.outputs["Grid"], sample.inputs["Grid"])
        h.link(tree, point.outputs[0], sample.inputs["Position"])
        cloud = h.add_node(tree, "ShaderNodeClamp", inputs={"Min": 0.0, "Max": float(wet)})
        h.link(tree, sample.outputs[0], cloud.inputs["Value"])
        total = cloud.outputs[0] if total is None else h.math(tree, "ADD", total, cloud.outputs[0]).outputs[0]
    depth = h.math(tree, "MULTIPLY", total, across.outputs[0], label="Optical Depth ÷ Density")
    light = h.math(tree, "EXPONENT", h.math(tree, "MULTIPLY", depth.outputs[0], -float(density)).outputs[0])
    baked = h.add_node(tree, "GeometryNodeFieldToGrid", label="Per Voxel")
    baked.grid_items.new("FLOAT", "Light")
    h.link(tree, grid.outputs["Grid"], baked.inputs["Topology"])
    h.link(tree, light.outputs[0], baked.inputs["Light"])
    store = h.add_node(tree, "GeometryNodeStoreNamedGrid", inputs={"Name": GRID},
                       label="Sun's Light Let Through")
    h.link(tree, volume, store.inputs["Volume"])
    h.link(tree, baked.outputs["Light"], store.inputs["Grid"])
    again = h.add_node(tree, "GeometryNodeGetNamedGrid", inputs={"Name": "density"})
    h.link(tree, store.outputs[0], again.inputs["Volume"])
    last = h.add_node(tree, "GeometryNodeStoreNamedGrid", inputs={"Name": "density"}, label="Density Last")
    h.link(tree, again.outputs["Volume"], last.inputs["Volume"])
    h.link(tree, again.outputs["Grid"], last.inputs["Grid"])
    return last.outputs[0]


def baked(layer):
    """Whether the layer's grid carries the sun's light (a grid built with a sun lamp)."""
    modifier = next((m for m in layer.modifiers if m.type == "NODES"), None)
    tree = modifier.node_group if modifier is not None else None
    return tree is not None and SUN_DIRECTION in tree.nodes


def _ground_colour(tree, scene):
    """Colour socket: the ground's colour as the world's light from below takes it (the same
    material followed: sky_eevee_ground.py), else the sand's."""
    node = h.add_node(tree, "ShaderNodeCombineColor", name=sky_eevee_ground.NODE,
                      label="Ground Colour (driven)")
    world = own.scene_world(scene)
    sky_eevee_ground.match(node, world.node_tree if world is not None else None)
    return node.outputs[0]


def _ambient(tree, sun, ground, base, thickness):
    """Colour socket: the light a cloud's inside gets from EEVEE's lighting world (two
    hemispheres, from the lamp (driven) and the sky model's table): seed 001's ambient term, the
    cloud's base colour to its top colour by the height in the layer. At the base the lit sand's
    hemisphere below (the sky hidden by the cloud above), at the top the sky's above; each half
    the sphere's mean radiance, E / (2 pi)."""
    direction, _, height, light = sky_eevee.sun_nodes(tree, SUN_DIRECTION)
    drivers.follow_lamp_axis(direction.inputs[:3], sun)
    drivers.follow_lamp_light(light.inputs[:3], sun)
    sky = sky_eevee.sky_irradiance(tree, height.outputs[0])
    level = h.vector_math(tree, "MULTIPLY_ADD", light.outputs[0], (0.0, 0.0, 0.0), c=sky,
                          label="Light on Level Sand")
    mean = sky_eevee_ground.sun_let_through_node(tree)  # the clouds' shadows on the ground, on the whole
    shaded = h.math(tree, "MULTIPLY", height.outputs[0], mean.outputs[0], label="Sine × Sun Let Through")
    h.link(tree, shaded.outputs[0], level.inputs[1])
    below = h.vector_math(tree, "MULTIPLY", level.outputs[0], ground, label="Lit Sand × π")
    where = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, h.position(tree).outputs["Position"], where.inputs[0])
    fraction = h.add_node(tree, "ShaderNodeMapRange", label="Height in the Layer",
                          inputs={"From Min": float(base), "From Max": float(base + thickness)})
    h.link(tree, where.outputs["Z"], fraction.inputs["Value"])
    mix = h.add_node(tree, "ShaderNodeMix", data_type="VECTOR", label="Base to Top")
    h.link(tree, fraction.outputs["Result"], mix.inputs["Factor"])
    h.link(tree, below.outputs[0], mix.inputs["A"])
    h.link(tree, sky, mix.inputs["B"])
    ambient = h.vector_math(tree, "SCALE", mix.outputs["Result"], Scale=0.5 / math.pi, label="Radiance")
    return ambient.outputs[0], light.outputs[0]


def _many_scatterings(tree, let_through, light):
    """Colour socket: the radiance the higher orders of scattering send per unit of extinction,
    the lamp's light x core.cloud_shadows.many_scatterings(T) / 4 pi (isotropic)."""
    total = None
    for order in range(1, shadow_twin.OCTAVES + 1):
        scale = shadow_twin.OCTAVE_SCALE**order
        reached = h.math(tree, "POWER", let_through, scale)
        term = h.math(tree, "MULTIPLY", reached.outputs[0], scale / (4.0 * math.pi))
        total = term if total is None else h.math(tree, "ADD", total.outputs[0], term.outputs[0])
    total.label = "Higher Orders' Share / 4π"
    radiance = h.vector_math(tree, "SCALE", light, Scale=1.0, label="Many Scatterings")
    h.link(tree, total.outputs[0], radiance.inputs["Scale"])
    return radiance.outputs[0]


def eevee_output(tree, density, scattering, scene, sun, base, thickness):
    """The material's EEVEE output for a baked grid: density socket -> a share T scattering
    (scattering(tree, density socket) -> volume socket), the rest absorbing and emitting the
    ambient light (_ambient) of the layer between base and base + thickness; all of it emitting
    the higher orders' light (_many_scatterings). With the scene's Volume Shadows on, the share
    scattering is all of it."""
    attribute = h.add_node(tree, "ShaderNodeAttribute", attribute_type="GEOMETRY", attribute_name=GRID,
                           label="Sun's Light Let Through")
    switch = h.add_node(tree, "ShaderNodeValue", name=SHADOWS_SWITCH, label="EEVEE Shadows On (driven)")
    drivers.drive(switch.outputs[0], "default_value", "on",
                  [("on", "SCENE", scene, "eevee.use_volumetric_shadows")])
    let_through = h.math(tree, "MAXIMUM", attribute.outputs["Fac"], switch.outputs[0])
    lit = h.math(tree, "MULTIPLY", density, let_through.outputs[0], label="Lit Share")
    unlit = h.math(tree, "SUBTRACT", density, lit.outputs[0], label="Unlit Share")
    absorbed = h.add_node(tree, "ShaderNodeVolumeAbsorption", inputs={"Color": (0.0, 0.0, 0.0, 1.0)})
    h.link(tree, unlit.outputs[0], absorbed.inputs["Density"])
    glow = h.add_node(tree, "ShaderNodeEmission", label="The World's Light")
    ambient, light = _ambient(tree, sun, _ground_colour(tree, scene), base, thickness)
    h.link(tree, ambient, glow.inputs["Color"])
    h.link(tree, unlit.outputs[0], glow.inputs["Strength"])
    # The higher orders from the baked T itself, also under EEVEE's own shadows.
    orders = h.add_node(tree, "ShaderNodeEmission", name=MANY_SCATTERINGS, label="Many Scatterings")
    h.link(tree, _many_scatterings(tree, attribute.outputs["Fac"], light), orders.inputs["Color"])
    h.link(tree, density, orders.inputs["Strength"])
    shaders = [scattering(tree, lit.outputs[0]), absorbed.outputs[0], glow.outputs[0], orders.outputs[0]]
    total = shaders[0]
    for shader in shaders[1:]:
        add = h.add_node(tree, "ShaderNodeAddShader")
        h.link(tree, total, add.inputs[0])
        h.link(tree, shader, add.inputs[1])
        total = add.outputs[0]
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name=OUTPUT, target="EEVEE")
    h.link(tree, total, output.inputs["Volume"])
    return output
