"""The cloud layer as a voxel grid: geometry nodes evaluate the Cloud Density's signed
Cloudiness once per voxel (Volume Cube; the material clamps it into a density after Cycles
interpolates it, so edges stay where the procedural layer has them). A render looks voxels up
instead of evaluating a dozen noise octaves at every step, and Cycles builds its volume bounds
from the grid (voxels far from cloud hold the background and stay inactive).

The grid is the layer at frame 0 and drifts downwind as a whole: the object's location is driven
by `wind x frame / fps` (a simple expression, evaluated without Python auto-run). The procedural
density is the same field carried by the same wind (every noise samples p - wind x time), so the
drifted grid is the procedural layer at every frame. The modifier's inputs never change with the
frame, so the grid is evaluated once per render, not once per frame.
"""

import math

import bpy

from ..core import clouds
from ..node_groups import cloud_density, weather_map
from ..node_groups import helper as h
from . import cloud_sunlight, drivers
from . import ownership as own

MODIFIER = "Sandscape Cloud Grid"
CLEAR = -clouds.CLOUDINESS_RANGE  # cloudiness far from cloud: the background, so those voxels stay inactive
MAX_VOXELS = 12_000_000  # about 20 s of geometry nodes on 2 cores, 46 MiB of floats at most


def box_and_resolution(region, low, high, voxel):
    """The Volume Cube's corners and voxel counts for a region (xmin, ymin, xmax, ymax), cubic
    voxels of edge `voxel` whose centres span the box corner to corner."""
    xmin, ymin, xmax, ymax = region
    extents = (xmax - xmin, ymax - ymin, high - low)
    counts = [max(2, int(math.ceil(extent / voxel)) + 1) for extent in extents]
    corner_min = (xmin, ymin, low)
    corner_max = tuple(start + (count - 1) * voxel for start, count in zip(corner_min, counts, strict=True))
    return corner_min, corner_max, counts


def _interface(tree):
    tree.interface.clear()
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")


def _plane_points(tree, corner_min, counts, voxel):
    """A point under every column of voxels (row after row of x): the weather map is 2D, so it is
    evaluated once per column on these points and looked up by index, not once per voxel."""
    index = h.add_node(tree, "GeometryNodeInputIndex")
    column = h.math(tree, "FLOORED_MODULO", index.outputs[0], float(counts[0]), label="Column")
    row = h.math(tree, "DIVIDE", index.outputs[0], float(counts[0]), label="Row")
    row_floor = h.math(tree, "FLOOR", row.outputs[0], label="Row Index")
    where = h.add_node(tree, "ShaderNodeCombineXYZ", label="Column Position")
    for axis, step in (("X", column), ("Y", row_floor)):
        placed = h.math(tree, "MULTIPLY_ADD", step.outputs[0], voxel, label=f"{axis} of the Column")
        placed.inputs[2].default_value = corner_min["XY".index(axis)]
        h.link(tree, placed.outputs[0], where.inputs[axis])
    points = h.add_node(tree, "GeometryNodePoints", name="Sandscape Weather Points", label="Columns",
                        inputs={"Count": counts[0] * counts[1]})
    h.link(tree, where.outputs[0], points.inputs["Position"])
    return points.outputs["Points"]


def _column_index(tree, corner_min, counts, voxel):
    """The index of the point under the voxel being evaluated."""
    position = h.position(tree)
    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, position.outputs["Position"], split.inputs[0])
    steps = []
    for axis in ("X", "Y"):
        low = corner_min["XY".index(axis)]
        offset = h.math(tree, "SUBTRACT", split.outputs[axis], low, label=f"{axis} − Min")
        step = h.math(tree, "DIVIDE", offset.outputs[0], voxel, label=f"{axis} Step")
        nearest = h.math(tree, "ROUND", step.outputs[0], label=f"{axis} Index")
        steps.append(nearest)
    index = h.math(tree, "MULTIPLY_ADD", steps[1].outputs[0], float(counts[0]), label="Column Index")
    h.link(tree, steps[0].outputs[0], index.inputs[2])
    return index.outputs[0]


