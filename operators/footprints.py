"""Footprint operators: emit prints along the walker's path, paint them into the sand.

They read the scene's Sandscape footprint settings (scene.sandscape_footprints).
"""

import bpy

from ..addon import footprints, units
from ..addon.settings import SandscapeFootprintSettings, SandscapeWalkerEntry
from .base import SandscapeOperator, value_problem


def _terrain_set(context):
    terrain = context.scene.sandscape_footprints.terrain
    return terrain is not None and terrain.type == "MESH"


def _source_set(context):
    settings = context.scene.sandscape_footprints
    source = settings.walker if settings.source == "WALKER" else settings.particle_object
    return source is not None


def settings_problem(scene, settings):
    """An error message for settings that cannot make prints, or None (values, then the data)."""
    problem = value_problem(settings, SandscapeFootprintSettings.LIMITS, scene)
    if problem:
        return problem
    source = settings.walker if settings.source == "WALKER" else settings.particle_object
    terrain = settings.terrain
    if source == terrain:
        return "The walker cannot be the terrain"
    if settings.source == "PARTICLES" and not source.particle_systems:
        return f"'{source.name}' has no particle system"
    start, end = footprints.frame_range(scene, settings)
    if end < start:
        return f"The frame range {start}..{end} is empty"
    for index, entry in enumerate(settings.more_walkers):
        problem = value_problem(entry, SandscapeWalkerEntry.LIMITS, scene)
        if problem:
            return f"More walkers, row {index + 1}: {problem}"
        if entry.walker is not None and entry.walker == terrain:
            return f"More walkers, row {index + 1}: the walker cannot be the terrain"
    if settings.foot_width > settings.foot_length:
        return (f"Foot width ({units.length_text(scene, settings.foot_width)}) must be at most the length "
                f"({units.length_text(scene, settings.foot_length)})")
    return footprints.terrain_problem(terrain)


class _FootprintOperator(SandscapeOperator):
    POLL = (
        (_source_set, "No walker (or particle emitter): set one in the Footprints panel, or use Add Walker"),
        (_terrain_set, "No terrain: choose the mesh the prints go into in the Footprints panel"),
    )

    def run(self, context, task):
        scene = context.scene
        settings = scene.sandscape_footprints
        problem = settings_problem(scene, settings)
        if problem:
            return self.fail(problem)
        window_manager = context.window_manager
        window_manager.progress_begin(0, 100)
        try:
            result = task(scene, settings, lambda f: window_manager.progress_update(int(100 * f)))
        except footprints.FootprintError as error:
            return self.fail(str(error))
        finally:
            window_manager.progress_end()
        self.report({"INFO"}, self.summary(scene, result))
        return {"FINISHED"}


class SANDSCAPE_OT_emit_footprints(_FootprintOperator, bpy.types.Operator):
    """Place one print per step along the walker's path, on the terrain (a point object you can edit)"""

    bl_idname = "sandscape.emit_footprints"
    bl_label = "Emit Footprints"

    def execute(self, context):
        return self.run(context, footprints.emit)

    def summary(self, _scene, result):
        obj, skipped = result
        off = f", {skipped} off the terrain skipped" if skipped else ""
        walked = f", the walker {obj['walked']}" if obj.get("walked") else ""
        return f"Emitted {len(obj.data.vertices)} prints into '{obj.name}'{off}{walked}"


class SANDSCAPE_OT_paint_footprints(_FootprintOperator, bpy.types.Operator):
    """Paint the prints into a height image and displace the terrain's sand with it (emits again when the
    walk, the terrain or the settings changed)"""

    bl_idname = "sandscape.paint_footprints"
    bl_label = "Paint Footprints"

    def execute(self, context):
        return self.run(context, footprints.paint)

    def summary(self, scene, result):
        width, height = result["size"]
        off = f", {result['skipped']} off the terrain skipped" if result["skipped"] else ""
        return (f"Painted {result['prints']} prints{off} into '{result['image'].name}' {width}x{height} "
                f"({units.length_text(scene, result['texel'])} texels, {result['memory'] / 2**20:.1f} MiB in "
                f"memory, {result['packed'] / 2**20:.2f} MiB packed)")


class SANDSCAPE_OT_footprint_walker_add(SandscapeOperator, bpy.types.Operator):
    """Add a row for another walker on the same terrain (the active object, if it is not the terrain or
    a walker already): its prints go into the same height image"""

    bl_idname = "sandscape.footprint_walker_add"
    bl_label = "Add Another Walker"

    def execute(self, context):
        settings = context.scene.sandscape_footprints
        entry = settings.more_walkers.add()
        candidate = context.active_object
        taken = {settings.terrain, settings.walker, *(e.walker for e in settings.more_walkers)}
        if candidate is not None and candidate not in taken:
            entry.walker = candidate
        name = f"'{entry.walker.name}'" if entry.walker else "an empty row (pick the walker in it)"
        self.report({"INFO"}, f"More walkers: {name}, row {len(settings.more_walkers)}")
        return {"FINISHED"}


class SANDSCAPE_OT_footprint_walker_remove(SandscapeOperator, bpy.types.Operator):
    """Remove a row from the other walkers (its prints go at the next paint)"""

    bl_idname = "sandscape.footprint_walker_remove"
    bl_label = "Remove Walker"

    index: bpy.props.IntProperty(name="Row", default=0, min=0)

    def execute(self, context):
        walkers = context.scene.sandscape_footprints.more_walkers
        if self.index >= len(walkers):
            return self.fail(f"There is no row {self.index + 1} among the other walkers")
        walkers.remove(self.index)
        self.report({"INFO"}, f"Removed row {self.index + 1} of the other walkers")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_emit_footprints, SANDSCAPE_OT_paint_footprints, SANDSCAPE_OT_footprint_walker_add,
           SANDSCAPE_OT_footprint_walker_remove)
