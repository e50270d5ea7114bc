"""An artist's glossy ground seen toward a low sun, EEVEE against Cycles: what of the gap is EEVEE's
light specular and what is Sandscape's world.

A 2 km plane with the artist's own Principled BSDF (Base Color 0.3, Roughness 0.5), Add
Atmosphere's sun at each elevation straight ahead of a camera 1.6 m up pitched 10 degrees down,
RESOLUTION, Cycles at CYCLES_SAMPLES and EEVEE at EEVEE_SAMPLES (Clamp Surface Indirect 0). Per
variant, EEVEE's mean over Cycles' (R, G, B) over the ground's lower quarter, and in its middle
columns (toward the sun) and at its sides:
- principled: the scene as Add Atmosphere leaves it;
- no specular: the Principled's Specular IOR Level 0 (its diffuse alone);
- lamp alone: a black world, the dust and far haze hidden (the lamp's light only);
- lamp alone, no shadow: the same, the lamp casting no shadow;
- lamp alone, GGX: the same, the Principled's GGX for its Multiscatter GGX;
- sky alone: the lamp's diffuse and specular off in both engines.
Appends to bench/RESULTS.md.

Run: .venv/bin/python bench/eevee_glossy_ground.py [--elevations 10 30] [--no-append]
"""

import argparse
import math
import pathlib
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (64, 36)
CYCLES_SAMPLES, EEVEE_SAMPLES = 64, 16
VARIANTS = ("principled", "no specular", "lamp alone", "lamp alone, no shadow", "lamp alone, GGX",
            "sky alone")
GROUND_ROWS = slice(0, 9)  # rows bottom-up: the near ground
MIDDLE = slice(24, 40)  # columns toward the sun


def build(bpy, sandscape, scenes, elevation, variant):
    session.reset()
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=2000)
    material = bpy.data.materials.new("Their Grey")
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.3, 0.3, 0.3, 1.0)
    if variant == "no specular":
        bsdf.inputs["Specular IOR Level"].default_value = 0.0
    if variant.endswith("GGX"):
        bsdf.distribution = "GGX"
    bpy.context.active_object.data.materials.append(material)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(elevation), math.radians(90.0)
    scenes.camera("PERSP", location=(0.0, 0.0, 1.6), rotation=(math.radians(80), 0.0, 0.0), lens=35)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    toward = sun.matrix_world.col[2]
    scene.camera.rotation_euler.z = math.atan2(toward[1], toward[0]) - math.pi / 2  # facing the sun
    if variant.startswith("lamp alone"):
        black = bpy.data.worlds.new("Black")
        black.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
        scene.world = black
        for obj in scene.objects:
            if obj.get("sandscape_object") in ("dust_volume", "far_haze"):
                obj.hide_render = True
        sun.data.use_shadow = not variant.endswith("no shadow")
    if variant == "sky alone":
        sun.visible_diffuse = sun.visible_glossy = False
        sun.data.diffuse_factor = sun.data.specular_factor = 0.0
    scene.eevee.taa_render_samples, scene.eevee.clamp_surface_indirect = EEVEE_SAMPLES, 0.0
    scene.frame_set(1)
    return scene


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elevations", type=float, nargs="+", default=[10.0, 30.0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    sandscape = session.start()
    import bpy
    import numpy as np

    from devtools import readback, scenes

    lines = [results.heading("EEVEE beside Cycles: an artist's glossy ground toward a low sun",
                             ["--elevations", *(f"{e:g}" for e in args.elevations)]),
             f"{results.machine()}; {RESOLUTION[0]}x{RESOLUTION[1]}, Cycles {CYCLES_SAMPLES} spp, EEVEE "
             f"{EEVEE_SAMPLES} samples. EEVEE's mean over Cycles' (R / G / B), the near ground's rows.", "",
             "| sun | variant | near ground | toward the sun | sides | Cycles' near ground | seconds |",
             "|---|---|---|---|---|---|---|"]
    for elevation in args.elevations:
        for variant in VARIANTS:
            started = time.perf_counter()
            scene = build(bpy, sandscape, scenes, elevation, variant)
            readback.cycles_scene(scene, RESOLUTION, CYCLES_SAMPLES)
            frames = {}
            for engine in ("CYCLES", "BLENDER_EEVEE"):
                scene.render.engine = engine
                frames[engine] = readback.render(scene)[GROUND_ROWS, :, :3].astype(np.float64)
            cycles, eevee = frames["CYCLES"], frames["BLENDER_EEVEE"]
            sides = np.r_[0:16, 48:64]

            def ratio(columns, cycles=cycles, eevee=eevee):
                value = eevee[:, columns].mean((0, 1)) / cycles[:, columns].mean((0, 1))
                return " / ".join(f"{v:.3f}" for v in value)

            lines.append(f"| {elevation:g}° | {variant} | {ratio(slice(None))} | {ratio(MIDDLE)} | "
                         f"{ratio(sides)} | {' / '.join(f'{v:.2f}' for v in cycles.mean((0, 1)))} | "
                         f"{time.perf_counter() - started:.0f} |")
            print(lines[-1], flush=True)
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
