"""Calling an operator's execute() directly, for tests: bpy.ops turns an ERROR report into a
RuntimeError and hides the returned set, so a test of "ERROR and CANCELLED" needs both."""

import types

import bpy


def is_refusal(error):
    """True when a RuntimeError from bpy.ops is an operator's own ERROR report (a refusal), not a
    Python traceback inside it or a failed poll."""
    text = str(error)
    return text.startswith("Error: ") and "Traceback" not in text and "poll()" not in text


def run_execute(idname, context=None, **props):
    """execute() of operator `idname` ("sandscape.paint_footprints") on a stand-in for the operator:
    its property defaults, then props, and its own methods. Returns (result set, [(kinds, text)])."""
    return _run(idname, "execute", context, props)


def run_invoke(idname, context=None, **props):
    """invoke() as a button click does it, which a background session cannot: bpy.ops falls back to
    execute() without a window. Only props count as set by the caller."""
    return _run(idname, "invoke", context, props)


def _run(idname, method, context, props):
    module, name = idname.split(".")
    cls = getattr(bpy.types, f"{module.upper()}_OT_{name}")
    rna = getattr(getattr(bpy.ops, module), name).get_rna_type()
    values = {p.identifier: tuple(p.default_array) if getattr(p, "is_array", False) else p.default
              for p in rna.properties if p.identifier != "rna_type"}
    reports = []
    stand_in = _StandIn(**{**values, **props}, bl_rna=rna,
                        report=lambda kinds, text: reports.append((set(kinds), text)))
    stand_in.properties = stand_in  # an operator's own properties, as value checks read them
    stand_in.is_property_set = lambda name: name in props or name in stand_in.assigned
    stand_in.assigned = set()
    for base in reversed(cls.__mro__):
        if base.__module__.startswith("bpy"):
            continue
        for attr, value in vars(base).items():
            if isinstance(value, types.FunctionType) and attr != method:  # invoke() calls execute()
                setattr(stand_in, attr, types.MethodType(value, stand_in))
            elif not attr.startswith("__") and not callable(value) and not hasattr(stand_in, attr):
                setattr(stand_in, attr, value)
    if method == "invoke":
        return cls.invoke(stand_in, context or bpy.context, None), reports
    return cls.execute(stand_in, context or bpy.context), reports


class _StandIn(types.SimpleNamespace):
    """Properties an operator assigns count as set from then on, as with a real operator."""

    def __setattr__(self, name, value):
        if "assigned" in vars(self):
            self.assigned.add(name)
        super().__setattr__(name, value)
