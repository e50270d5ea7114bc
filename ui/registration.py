"""Registers every Sandscape class; the root __init__ only calls register()/unregister().

A module may also define register()/unregister() for what is not a class (properties attached
to Blender types, menu entries, handlers); they run after its classes are registered, and
before they go.
"""

import bpy

from ..addon import post_handlers, settings, sparkle_footprint
from ..operators import atmosphere, clouds, demo, dunes, footprints, nodes, render, sand, walker
from ..operators import post as post_operators
from . import menus, panels

MODULES = (settings, dunes, sand, walker, footprints, atmosphere, clouds, post_operators, demo, render,
           nodes, panels, menus, post_handlers, sparkle_footprint)


def register():
    for module in MODULES:
        for cls in getattr(module, "classes", ()):
            bpy.utils.register_class(cls)
        if hasattr(module, "register"):
            module.register()


def unregister():
    for module in reversed(MODULES):
        if hasattr(module, "unregister"):
            module.unregister()
        for cls in reversed(getattr(module, "classes", ())):
            bpy.utils.unregister_class(cls)
