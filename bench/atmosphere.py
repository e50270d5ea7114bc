"""Atmosphere benchmark: render time against error for the wind-lifted dust volume.

Scene: 40 m of pale ground with three blocks, a low sun behind them, the Sandscape dust box
(Rayleigh air 0.03/m at 550 nm plus forward-scattering dust 0.02/m, g = 0.6, wind-lifted
patches), a perspective camera, Cycles CPU, no denoising.
Reference: the default unbiased volume sampling at REFERENCE_SPP samples.
Rows: unbiased at several sample counts; biased ray marching (volume_biased) at several
step rates and sample counts; the homogeneous fallback (wind off) against its own reference.
RMSE is over all pixels and channels, linear, with both images clipped at the reference's 99th
percentile: the sun is in frame, and camera rays see the sky's sun disc (added after the
2026-11-22 run), 0.1 % of the pixels at up to 1e5, whose noise alone made the unclipped RMSE
thousands. The sky itself is physical (median 3.8), so clipping at a display white of 1 would
clip 99.97 % of the frame.

Run: .venv/bin/python bench/atmosphere.py [--quick] [--no-append]
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

RESOLUTION = (96, 54)


def build_scene(bpy, readback, scenes, wind):
    session.reset()
    bpy.ops.mesh.primitive_plane_add(size=40.0)
    for x in (-3.0, 0.0, 3.0):
        bpy.ops.mesh.primitive_cube_add(size=1.0, location=(x, 6.0, 1.0))
        bpy.context.active_object.scale = (1.0, 1.0, 2.0)
    settings = bpy.context.scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth = math.radians(12.0), 0.0
    settings.density, settings.dust_density, settings.anisotropy = 0.03, 0.02, 0.6
    settings.use_wind, settings.margin = wind, 1.0
    settings.set_exposure = True
    bpy.ops.sandscape.add_atmosphere()
    scene = readback.cycles_scene(resolution=RESOLUTION, samples=16)
    scenes.camera("PERSP", location=(0.0, -6.0, 1.6), rotation=(math.radians(84), 0.0, 0.0), lens=24.0)
    return scene


def timed(readback, scene, samples, biased, step_rate=1.0):
    scene.cycles.samples = samples
    scene.cycles.volume_biased = biased
    scene.cycles.volume_step_rate = step_rate
    started = time.perf_counter()
    pixels = readback.render(scene)[..., :3]
    return time.perf_counter() - started, pixels


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a lower reference and fewer rows")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback, scenes

    reference_spp = 256 if args.quick else 1024
    counts = (4, 16, 64) if args.quick else (4, 16, 64, 256)
    rows = []
    for wind in (True, False):
        scene = build_scene(bpy, readback, scenes, wind)
        _, reference = timed(readback, scene, reference_spp, biased=False)
        white = float(np.percentile(reference, 99))
        label = "wind-lifted dust" if wind else "homogeneous fallback"
        cases = [("unbiased (default)", False, 1.0)]
        cases += [(f"biased, step rate {rate:g}", True, rate) for rate in ((1.0, 4.0) if wind else ())]
        for name, biased, rate in cases:
            for samples in counts:
                seconds, pixels = timed(readback, scene, samples, biased, rate)
                error = results.clipped_rmse(pixels, reference, white)
                rows.append((label, name, samples, seconds, error,
                             bool(np.isfinite(pixels).all())))
                print(rows[-1], flush=True)

    lines = [results.heading("Atmosphere", ["--quick"] if args.quick else []),
             f"{results.machine()}. {RESOLUTION[0]}x{RESOLUTION[1]}, no denoising. "
             f"Reference per scene: unbiased at {reference_spp} spp. RMSE of linear pixels clipped at "
             "the reference's 99th percentile (the sun disc, 0.1 % of the frame, reaches 1e5).\n",
             "| Blender | scene | volume sampling | spp | render s | RMSE | finite |",
             "|---|---|---|---|---|---|---|"]
    for label, name, samples, seconds, error, finite in rows:
        lines.append(f"| {results.blender()} | {label} | {name} | {samples} | {seconds:.2f} | {error:.5f} | "
                     f"{finite} |")
    lines += ["", *speedups(rows)]
    results.publish(lines, append=not args.no_append)


def speedups(rows):
    """For each biased row, the unbiased time at equal error (log-log interpolated), as a ratio."""
    out = []
    unbiased = sorted((error, seconds) for label, name, _, seconds, error, _ in rows
                      if label == "wind-lifted dust" and name.startswith("unbiased"))
    errors = np.log([e for e, _ in unbiased])  # ascending, as np.interp needs
    times = np.log([t for _, t in unbiased])
    for label, name, samples, seconds, error, _ in rows:
        if label != "wind-lifted dust" or not name.startswith("biased"):
            continue
        if not errors[0] <= np.log(error) <= errors[-1]:
            out.append(f"- {name}, {samples} spp: RMSE {error:.5f} is outside the unbiased rows' range.")
            continue
        equal = float(np.exp(np.interp(np.log(error), errors, times)))
        out.append(f"- {name}, {samples} spp: {seconds:.2f} s for RMSE {error:.5f}; unbiased needs "
                   f"{equal:.2f} s for the same error: {equal / seconds:.1f}x faster.")
    return out


if __name__ == "__main__":
    main()
