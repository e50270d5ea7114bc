"""What every Sandscape operator shares: poll() for the structure a button needs (with a poll
message saying what is missing), value checks before any data changes, one-line reports.

poll() answers "can this run here at all?" (a mesh is active, a terrain is set); values that
are out of range, NaN or inf are execute()'s to refuse, with an ERROR report and CANCELLED.
"""

import functools
import math

from ..addon import ownership, shot, units
from ..node_groups import versions


class SandscapeOperator:
    bl_options = {"REGISTER", "UNDO"}

    def __init_subclass__(cls, **kwargs):
        """Each operator also reports what happened to node groups it did not rebuild (a newer
        file's kept, an artist's edited one kept beside ours): node_groups/versions.py."""
        super().__init_subclass__(**kwargs)
        execute = cls.__dict__.get("execute")
        if execute is None:
            return

        @functools.wraps(execute)
        def execute_and_report(self, context):
            versions.drain_notes()  # notes from before this run are not this run's
            result = execute(self, context)
            for note in versions.drain_notes():
                self.report({"INFO"}, f"Node groups: {note}")
            return result
        cls.execute = execute_and_report

    # (condition(context) -> bool, message) pairs that poll() checks in order.
    POLL = ()

    @classmethod
    def poll(cls, context):
        if context.scene is None:
            return False
        if context.scene.library is not None or context.scene.override_library is not None:
            cls.poll_message_set("The scene is linked from a library: Sandscape changes only local scenes")
            return False
        for condition, message in cls.POLL:
            if not condition(context):
                cls.poll_message_set(message)
                return False
        return True

    def fail(self, message):
        self.report({"ERROR"}, message)
        return {"CANCELLED"}


class SceneSettings:
    """For an operator whose arguments are also a scene's settings (Add Clouds, Add Dunes): its
    settings(context) gives every value (passed, else the scene's) and problem(context, values)
    what is wrong with them; the scene keeps what a run used."""

    def checked_settings(self, context):
        """(values, the first problem with them or None)."""
        values = self.settings(context)
        return values, self.problem(context, values)

    def remember(self, stored, values):
        for name, value in values.items():
            self.store(stored, name, value)

    def store(self, stored, name, value):
        setattr(stored, name, value)


# Conditions shared by several operators' POLL tables.
def active_mesh(context):
    obj = context.active_object
    return obj is not None and obj.type == "MESH"


def has_camera(context):
    return shot.scene_camera(context.scene) is not None  # an empty can be the scene camera


def value_problem(settings, limits, scene):
    """The first numeric setting that is not finite or not within its limits, as a sentence.

    limits: property name -> (low, high), inclusive, in metres for lengths and speeds (which
    the settings hold in scene units) and in the property's own unit otherwise.
    """
    for prop in settings.bl_rna.properties:
        if prop.type not in {"FLOAT", "INT"} or prop.identifier == "rna_type":
            continue
        raw = getattr(settings, prop.identifier)
        values = list(raw) if getattr(prop, "is_array", False) else [raw]
        physical = prop.unit in {"LENGTH", "VELOCITY"}
        scale = units.metres_per_unit(scene) if physical else 1.0
        shown = [v * scale for v in values]
        text = ", ".join(_number(v, prop, scene) for v in values)
        if not all(math.isfinite(v) for v in shown):
            return f"{prop.name} must be a number, got {text}"
        low, high = limits.get(prop.identifier, (-math.inf, math.inf))
        if not all(_within(v, low, high) for v in shown):
            if physical:
                low_text, high_text = (units.length_text(scene, v / scale) for v in (low, high))
                bounds = f"{low_text} .. {high_text}"
            elif prop.subtype == "ANGLE":
                bounds = f"{math.degrees(low):g}° .. {math.degrees(high):g}°"
            else:
                bounds = f"{low:g} .. {high:g}"
            return f"{prop.name} must lie in {bounds}, got {text}"
    return None


def _within(value, low, high):
    """low <= value <= high, give or take single-precision storage (90 degrees reads back 4e-8
    above pi / 2)."""
    def slack(bound):
        return 1e-6 * abs(bound) if math.isfinite(bound) else 0.0
    return low - slack(low) <= value <= high + slack(high)


def _number(value, prop, scene):
    if math.isnan(value):
        return str(value)
    if abs(value) >= units.FLOAT_MAX:
        return str(math.copysign(math.inf, value))
    if prop.unit == "LENGTH":
        return units.length_text(scene, value)
    if prop.subtype == "ANGLE":
        return f"{math.degrees(value):g}°"
    return f"{value:g}"


def editable_problem(*blocks):
    """Why one of these data-blocks cannot take Sandscape's changes, or None."""
    for block in blocks:
        problem = ownership.not_editable(block)
        if problem:
            return problem
    return None
