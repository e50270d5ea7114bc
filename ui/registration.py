"""Registers every Sandscape class; the root __init__ only calls register()/unregister().

A module may also define register()/unregister() for what is not a class (properties
attached to Blender types); they run after its classes are registered, and before they go.
"""

import bpy

from ..operators import atmosphere, demo, footprints, sand_material
from . import panels, properties

MODULES = (properties, sand_material, footprints, atmosphere, demo, panels)


def register():
    for module in MODULES:
        for cls in module.classes:
            bpy.utils.register_class(cls)
        if hasattr(module, "register"):
            module.register()


def unregister():
    for module in reversed(MODULES):
        if hasattr(module, "unregister"):
            module.unregister()
        for cls in reversed(module.classes):
            bpy.utils.unregister_class(cls)
