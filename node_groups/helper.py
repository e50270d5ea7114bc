"""Shared node-group plumbing: versioned, idempotent groups, terse tree building, and a layout
that reads left to right.

A group we build carries custom properties: GROUP_KEY (the builder's NAME), VERSION_KEY and a
fingerprint of what was built (versions.py: never downgraded, an artist's edit kept). We find our
groups by GROUP_KEY, never by name, so a user's group that happens to share the name is left alone.

Builders create nodes anywhere, put the nodes of each stage in a frame (frame()), and end
with arrange(tree): columns by dependency, frames stacked as bands, no two nodes overlapping.
"""

import bpy

from .versions import GROUP_KEY, VERSION_KEY, ensure_group, find_group  # noqa: F401 (the builders' API)

GROUP_NODE_TYPES = {"ShaderNodeTree": "ShaderNodeGroup", "CompositorNodeTree": "CompositorNodeGroup",
                    "GeometryNodeTree": "GeometryNodeGroup"}


def insert_group_node(tree, builder, location=(0.0, 0.0)):
    """A node of our group (ensured first) in someone's tree, selected and active."""
    node = tree.nodes.new(GROUP_NODE_TYPES[tree.bl_idname])
    node.node_tree = ensure_group(builder)
    node.label = builder.NAME.removeprefix("Sandscape ")
    node.width = GROUP_NODE_WIDTH
    node.location = location
    for other in tree.nodes:
        other.select = False
    node.select = True
    tree.nodes.active = node
    return node


SURFACE_NORMAL = "sandscape:surface-normal"  # a Normal input that falls back to the shading normal


def add_input(tree, name, socket_type, description, default=None, min_value=None, max_value=None,
              subtype=None):
    """An interface input. A vector Normal input shows no value field: unlinked, the group uses
    the shading normal (normal_or_geometry), so a typed value would mean nothing."""
    socket = _add_socket(tree, "INPUT", name, socket_type, description, default, min_value, max_value,
                         subtype)
    if subtype == SURFACE_NORMAL:
        socket.hide_value = True
    return socket


def add_output(tree, name, socket_type, description):
    return _add_socket(tree, "OUTPUT", name, socket_type, description)


def _add_socket(tree, in_out, name, socket_type, description, default=None, min_value=None,
                max_value=None, subtype=None):
    socket = tree.interface.new_socket(name, in_out=in_out, socket_type=socket_type)
    socket.description = description
    if subtype is not None and subtype != SURFACE_NORMAL:
        socket.subtype = subtype
    if min_value is not None:
        socket.min_value = min_value
    if max_value is not None:
        socket.max_value = max_value
    if default is not None:
        socket.default_value = default
    return socket


def add_node(tree, node_type, location=(0, 0), label=None, inputs=None, name=None, **props):
    """Add a node, set its properties, and set unlinked input defaults by name or index.

    name: a fixed node name, for nodes the bpy layer finds again (labels are the artist's).
    """
    node = tree.nodes.new(node_type)
    node.location = location
    if name:
        node.name = name
    if label:
        node.label = label
    for key, value in props.items():
        setattr(node, key, value)
    for key, value in (inputs or {}).items():
        node.inputs[key].default_value = value
    return node


def math(tree, operation, a=None, b=None, location=(0, 0), label=None, c=None):
    """A Math node whose inputs (c: the third, of Multiply Add and the like) are either sockets
    (linked) or numbers (defaults)."""
    return _operands(tree, add_node(tree, "ShaderNodeMath", location, label, operation=operation), a, b, c)


def finite(tree, value, top, label=None):
    """A driven input typed by hand as NaN or infinity made a number in [0, top]. Returns the socket
    and the two nodes. The bound goes first: Cycles' CPU max and min keep a NaN in their first input
    and drop it in the second (the GPU's drop it in either)."""
    low = math(tree, "MAXIMUM", 0.0, value)
    high = math(tree, "MINIMUM", top, low.outputs[0], label=label)
    return high.outputs[0], (low, high)


def vector_math(tree, operation, a=None, b=None, label=None, c=None, **inputs):
    """A Vector Math node whose first three inputs are sockets (linked) or values (defaults)."""
    node = add_node(tree, "ShaderNodeVectorMath", label=label, operation=operation, inputs=inputs)
    return _operands(tree, node, a, b, c)


