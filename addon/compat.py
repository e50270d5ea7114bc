"""Where Blender 5.0 and 5.2 differ, in one place: the rest of Sandscape calls these functions.

Each difference is detected by the feature, not by the version number, so a 5.1 or a later
5.x build takes whichever path it supports.

- Geometry-nodes modifier inputs: 5.0 stores them as ID properties on the modifier
  (`modifier["Socket_1"]`); 5.2 gives the modifier real RNA properties
  (`modifier.properties.inputs.Socket_1.value`) and the modifier holds no ID properties at
  all, so item access raises TypeError. Writing the RNA value does not tag the object for
  re-evaluation, so the setter tags it on both versions.
- EEVEE's world lighting damps its second spherical-harmonic band more on 5.0 than on 5.2: a
  measured behaviour, not a feature to detect, so it goes by the version (5.1, not measured,
  takes 5.0's).
"""

import bpy

from ..core import atmosphere as air


def _input_holder(modifier, identifier):
    """The 5.2 RNA struct of one input, or None where inputs are ID properties (5.0)."""
    properties = getattr(modifier, "properties", None)
    if properties is None:
        return None
    return getattr(properties.inputs, identifier)


def set_modifier_input(modifier, identifier, value):
    """Set a geometry-nodes modifier input by its interface socket identifier."""
    holder = _input_holder(modifier, identifier)
    if holder is None:
        modifier[identifier] = value
    else:
        holder.value = value
    modifier.id_data.update_tag()


def modifier_input(modifier, identifier):
    """A geometry-nodes modifier input's value, by its interface socket identifier."""
    holder = _input_holder(modifier, identifier)
    value = modifier[identifier] if holder is None else holder.value
    return tuple(value) if hasattr(value, "__len__") and not isinstance(value, str) else value


def modifier_input_identifiers(modifier):
    """A geometry-nodes modifier's input identifiers by their sockets' names."""
    return {item.name: item.identifier for item in modifier.node_group.interface.items_tree
            if item.item_type == "SOCKET" and item.in_out == "INPUT"}


def set_modifier_input_named(modifier, name, value):
    """Set a geometry-nodes modifier input by its socket's name (a group's own, never a user's)."""
    set_modifier_input(modifier, modifier_input_identifiers(modifier)[name], value)


def eevee_dering_limit():
    """The contrast EEVEE's world lighting keeps before deringing, in this Blender (core.atmosphere)."""
    return air.EEVEE_DERING_LIMIT[(5, 2) if bpy.app.version >= (5, 2) else (5, 0)]
