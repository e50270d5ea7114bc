"""Our node groups across Sandscape versions, without taking an artist's work away.

A group we build carries GROUP_KEY (the builder's NAME), VERSION_KEY and BUILT_KEY (a
fingerprint of what the builder made). ensure_group(builder) then:
- returns the group when its version is the builder's (edited or not: it is in use as it is);
- keeps a group of a newer version, made by a newer Sandscape, and notes it: an older Sandscape
  never downgrades a file;
- rebuilds an older group the artist has not edited (its fingerprint is still the built one), and
  moves every user over;
- leaves an older group the artist edited as theirs (renamed "<NAME> (edited)", no longer ours,
  its users unchanged) and builds ours beside it, noting both names.
NOTES collects those notes for the operator that caused them to report (drain_notes()).
"""

import hashlib

import bpy

GROUP_KEY = "sandscape_group"
VERSION_KEY = "sandscape_version"
BUILT_KEY = "sandscape_built"
EDITED_SUFFIX = " (edited)"
NOTES = []
# Node settings that are layout, not behaviour: moving or recolouring a node is no edit.
LAYOUT = {"rna_type", "name", "location", "location_absolute", "width", "height", "dimensions", "select",
          "show_options", "show_preview", "show_texture", "hide", "color", "color_tag", "use_custom_color",
          "session_uid", "internal_links", "inputs", "outputs", "type", "parent", "label", "shrink",
          "label_size", "text", "width_hidden", "is_active_output", "warning_propagation"}


def find_group(name):
    for group in bpy.data.node_groups:
        if group.get(GROUP_KEY) == name:
            return group
    return None


def _plain(value):
    if isinstance(value, float):
        return round(value, 6)
    if isinstance(value, bpy.types.ID):
        return value.name
    if isinstance(value, (set, frozenset)):
        return tuple(sorted(value))
    if hasattr(value, "__len__") and not isinstance(value, str):
        return tuple(_plain(v) for v in value)
    return value


def fingerprint(tree):
    """A digest of what a group does: its interface, nodes (type, settings, unlinked input values,
    muted or not) and links; where nodes sit and how they look do not count."""
    parts = [tuple((i.in_out, i.name, i.socket_type, _plain(getattr(i, "default_value", None)))
                   for i in tree.interface.items_tree if i.item_type == "SOCKET")]
    for node in sorted(tree.nodes, key=lambda n: n.name):
        settings = tuple((p.identifier, _plain(getattr(node, p.identifier))) for p in node.bl_rna.properties
                         if p.identifier not in LAYOUT and not p.identifier.startswith("bl_")
                         and (p.type in {"BOOLEAN", "INT", "FLOAT", "ENUM", "STRING"} and not p.is_readonly
                              or p.identifier == "node_tree"))
        inputs = tuple((s.identifier, _plain(s.default_value)) for s in node.inputs
                       if not s.is_linked and hasattr(s, "default_value"))
        parts.append((node.name, node.bl_idname, settings, inputs))
    parts.append(tuple(sorted((link.from_node.name, link.from_socket.identifier, link.to_node.name,
                               link.to_socket.identifier) for link in tree.links)))
    return hashlib.sha1(repr(parts).encode()).hexdigest()


def _build(builder):
    new = bpy.data.node_groups.new(builder.NAME, builder.TREE_TYPE)
    new[GROUP_KEY] = builder.NAME
    new[VERSION_KEY] = builder.VERSION
    builder.build(new)
    new[BUILT_KEY] = fingerprint(new)
    return new


def ensure_group(builder):
    """Our group for a builder module, built, kept or rebuilt as the module docstring says."""
    old = find_group(builder.NAME)
    if old is None:
        return _build(builder)
    version = old.get(VERSION_KEY, 0)
    if version == builder.VERSION:
        return old
    if version > builder.VERSION:
        NOTES.append(f"kept '{old.name}' at version {version}, newer than this Sandscape's {builder.VERSION}")
        return old
    edited = BUILT_KEY in old and old[BUILT_KEY] != fingerprint(old)
    new = _build(builder)
    if edited:
        del old[GROUP_KEY]  # the artist's now: never found, rebuilt or removed by us again
        old.name = builder.NAME + EDITED_SUFFIX
        new.name = builder.NAME
        NOTES.append(f"kept your edited '{old.name}' (its users unchanged) and built '{new.name}' "
                     f"version {builder.VERSION} beside it")
        return new
    old.user_remap(new)
    bpy.data.node_groups.remove(old)
    new.name = builder.NAME
    return new


def drain_notes():
    """The notes since the last call, once each, and forget them."""
    notes = list(dict.fromkeys(NOTES))
    NOTES.clear()
    return notes
