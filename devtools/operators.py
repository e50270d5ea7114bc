"""Calling an operator's execute() directly, for tests: bpy.ops turns an ERROR report into a
RuntimeError and hides the returned set, so a test of "ERROR and CANCELLED" needs both."""

import types

import bpy


def run_execute(idname, context=None, **props):
    """execute() of operator `idname` ("sandscape.paint_footprints") on a stand-in for the operator:
    its property defaults, then props, and its own methods. Returns (result set, [(kinds, text)])."""
    module, name = idname.split(".")
    cls = getattr(bpy.types, f"{module.upper()}_OT_{name}")
    rna = getattr(getattr(bpy.ops, module), name).get_rna_type()
    values = {p.identifier: tuple(p.default_array) if getattr(p, "is_array", False) else p.default
              for p in rna.properties if p.identifier != "rna_type"}
    reports = []
    stand_in = types.SimpleNamespace(**{**values, **props}, bl_rna=rna,
                                     report=lambda kinds, text: reports.append((set(kinds), text)))
    stand_in.properties = stand_in  # an operator's own properties, as value checks read them
    for base in reversed(cls.__mro__):
        if base.__module__.startswith("bpy"):
            continue
        for attr, value in vars(base).items():
            if isinstance(value, types.FunctionType) and attr != "execute":
                setattr(stand_in, attr, types.MethodType(value, stand_in))
            elif not attr.startswith("__") and not callable(value) and not hasattr(stand_in, attr):
                setattr(stand_in, attr, value)
    return cls.execute(stand_in, context or bpy.context), reports
