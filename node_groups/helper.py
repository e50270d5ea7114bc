"""Shared node-group plumbing: versioned, idempotent groups and terse tree building.

A group we build carries two custom properties: GROUP_KEY (the builder's NAME) and
VERSION_KEY. We find our groups by GROUP_KEY, never by name, so a user's group that
happens to share the name is left alone.
"""

import bpy

GROUP_KEY = "sandscape_group"
VERSION_KEY = "sandscape_version"


def find_group(name):
    for group in bpy.data.node_groups:
        if group.get(GROUP_KEY) == name:
            return group
    return None


def ensure_group(builder):
    """Return our group for a builder module, (re)building it when its version changed.

    A rebuilt group takes over every user of the old one (user_remap), so materials
    keep working; then the old one is removed and the new one takes its name.
    """
    old = find_group(builder.NAME)
    if old is not None and old.get(VERSION_KEY) == builder.VERSION:
        return old
    new = bpy.data.node_groups.new(builder.NAME, builder.TREE_TYPE)
    new[GROUP_KEY] = builder.NAME
    new[VERSION_KEY] = builder.VERSION
    builder.build(new)
    if old is not None:
        old.user_remap(new)
        bpy.data.node_groups.remove(old)
        new.name = builder.NAME
    return new


def add_input(tree, name, socket_type, description, default=None, min_value=None, max_value=None,
              subtype=None):
    return _add_socket(tree, "INPUT", name, socket_type, description, default, min_value, max_value,
                       subtype)


def add_output(tree, name, socket_type, description):
    return _add_socket(tree, "OUTPUT", name, socket_type, description)


def _add_socket(tree, in_out, name, socket_type, description, default=None, min_value=None,
                max_value=None, subtype=None):
    socket = tree.interface.new_socket(name, in_out=in_out, socket_type=socket_type)
    socket.description = description
    if subtype is not None:
        socket.subtype = subtype
    if min_value is not None:
        socket.min_value = min_value
    if max_value is not None:
        socket.max_value = max_value
    if default is not None:
        socket.default_value = default
    return socket


def add_node(tree, node_type, location=(0, 0), label=None, inputs=None, **props):
    """Add a node, set its properties, and set unlinked input defaults by name or index."""
    node = tree.nodes.new(node_type)
    node.location = location
    if label:
        node.label = label
    for key, value in props.items():
        setattr(node, key, value)
    for key, value in (inputs or {}).items():
        node.inputs[key].default_value = value
    return node


def math(tree, operation, a=None, b=None, location=(0, 0), label=None):
    """A Math node whose two inputs are either sockets (linked) or numbers (defaults)."""
    node = add_node(tree, "ShaderNodeMath", location, label, operation=operation)
    for index, value in enumerate((a, b)):
        if value is None:
            continue
        if isinstance(value, bpy.types.NodeSocket):
            tree.links.new(value, node.inputs[index])
        else:
            node.inputs[index].default_value = value
    return node


def link(tree, from_socket, to_socket):
    return tree.links.new(from_socket, to_socket)


def group_io(tree):
    """Group Input and Group Output nodes, placed left and right."""
    return (add_node(tree, "NodeGroupInput", (-900, 0)),
            add_node(tree, "NodeGroupOutput", (900, 0)))
