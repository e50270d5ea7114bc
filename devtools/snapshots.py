"""Snapshots of Sandscape's node groups: interface, nodes (type, label, frame, place, settings,
unlinked input values) and links, as JSON in tests/snapshots/. A builder that changes its group
must bump its VERSION (files built by the old one are then rebuilt); the snapshot test fails
when the group changed and the VERSION did not.

Update after a deliberate change (and a VERSION bump; a changed group at its old VERSION is
refused, so the snapshot cannot be brought in line without one):
    .venv/bin/python devtools/snapshots.py
"""

import importlib
import json
import pathlib
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent
SNAPSHOTS = REPO / "tests" / "snapshots"
# Node properties that are the editor's state, not what the group computes or how it reads.
SKIP = {"rna_type", "name", "location", "location_absolute", "width", "height", "dimensions", "select",
        "show_options", "show_preview", "show_texture", "hide", "mute", "color", "color_tag",
        "use_custom_color", "session_uid", "internal_links", "inputs", "outputs", "type", "bl_idname",
        "bl_label", "bl_description", "bl_icon", "bl_static_type", "bl_width_default", "bl_width_min",
        "bl_width_max", "bl_height_default", "bl_height_min", "bl_height_max", "is_active_output",
        "warning_propagation", "parent", "label", "shrink", "label_size", "text", "is_dangling_reroute",
        "width_hidden"}


def _value(value):
    if hasattr(value, "name") and hasattr(value, "bl_rna") and hasattr(value, "users"):
        return f"<{value.name}>"  # a data-block: its name
    if isinstance(value, float):
        return round(value, 6)
    if isinstance(value, (bool, int, str)) or value is None:
        return value
    try:
        return [_value(v) for v in value]
    except TypeError:
        return str(value)


_MISSING = object()


def _stock_inputs(tree, node):
    """Input values of a new node of the same type, as Blender makes it (with the same settings
    for nodes whose sockets depend on them, like Math's operation)."""
    fresh = tree.nodes.new(node.bl_idname)
    try:
        for prop in fresh.bl_rna.properties:
            if prop.type == "ENUM" and not prop.is_readonly and prop.identifier not in SKIP:
                try:
                    setattr(fresh, prop.identifier, getattr(node, prop.identifier))
                except (TypeError, AttributeError):
                    continue
        if hasattr(node, "node_tree"):
            fresh.node_tree = node.node_tree
            return {}  # a group node: its inputs are the group's own, every one counts
        return {s.name: _value(s.default_value) for s in fresh.inputs
                if hasattr(s, "default_value") and s.enabled}
    finally:
        tree.nodes.remove(fresh)


def serialize(tree):
    interface = []
    for item in tree.interface.items_tree:
        if item.item_type != "SOCKET":
            continue
        entry = {"in_out": item.in_out, "name": item.name, "type": item.socket_type,
                 "description": item.description}
        for key in ("default_value", "min_value", "max_value", "subtype"):
            if hasattr(item, key):
                entry[key] = _value(getattr(item, key))
        interface.append(entry)
    nodes = {}
    for node in tree.nodes:
        settings = {}
        for prop in node.bl_rna.properties:
            if prop.identifier in SKIP or prop.is_readonly and prop.type != "POINTER":
                continue
            if prop.type in {"POINTER", "COLLECTION"} and prop.identifier != "node_tree":
                continue
            settings[prop.identifier] = _value(getattr(node, prop.identifier))
        # Sockets by name: identifiers of the same socket differ between versions ("A", "A_VEC3").
        # Only the values the builder set: Blender's own defaults (and sockets one version has and
        # the other not, like 5.2's Thin Wall) are not the builder's.
        stock = _stock_inputs(tree, node)
        inputs = {socket.name: _value(socket.default_value) for socket in node.inputs
                  if not socket.is_linked and hasattr(socket, "default_value") and socket.enabled
                  and stock.get(socket.name, _MISSING) != _value(socket.default_value)}
        nodes[node.name] = {"type": node.bl_idname, "label": node.label,
                            "frame": node.parent.name if node.parent else None,
                            "at": [round(v) for v in node.location_absolute], "settings": settings,
                            "inputs": inputs}
    links = sorted([link.from_node.name, link.from_socket.name, link.to_node.name, link.to_socket.name]
                   for link in tree.links)
    return {"description": tree.description, "interface": interface, "nodes": nodes, "links": links}


def path_for(builder):
    return SNAPSHOTS / (builder.NAME.lower().replace(" ", "_") + ".json")


def build_fresh(bpy, builder):
    tree = bpy.data.node_groups.new(builder.NAME, builder.TREE_TYPE)
    builder.build(tree)
    return tree


def main():
    sys.path.insert(0, str(REPO))
    from devtools import session

    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    session.reset()
    SNAPSHOTS.mkdir(parents=True, exist_ok=True)
    refused = []
    for builder in importlib.import_module(f"{session.MODULE}.node_groups.catalog").builders():
        snapshot = {"version": builder.VERSION, "group": serialize(build_fresh(bpy, builder))}
        path = path_for(builder)
        if path.is_file():
            stored = json.loads(path.read_text())
            changed = json.loads(json.dumps(snapshot["group"])) != stored["group"]
            if changed and builder.VERSION <= stored["version"]:
                # No way round the version test: a changed group needs a higher VERSION first.
                refused.append(f"{builder.NAME} changed at VERSION {builder.VERSION} (snapshot at "
                               f"{stored['version']}): bump VERSION in its builder")
                continue
        text = json.dumps(snapshot, indent=1, ensure_ascii=False, sort_keys=True)
        path.write_text(text + "\n")
        print(f"snapshots: {builder.NAME} v{builder.VERSION} -> {path.relative_to(REPO)}")
    for line in refused:
        print(f"snapshots: refused: {line}", file=sys.stderr)
    if refused:
        sys.exit(1)


if __name__ == "__main__":
    main()
