"""Clouds: set-up time, ray marching against Cycles' default volume sampling, bounces, phases.

A camera at the ground looking 5 degrees up under a 12 degree sun, the default cloud layer
(coverage 0.4, cumulus), 64x36 pixels, no denoising:

1. Set-up: Add Clouds' own time, and a 1-sample 16x9 render (the time before the first sample
   dominates it).
2. Time against RMSE: ray-marched steps of 100, 200 and 400 m against unbiased (null scattering)
   sampling at 4, 16 and 64 samples, all against an unbiased reference; 4 volume bounces.
3. Bounces: mean brightness of the sky half of the frame for 0..32 volume bounces (ray-marched,
   100 m), relative to 32.
4. Phase: dual-lobe Henyey-Greenstein against Mie at equal samples.
"""

import argparse
import math
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (64, 36)
BOUNCES = 4


def build(bpy, readback, scenes, **clouds):
    session.reset()
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=2000.0)
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.radians(95.0), 0.0, 0.0),
                           lens=20.0)
    camera.data.clip_end = 1e6
    settings = scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth = math.radians(12.0), math.radians(160.0)
    settings.density = 0.0
    readback.cycles_scene(scene, RESOLUTION, 1)
    bpy.ops.sandscape.add_atmosphere()
    started = time.perf_counter()
    bpy.ops.sandscape.add_clouds(**clouds)
    setup = time.perf_counter() - started
    scene.cycles.volume_bounces = BOUNCES
    return scene, setup


def render(readback, scene, samples, biased=True):
    scene.cycles.samples = samples
    scene.cycles.volume_biased = biased
    started = time.perf_counter()
    pixels = readback.render(scene)[..., :3]
    return time.perf_counter() - started, pixels


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a lower reference")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback, scenes

    scene, setup = build(bpy, readback, scenes)
    scene.render.resolution_x, scene.render.resolution_y = 16, 9
    first, _ = render(readback, scene, 1)
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    reference_spp = 64 if args.quick else 256
    _, reference = render(readback, scene, reference_spp, biased=False)
    white = float(np.percentile(reference, 99))
    rows = []
    for name, biased, step in [("unbiased (default)", False, None), ("ray-marched, 100 m", True, 100.0),
                               ("ray-marched, 200 m", True, 200.0), ("ray-marched, 400 m", True, 400.0)]:
        if step is not None:
            scene, _ = build(bpy, readback, scenes, step=step)
        for samples in (4, 16, 64):
            seconds, pixels = render(readback, scene, samples, biased)
            rows.append((name, samples, seconds, results.clipped_rmse(pixels, reference, white),
                         bool(np.isfinite(pixels).all())))
            print(rows[-1], flush=True)

    scene, _ = build(bpy, readback, scenes, step=100.0)
    sky = slice(RESOLUTION[1] // 2, None)  # rows are bottom-up: the upper half
    brightness = {}
    for bounces in (0, 1, 2, 4, 8, 16, 32):
        scene.cycles.volume_bounces = bounces
        seconds, pixels = render(readback, scene, 32)
        brightness[bounces] = (float(pixels[sky].mean()), seconds)
        print(bounces, brightness[bounces], flush=True)
    phases = {}
    for phase in ("DUAL_LOBE", "MIE"):
        scene, _ = build(bpy, readback, scenes, step=100.0, phase=phase)
        seconds, pixels = render(readback, scene, 16)
        phases[phase] = (seconds, float(pixels[sky].mean()))

    lines = [results.heading("Clouds", ["--quick"] if args.quick else []),
             f"{results.machine()}. {RESOLUTION[0]}x{RESOLUTION[1]}, no denoising, camera at the ground 5 "
             f"degrees up, sun at 12 degrees, default layer (coverage 0.4, cumulus). Reference: unbiased at "
             f"{reference_spp} spp, {BOUNCES} volume bounces; RMSE of linear pixels clipped at its 99th "
             "percentile.\n",
             f"- Set-up: Add Clouds {setup:.3f} s; a 1-sample 16x9 render (mostly the time before the first "
             f"sample) {first:.2f} s.\n",
             "| volume sampling | spp | render s | RMSE | finite |", "|---|---|---|---|---|"]
    lines += [f"| {name} | {samples} | {seconds:.2f} | {error:.5f} | {finite} |"
              for name, samples, seconds, error, finite in rows]
    unbiased = [(s, e) for n, _, s, e, _ in rows if n.startswith("unbiased")]
    lines.append("")
    for name, samples, seconds, error, _ in rows:
        if name.startswith("unbiased"):
            continue
        # Unbiased time for this error, interpolated in log-log between its samples.
        times, errors = zip(*unbiased, strict=True)
        if errors[-1] <= error <= errors[0]:
            needed = math.exp(np.interp(math.log(error), np.log(errors[::-1]), np.log(times[::-1])))
            lines.append(f"- {name}, {samples} spp: {seconds:.2f} s for RMSE {error:.5f}; unbiased needs "
                         f"{needed:.2f} s: {needed / seconds:.1f}x faster.")
        else:
            lines.append(f"- {name}, {samples} spp: RMSE {error:.5f} is outside the unbiased rows' range.")
    top = brightness[32][0]
    lines += ["", "| volume bounces | sky mean | vs 32 bounces | render s (32 spp) |", "|---|---|---|---|"]
    lines += [f"| {b} | {m:.4f} | {100 * (m / top - 1):+.1f} % | {s:.2f} |"
              for b, (m, s) in brightness.items()]
    lines += ["", "| phase | render s (16 spp) | sky mean |", "|---|---|---|"]
    lines += [f"| {p} | {s:.2f} | {m:.4f} |" for p, (s, m) in phases.items()]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
