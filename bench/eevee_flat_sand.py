"""Our sand on flat ground, EEVEE against Cycles, where an artist points a camera: toward a low
sun, away from it, and across a high one, with the haze and without.

A 400 m plane of Add Sand Material's default sand (Physical, lit glints, ripples), Add
Atmosphere's sun at each elevation and azimuth (0: straight ahead of the camera, 180: behind it),
a camera 1.6 m up pitched 15 degrees down with a 35 mm lens, RESOLUTION, Cycles at CYCLES_SAMPLES
without denoising and EEVEE at EEVEE_SAMPLES (Clamp Surface Indirect 0, as the EEVEE presets
set). Per case, the near half of the frame's mean (linear): Cycles', and EEVEE's over Cycles'
(R / G / B and luminance) with the sand's EEVEE output and without it.
Appends to bench/RESULTS.md.

Run: .venv/bin/python bench/eevee_flat_sand.py [--no-append]
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
CYCLES_SAMPLES, EEVEE_SAMPLES = 32, 16
CASES = ((8.0, 180.0), (8.0, 0.0), (15.0, 150.0), (55.0, 30.0))  # sun elevation, azimuth (degrees)
NEAR = slice(0, RESOLUTION[1] // 2)  # rows bottom-up: the near half of the ground
LUMINANCE = (0.2126, 0.7152, 0.0722)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    sandscape = session.start()
    import bpy
    import numpy as np

    from devtools import readback, scenes

    session.reset()
    scene = bpy.context.scene
    readback.cycles_scene(scene, RESOLUTION, CYCLES_SAMPLES)
    scene.eevee.taa_render_samples, scene.eevee.clamp_surface_indirect = EEVEE_SAMPLES, 0.0
    bpy.ops.mesh.primitive_plane_add(size=400)
    ground = bpy.context.active_object
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    material = ground.active_material
    scenes.camera("PERSP", location=(0.0, 0.0, 1.6), rotation=(math.radians(75), 0.0, 0.0), lens=35)
    air = scene.sandscape_atmosphere
    luminance = np.array(LUMINANCE)

    def mean(engine):
        scene.render.engine = engine
        return readback.render(scene)[NEAR, :, :3].reshape(-1, 3).astype(np.float64).mean(0)

    def ratio(eevee, cycles):
        channels = " / ".join(f"{v:.3f}" for v in eevee / cycles)
        return f"{channels} ({eevee @ luminance / (cycles @ luminance):.3f})"

    lines = [results.heading("EEVEE beside Cycles: our sand on flat ground"),
             f"{results.machine()}; {RESOLUTION[0]}x{RESOLUTION[1]}, Cycles {CYCLES_SAMPLES} spp, EEVEE "
             f"{EEVEE_SAMPLES} samples; camera 1.6 m up pitched 15° down, 35 mm; the near half of the "
             "frame. EEVEE's mean over Cycles' (R / G / B (luminance)).", "",
             "| sun | azimuth | haze | Cycles | EEVEE, the sand's EEVEE output | EEVEE without it "
             "| seconds |",
             "|---|---|---|---|---|---|---|"]
    for elevation, azimuth in CASES:
        for haze in (True, False):
            started = time.perf_counter()
            air.sun_elevation, air.sun_azimuth = math.radians(elevation), math.radians(azimuth)
            air.use_haze = haze
            if haze:
                air.property_unset("density")
            else:
                air.density = 0.0
            assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
            assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}  # its EEVEE output back
            scene.frame_set(1)
            cycles, balanced = mean("CYCLES"), mean("BLENDER_EEVEE")
            sandscape.addon.sand_eevee.attach(material, scene, sandscape.addon.sand.look_node(material), None)
            plain = mean("BLENDER_EEVEE")
            lines.append(f"| {elevation:g}° | {azimuth:g}° | {'on' if haze else 'off'} | "
                         f"{' / '.join(f'{v:.2f}' for v in cycles)} | {ratio(balanced, cycles)} | "
                         f"{ratio(plain, cycles)} | {time.perf_counter() - started:.0f} |")
            print(lines[-1], flush=True)
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
