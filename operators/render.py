"""Render operators: measured quality presets, and the optimizer that switches off what cannot
reach the image."""

import bpy
from bpy.props import BoolProperty, EnumProperty

from ..addon import optimize, presets, shot
from ..addon.post_passes import ENGINE_NAMES
from .base import SandscapeOperator


class SANDSCAPE_OT_optimize_scene(SandscapeOperator, bpy.types.Operator):
    """Switch off what does not reach the image in the scene's engine: empty volumes, idle adaptive
    subdivision, dark glints, god rays with the sun out of view, idle volume bounces, passes nothing
    reads (in EEVEE, Cycles' settings are left alone)"""

    bl_idname = "sandscape.optimize_scene"
    bl_label = "Optimize Scene"

    dry_run: BoolProperty(name="Dry Run", default=False,
                          description="Only list what would be switched off; change nothing")

    def execute(self, context):
        found = optimize.decisions(context.scene)
        if self.dry_run:
            for decision in found:
                self.report({"INFO"}, "would: " + decision.message)
        else:
            # One decision can free another (a rebuilt compositor reads fewer passes): repeat.
            batch, found = found, []
            for _ in range(3):
                for decision in batch:
                    decision.apply()
                    self.report({"INFO"}, decision.message)
                found += batch
                batch = optimize.decisions(context.scene)
                if not batch:
                    break
        verb = "Would switch off" if self.dry_run else "Switched off"
        engine = " in EEVEE (Cycles' settings left alone)" if optimize.for_eevee(context.scene) else ""
        self.report({"INFO"}, f"{verb} {len(found)} thing(s){engine}" if found else
                    f"Nothing to switch off{engine}")
        return {"FINISHED"}


class SANDSCAPE_OT_apply_quality_preset(SandscapeOperator, bpy.types.Operator):
    """Set the render settings of a measured quality preset for the scene's engine: Cycles' samples,
    denoising, volume sampling, dicing and bounces, or EEVEE's samples and volume tiles (Workbench,
    or another engine asked for, is switched to, and the report says so)"""

    bl_idname = "sandscape.apply_quality_preset"
    bl_label = "Apply Quality Preset"

    preset: EnumProperty(
        name="Preset", default="PREVIEW",
        items=(("DRAFT", "Draft", "Cycles: 16 samples, denoised but for the glints; EEVEE: its draft "
                "samples and volume tiles. Composition and light"),
               ("PREVIEW", "Preview", "Cycles: 72 samples, denoised but for the glints; EEVEE: more samples, "
                "finer volume tiles. Clean enough to judge glints and prints (the demo still)"),
               ("FINAL", "Final", "Cycles: 512 samples, adaptive, unbiased volumes, Cycles' denoiser with "
                "the glints kept raw; EEVEE: its converged samples and finest volume tiles")))

    sharp_pixels: BoolProperty(
        name="Sharp Pixel Filter", default=False,
        description="Cycles: a half-pixel pixel filter: glints converge about four times faster, the image "
                    "is crisper, and the denoised sand keeps less of its finest detail")

    engine: EnumProperty(
        name="Engine", default="SCENE",
        items=(("SCENE", "Scene's Engine", "The preset for the engine the scene renders with (Workbench: "
                "Cycles)"),
               ("CYCLES", "Cycles", "Cycles' preset, switching the scene to Cycles"),
               ("EEVEE", "EEVEE", "EEVEE's preset, switching the scene to EEVEE")))

    def execute(self, context):
        scene = context.scene
        before = scene.render.engine
        wanted = self.engine if self.engine != "SCENE" else "EEVEE" if before == "BLENDER_EEVEE" else "CYCLES"
        scene.render.engine = "BLENDER_EEVEE" if wanted == "EEVEE" else "CYCLES"
        switched = ""
        if scene.render.engine != before:
            # As Blender spells them ("Eevee" from the identifier was not); other engines by theirs
            was = ENGINE_NAMES.get(before, before.replace("BLENDER_", "").title())
            switched = f"; render engine {was} → {'EEVEE' if wanted == 'EEVEE' else 'Cycles'}"
        if wanted == "EEVEE":  # EEVEE's own presets, measured in EEVEE
            settings = presets.EEVEE_PRESETS[self.preset]
            presets.apply_eevee(scene, settings)
            ignored = "; the sharp pixel filter is Cycles' and was left out" if self.sharp_pixels else ""
            self.report({"INFO"}, f"{self.preset.title()} (EEVEE): "
                        + ", ".join(f"{k} {v}" for k, v in settings.items()) + switched + ignored)
            if depth := shot.eevee_depth_warning(scene):
                self.report({"WARNING"}, depth)
            return {"FINISHED"}
        settings = dict(presets.PRESETS[self.preset], **(presets.SHARP_FILTER if self.sharp_pixels else {}))
        presets.apply(scene, settings)
        self.report({"INFO"}, f"{self.preset.title()} (Cycles): "
                    + ", ".join(f"{k} {v}" for k, v in settings.items()) + switched)
        return {"FINISHED"}


classes = (SANDSCAPE_OT_optimize_scene, SANDSCAPE_OT_apply_quality_preset)