def _operands(tree, node, *values):
    for index, value in enumerate(values):
        if value is None:
            continue
        if isinstance(value, bpy.types.NodeSocket):
            tree.links.new(value, node.inputs[index])
        else:
            node.inputs[index].default_value = value
    return node


def add_sockets(tree, input_names, inputs, outputs):
    """The named inputs of a socket table (name -> add_input's arguments) in that order, then
    every output of an output table (name -> (type, description))."""
    for name in input_names:
        add_input(tree, name, *inputs[name])
    for name, (socket_type, description) in outputs.items():
        add_output(tree, name, socket_type, description)


class GeometryBuilder:
    """A shader group's builder for geometry nodes, shaped like a builder module for ensure_group:
    the same nodes (position() picks the Position node), its name ending in "Field"."""

    TREE_TYPE = "GeometryNodeTree"

    def __init__(self, name, version, description, build):
        self.NAME, self.VERSION, self.DESCRIPTION = f"{name} Field", version, description
        self.build = build


def position(tree):
    """A node whose Position output is the point being shaded (shader trees) or evaluated
    (geometry nodes): one builder serves both."""
    if tree.bl_idname == "GeometryNodeTree":
        return add_node(tree, "GeometryNodeInputPosition")
    return add_node(tree, "ShaderNodeNewGeometry")


def normal_or_geometry(tree, normal):
    """The Normal input if it was linked (not zero), else the shading normal: a group's unlinked
    vector input is (0, 0, 0), and a zero normal would make the shaders meaningless.
    Returns (the normal socket, the nodes made)."""
    geometry = add_node(tree, "ShaderNodeNewGeometry")
    length = vector_math(tree, "LENGTH", normal, label="|Normal|")
    given = math(tree, "GREATER_THAN", length.outputs["Value"], 1e-6, label="Normal Given")
    choose = add_node(tree, "ShaderNodeMix", label="Given or Surface Normal", data_type="VECTOR")
    link(tree, given.outputs[0], socket(choose.inputs, "Factor"))
    link(tree, geometry.outputs["Normal"], socket(choose.inputs, "A"))
    link(tree, normal, socket(choose.inputs, "B"))
    unit = vector_math(tree, "NORMALIZE", socket(choose.outputs, "Result"), label="Normal")
    return unit.outputs["Vector"], (geometry, length, given, choose, unit)


def wind_direction(tree, wind):
    """Unit horizontal direction of a wind socket, along X when calm (core.sand / core.clouds
    twin it). Returns (the direction socket, the nodes made)."""
    flat = vector_math(tree, "MULTIPLY", wind, (1.0, 1.0, 0.0), label="Horizontal Wind")
    length = vector_math(tree, "LENGTH", flat.outputs[0], label="|Wind|")
    calm = math(tree, "LESS_THAN", length.outputs["Value"], 1e-9, label="Calm")
    fallback = vector_math(tree, "SCALE", (1.0, 0.0, 0.0), label="Calm: along X")
    link(tree, calm.outputs[0], fallback.inputs["Scale"])
    either = vector_math(tree, "ADD", flat.outputs[0], fallback.outputs[0], label="Wind or X")
    direction = vector_math(tree, "NORMALIZE", either.outputs[0], label="Wind Direction")
    return direction.outputs[0], (flat, length, calm, fallback, either, direction)


def link(tree, from_socket, to_socket):
    return tree.links.new(from_socket, to_socket)


def socket(sockets, name):
    """The enabled socket of that name (Mix and Compare nodes keep one per data type)."""
    return next(s for s in sockets if s.name == name and s.enabled)


def group_io(tree):
    """Group Input and Group Output nodes (arrange() puts them first and last)."""
    return add_node(tree, "NodeGroupInput"), add_node(tree, "NodeGroupOutput")


# ---------------------------------------------------------------- layout

COLUMN_GAP, ROW_GAP, BAND_GAP = 80.0, 30.0, 90.0
NODE_WIDTH, GROUP_NODE_WIDTH = 160.0, 180.0  # set, not left to defaults that vary between versions
WIDE_NODES = {"ShaderNodeBsdfPrincipled": 240.0}
HEADER, SOCKET_ROW, OPTIONS_ROW = 40.0, 24.0, 34.0
PLAIN = {"NodeGroupInput", "NodeGroupOutput", "NodeReroute", "ShaderNodeGroup", "CompositorNodeGroup",
         "GeometryNodeGroup"}


