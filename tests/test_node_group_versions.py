"""Node groups across Sandscape versions: a newer file's group is never downgraded, an artist's
edit of one of ours is never thrown away, and an unedited old one is rebuilt with its users moved
over; the operator that met them says so."""

import bpy
import pytest

from devtools import operators


@pytest.fixture
def versions(sandscape):
    return sandscape.node_groups.versions


@pytest.fixture
def builder(sandscape):
    return sandscape.node_groups.ripples


def user_of(group):
    """A material of the artist's that uses the group."""
    material = bpy.data.materials.new("Their Sand")
    node = material.node_tree.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    return material, node


def an_edit(group):
    """The artist changes what one node does: a value typed into an unlinked input."""
    def typed(socket):
        value = getattr(socket, "default_value", None)
        return not socket.is_linked and socket.enabled and isinstance(value, float)

    node = next(n for n in sorted(group.nodes, key=lambda n: n.name) if any(typed(s) for s in n.inputs))
    socket = next(s for s in node.inputs if typed(s))
    socket.default_value += 0.123
    return node.name, socket.identifier, socket.default_value


def test_an_unedited_older_group_is_rebuilt_and_its_users_move_over(versions, builder):
    group = versions.ensure_group(builder)
    group[versions.VERSION_KEY] = builder.VERSION - 1  # as an older Sandscape left it
    material, node = user_of(group)
    rebuilt = versions.ensure_group(builder)
    assert rebuilt[versions.VERSION_KEY] == builder.VERSION and rebuilt.name == builder.NAME
    assert node.node_tree == rebuilt and versions.find_group(builder.NAME) == rebuilt
    assert len([g for g in bpy.data.node_groups if g.name.startswith(builder.NAME)]) == 1
    assert versions.drain_notes() == []


def test_an_edited_older_group_stays_the_artists_beside_ours(versions, builder):
    group = versions.ensure_group(builder)
    group[versions.VERSION_KEY] = builder.VERSION - 1
    name, socket, value = an_edit(group)
    material, node = user_of(group)
    ours = versions.ensure_group(builder)
    assert ours != group and ours.name == builder.NAME and ours[versions.VERSION_KEY] == builder.VERSION
    assert group.name == builder.NAME + versions.EDITED_SUFFIX and versions.GROUP_KEY not in group
    assert node.node_tree == group  # their material keeps their edit
    assert group.nodes[name].inputs[socket].default_value == pytest.approx(value)
    assert versions.find_group(builder.NAME) == ours and versions.ensure_group(builder) == ours
    notes = versions.drain_notes()
    assert len(notes) == 1 and group.name in notes[0] and ours.name in notes[0]


def test_a_newer_group_is_kept_as_it_is(versions, builder):
    group = versions.ensure_group(builder)
    group[versions.VERSION_KEY] = builder.VERSION + 1  # saved by a newer Sandscape
    name, socket, value = an_edit(group)  # whatever the newer builder made differently
    assert versions.ensure_group(builder) == group
    assert group[versions.VERSION_KEY] == builder.VERSION + 1
    assert group.nodes[name].inputs[socket].default_value == pytest.approx(value)
    assert "newer" in versions.drain_notes()[0]


def test_moving_and_recolouring_nodes_is_no_edit(versions, builder):
    group = versions.ensure_group(builder)
    for node in group.nodes:
        node.location.x += 40.0
        node.use_custom_color, node.color = True, (1.0, 0.2, 0.2)
    assert versions.fingerprint(group) == group[versions.BUILT_KEY]
    an_edit(group)
    assert versions.fingerprint(group) != group[versions.BUILT_KEY]


def test_the_operator_that_met_a_newer_group_says_so(sandscape, versions):
    from devtools import readback

    readback.uv_plane()
    ripples = versions.ensure_group(sandscape.node_groups.ripples)
    ripples[versions.VERSION_KEY] = sandscape.node_groups.ripples.VERSION + 1
    result, reports = operators.run_execute("sandscape.add_sand_material", context=bpy.context)
    assert result == {"FINISHED"}
    assert any("Node groups: kept" in text and "Ripples" in text for kinds, text in reports), reports


def test_running_again_brings_an_older_files_groups_up_to_date(sandscape, versions):
    """Found by an artist-eye check: re-running Add Sand Material on an older file's material left
    its groups as they were, edited or not."""
    from devtools import readback

    readback.uv_plane()
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    material = bpy.context.active_object.active_material
    look = next(n for n in material.node_tree.nodes if n.name == "Sandscape Look")
    physical = sandscape.node_groups.physical_sand
    cells = versions.find_group(sandscape.node_groups.glint_cells.NAME)  # nested in the glints
    look.node_tree[versions.VERSION_KEY] = physical.VERSION - 1  # as an older Sandscape left them
    cells[versions.VERSION_KEY] = sandscape.node_groups.glint_cells.VERSION - 1
    edited = look.node_tree
    an_edit(edited)
    result, reports = operators.run_execute("sandscape.add_sand_material", context=bpy.context)
    assert result == {"FINISHED"}
    assert edited.name == physical.NAME + versions.EDITED_SUFFIX and look.node_tree == edited  # theirs, kept
    assert versions.find_group(physical.NAME)[versions.VERSION_KEY] == physical.VERSION  # ours, beside it
    fresh_cells = versions.find_group(sandscape.node_groups.glint_cells.NAME)
    assert fresh_cells[versions.VERSION_KEY] == sandscape.node_groups.glint_cells.VERSION  # unedited: rebuilt
    assert any("edited" in text for kinds, text in reports), reports
