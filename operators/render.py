"""Render operators: measured quality presets, and the optimizer that switches off what cannot
reach the image."""

import bpy
from bpy.props import BoolProperty, EnumProperty

from ..addon import optimize, presets
from .base import SandscapeOperator


class SANDSCAPE_OT_optimize_scene(SandscapeOperator, bpy.types.Operator):
    """Switch off what does not reach the image: empty volumes, idle adaptive subdivision, dark glints,
    god rays with the sun out of view, idle volume bounces, passes nothing reads"""

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
        self.report({"INFO"}, f"{verb} {len(found)} thing(s)" if found else "Nothing to switch off")
        return {"FINISHED"}


class SANDSCAPE_OT_apply_quality_preset(SandscapeOperator, bpy.types.Operator):
    """Set Cycles' samples, denoising, volume sampling, dicing and bounces from a measured quality preset
    (a scene in another engine is switched to Cycles, and the report says so)"""

    bl_idname = "sandscape.apply_quality_preset"
    bl_label = "Apply Quality Preset"

    preset: EnumProperty(
        name="Preset", default="PREVIEW",
        items=(("DRAFT", "Draft", "16 samples, denoised but for the glints: composition and light"),
               ("PREVIEW", "Preview", "72 samples, denoised but for the glints: clean enough to judge "
                "glints and prints (the demo still)"),
               ("FINAL", "Final", "512 samples, adaptive, unbiased volumes, Cycles' denoiser with the "
                "glints kept raw: Blender's recipe, a fraction of its samples")))

    sharp_pixels: BoolProperty(
        name="Sharp Pixel Filter", default=False,
        description="A half-pixel pixel filter: glints converge about four times faster, the image is "
                    "crisper, and the denoised sand keeps less of its finest detail")

    def execute(self, context):
        settings = dict(presets.PRESETS[self.preset], **(presets.SHARP_FILTER if self.sharp_pixels else {}))
        engine = context.scene.render.engine
        if engine != "CYCLES":  # the presets are Cycles settings, measured in Cycles
            context.scene.render.engine = "CYCLES"
        presets.apply(context.scene, settings)
        switched = ""
        if engine != "CYCLES":
            switched = f"; render engine {engine.replace('BLENDER_', '').title()} → Cycles"
        self.report({"INFO"}, f"{self.preset.title()} (Cycles): "
                    + ", ".join(f"{k} {v}" for k, v in settings.items()) + switched)
        return {"FINISHED"}


classes = (SANDSCAPE_OT_optimize_scene, SANDSCAPE_OT_apply_quality_preset)