def frame(tree, label, nodes):
    """Put nodes into a labelled frame: one stage of the group, drawn as a box around them."""
    if not nodes:
        return None
    box = tree.nodes.new("NodeFrame")
    box.label = label
    box.name = f"Stage: {label}"
    for node in nodes:
        node.parent = box
    return box


def node_size(node):
    """(width, height) a node takes in the editor: its drawn size, else an upper estimate.

    Background sessions draw nothing (dimensions are 0), so the estimate counts the rows a
    node shows: header, each visible socket, and a row of options for nodes that have them.
    """
    if node.dimensions[1] > 0:
        return float(node.dimensions[0]), float(node.dimensions[1])
    rows = sum(1 for s in node.outputs if s.enabled and not s.hide) + sum(
        1 for s in node.inputs if s.enabled and not s.hide and s.type != "CUSTOM")
    options = 0.0 if node.bl_idname in PLAIN else OPTIONS_ROW * 2
    return float(node.width), HEADER + SOCKET_ROW * rows + options


def arrange(tree, set_widths=True):
    """Place every node: a column per dependency depth (sources left, Group Output right), a
    band per frame (stacked top to bottom in the order the data flows), nodes stacked in their
    cell. Returns {node name: (x, y, width, height)}, y being the top edge.

    set_widths: give every node our width (groups); False keeps Blender's (materials, whose
    Principled BSDF needs its own).
    """
    nodes = [n for n in tree.nodes if n.bl_idname != "NodeFrame"]
    for node in nodes if set_widths else ():
        wide = GROUP_NODE_WIDTH if node.bl_idname.endswith("NodeGroup") else NODE_WIDTH
        node.width = max(WIDE_NODES.get(node.bl_idname, wide), node.bl_width_min)
    before = {n.name: set() for n in nodes}
    for link in tree.links:
        if link.from_node.name in before and link.to_node.name in before:
            before[link.to_node.name].add(link.from_node.name)
    column = {}

    def depth(name, seen=()):
        if name not in column:
            if name in seen:  # a cycle would be a broken tree; keep it finite
                return 0
            column[name] = max((depth(p, (*seen, name)) + 1 for p in before[name]), default=0)
        return column[name]

    for node in nodes:
        depth(node.name)
    last = max(column.values(), default=0)
    for node in nodes:
        if node.bl_idname == "NodeGroupOutput":
            column[node.name] = last + 1
    band_of = {n.name: (n.parent.name if n.parent is not None else "") for n in nodes}
    # Unframed nodes (group input and output) on top, then the stages in the order the builder
    # framed them, which is the order the data flows through them.
    bands = [""] + [n.name for n in tree.nodes if n.bl_idname == "NodeFrame"]
    widths = {}
    for node in nodes:
        widths[column[node.name]] = max(widths.get(column[node.name], 0.0), node_size(node)[0])
    x_of, x = {}, 0.0
    for index in range(max(widths, default=-1) + 1):
        x_of[index] = x
        x += widths.get(index, 0.0) + COLUMN_GAP
    placed, top = {}, 0.0
    for band in bands:
        members = [n for n in nodes if band_of[n.name] == band]
        if not members:
            continue
        deepest = 0.0
        for index in sorted({column[n.name] for n in members}):
            y = top
            for node in (n for n in members if column[n.name] == index):  # in creation order
                width, height = node_size(node)
                node.location_absolute = (x_of[index], y)
                placed[node.name] = (x_of[index], y, width, height)
                y -= height + ROW_GAP
            deepest = max(deepest, top - y)
        top -= deepest + BAND_GAP
    return placed


def polyline_curve(curve, xs, ys):
    """A curve mapping's curve through these points, straight between them (vector handles)."""
    while len(curve.points) > 2:
        curve.points.remove(curve.points[-1])
    curve.points[0].location = (float(xs[0]), float(ys[0]))
    curve.points[1].location = (float(xs[-1]), float(ys[-1]))
    for x, y in zip(xs[1:-1], ys[1:-1], strict=True):
        curve.points.new(float(x), float(y))
    for point in curve.points:
        point.handle_type = "VECTOR"