def build_tree(tree, material, density_inputs, weather_inputs, image, box, voxel, sunlight=None):
    """Weather (procedural group or painted image, once per column) -> Cloud Density -> Volume
    Cube (-> the sun's light let through, baked per voxel: sunlight, cloud_sunlight.march's
    arguments after the volume) -> material."""
    if tree.animation_data is not None:  # the sun's direction, driven in a grid built with a sun
        tree.animation_data_clear()
    tree.nodes.clear()
    _interface(tree)
    group_out = h.add_node(tree, "NodeGroupOutput")
    corner_min, corner_max, counts = box
    density = h.add_node(tree, "GeometryNodeGroup", name="Sandscape Cloud Density", label="Cloud Density",
                         node_tree=h.ensure_group(cloud_density.GEOMETRY), inputs=density_inputs)
    if image is not None:
        position = h.position(tree)
        to_uv = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY_ADD",
                           name="Sandscape Weather Mapping", label="World → UV")
        h.link(tree, position.outputs["Position"], to_uv.inputs[0])
        to_uv.inputs[1].default_value = weather_inputs["uv_scale"]
        to_uv.inputs[2].default_value = (0.5, 0.5, 0.0)
        texture = h.add_node(tree, "GeometryNodeImageTexture", name="Sandscape Weather Image",
                             label="Weather", interpolation="Linear", extension="REPEAT")
        texture.inputs["Image"].default_value = image
        h.link(tree, to_uv.outputs[0], texture.inputs["Vector"])
        channels = h.add_node(tree, "FunctionNodeSeparateColor", name="Sandscape Weather Channels")
        h.link(tree, texture.outputs["Color"], channels.inputs["Color"])
        fields = {name: channels.outputs[channel]
                  for name, channel in (("Coverage", "Red"), ("Precipitation", "Green"), ("Type", "Blue"))}
    else:
        weather = h.add_node(tree, "GeometryNodeGroup", name="Sandscape Weather Map", label="Weather Map",
                             node_tree=h.ensure_group(weather_map.GEOMETRY), inputs=weather_inputs["inputs"])
        fields = {name: weather.outputs[name] for name in weather_inputs["linked"]}
    columns = _plane_points(tree, corner_min, counts, voxel)
    index = _column_index(tree, corner_min, counts, voxel)
    for name, field in fields.items():
        looked_up = h.add_node(tree, "GeometryNodeSampleIndex", label=f"{name} of the Column")
        h.link(tree, columns, looked_up.inputs["Geometry"])
        h.link(tree, field, looked_up.inputs["Value"])
        h.link(tree, index, looked_up.inputs["Index"])
        h.link(tree, looked_up.outputs["Value"], density.inputs[name])
    resolution = {f"Resolution {axis}": count for axis, count in zip("XYZ", counts, strict=True)}
    cube = h.add_node(tree, "GeometryNodeVolumeCube", name="Sandscape Cloud Voxels", label="Voxels",
                      inputs={"Background": CLEAR, "Min": corner_min, "Max": corner_max, **resolution})
    h.link(tree, density.outputs["Cloudiness"], cube.inputs["Density"])
    volume = cube.outputs["Volume"]
    if sunlight is not None:
        volume = cloud_sunlight.march(tree, volume, **sunlight)
    with_material = h.add_node(tree, "GeometryNodeSetMaterial", name="Sandscape Cloud Material")
    with_material.inputs["Material"].default_value = material
    h.link(tree, volume, with_material.inputs["Geometry"])
    h.link(tree, with_material.outputs["Geometry"], group_out.inputs[0])
    h.arrange(tree, set_widths=False)


def ensure_modifier(layer):
    """The layer's geometry-nodes modifier and its own tree (marked ours)."""
    modifier = layer.modifiers.get(MODIFIER)
    if modifier is None or modifier.type != "NODES":
        modifier = layer.modifiers.new(MODIFIER, "NODES")
    tree = modifier.node_group
    if tree is None or tree.get(own.GROUP_KEY) != own.CLOUD_GRID:
        tree = own.mark(bpy.data.node_groups.new("Sandscape Cloud Grid", "GeometryNodeTree"), own.GROUP_KEY,
                        own.CLOUD_GRID)
        modifier.node_group = tree
    return modifier, tree


def remove_modifier(layer):
    modifier = layer.modifiers.get(MODIFIER)
    if modifier is None:
        return
    tree = modifier.node_group
    layer.modifiers.remove(modifier)
    if tree is not None and tree.get(own.GROUP_KEY) == own.CLOUD_GRID and tree.users == 0:
        bpy.data.node_groups.remove(tree)


def drift_with_wind(layer, wind, fps):
    """Drive the layer's x and y by wind x frame / fps; none when calm."""
    for axis in (0, 1):
        layer.driver_remove("location", axis)
        rate = float(wind[axis]) / fps
        layer.location[axis] = 0.0
        if rate != 0.0:
            drivers.drive(layer, "location", f"frame * {rate!r}", [], index=axis)


def stop_drift(layer):
    for axis in (0, 1):
        layer.driver_remove("location", axis)
        layer.location[axis] = 0.0
