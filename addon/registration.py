"""Registers every Sandscape class; the root __init__ only calls register()/unregister()."""

import bpy

from ..operators import sand_material
from . import panels

MODULES = (sand_material, panels)


def _classes():
    return [cls for module in MODULES for cls in module.classes]


def register():
    for cls in _classes():
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(_classes()):
        bpy.utils.unregister_class(cls)
