"""The dune operator: Add (or Update) Dunes from scene.sandscape_dunes or its own arguments."""

import os

import bpy

from ..addon import dunes, ownership, units
from ..addon.progress import Progress
from ..addon.settings import DUNE_LIMITS, dune_fields
from ..core import dunes as model
from .base import SandscapeOperator, SceneSettings, editable_problem, value_problem

FIELDS = dune_fields(True)
SPACING_CELLS = 4  # a dune narrower than this many cells falls between the vertices
FALLBACK_MEMORY = 8 * 2**30  # bytes, where the system does not say what it has


def available_memory():
    """Physical memory in bytes (os.sysconf where the system has it), else FALLBACK_MEMORY."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return FALLBACK_MEMORY


class SANDSCAPE_OT_add_dunes(SceneSettings, SandscapeOperator, bpy.types.Operator):
    """Add or regrow a dune field shaped by the scene's wind (Werner's slab model): slip faces at the
    angle of repose, barchans or ridges by the sand supply, land out to the horizon"""

    bl_idname = "sandscape.add_dunes"
    bl_label = "Add Dunes"
    LIMITS = DUNE_LIMITS
    __annotations__ = dict(FIELDS)

    def settings(self, context):
        """Every field: the value passed, else the scene's setting (scene units)."""
        stored = context.scene.sandscape_dunes
        values = {}
        for name in FIELDS:
            if not self.properties.is_property_set(name):
                setattr(self, name, getattr(stored, name))
            values[name] = getattr(self, name)
        return values

    def problem(self, context, values):
        scene = context.scene
        problem = value_problem(self.properties, self.LIMITS, scene)
        if problem:
            return problem
        if dunes.wind_angle(scene, dunes.scene_dunes(scene)) is None:
            return ("The scene's wind has no direction across the ground (Atmosphere > Wind): the dunes "
                    "grow along it")
        cell = values["cell_size"]
        if cell > min(values["width"], values["depth"]):
            extent = " x ".join(units.length_text(scene, values[k]) for k in ("width", "depth"))
            return f"Cell Size {units.length_text(scene, cell)} is larger than the field ({extent})"
        if values["spacing"] < SPACING_CELLS * cell:
            return (f"Dune Spacing must be at least {SPACING_CELLS} cells "
                    f"({units.length_text(scene, SPACING_CELLS * cell)} at this Cell Size), got "
                    f"{units.length_text(scene, values['spacing'])}")
        scale = units.metres_per_unit(scene)
        width, depth, cell_m = values["width"] * scale, values["depth"] * scale, cell * scale
        count = model.vertex_count(width, depth, cell_m)
        needed, have = model.estimated_bytes(width, depth, cell_m), available_memory()
        if count >= 2**31 // 4 or needed > have / 2:
            return (f"{count:,} vertices would need about {needed / 2**30:.1f} GB (this machine has "
                    f"{have / 2**30:.0f} GB): raise Cell Size or make the field smaller")
        ring = ownership.scene_object(scene, ownership.DUNE_HORIZON)
        return editable_problem(dunes.scene_dunes(scene), ring)

    def execute(self, context):
        scene = context.scene
        values, problem = self.checked_settings(context)
        if problem:
            return self.fail(problem)
        self.remember(scene.sandscape_dunes, values)
        progress = Progress("Sandscape dunes", context)
        try:
            facts = dunes.build(scene, values, progress)
        finally:
            seconds = progress.end()
        dunes.activate(context, facts["field"])
        self.report({"INFO"}, report_line(scene, values, facts, seconds))
        for warning in (facts["camera_problem"], facts["relay_problem"]):
            if warning:
                self.report({"WARNING"}, warning)
        return {"FINISHED"}


def report_line(scene, values, facts, seconds):
    def length(metres):
        return units.length_text(scene, units.to_units(scene, metres))

    ring = ""
    if facts.get("ring_vertices"):
        reach = units.length_text(scene, values["horizon"])
        ring = f"; land out to {reach} ({facts['ring_vertices']:,} vertices)"
    relaid = f"; laid {' and '.join(facts['relaid'])} on the new sand" if facts["relaid"] else ""
    return (f"Dune field '{facts['field'].name}': {facts['vertices']:,} vertices, dunes "
            f"{length(facts['spacing'])} apart and up to {length(facts['height'])} high, grown from "
            f"{facts['slabs']:,} slabs along the scene's wind{ring}{relaid}; {seconds:.1f} s")


classes = (SANDSCAPE_OT_add_dunes,)
