"""Clouds: set-up time, ray marching against Cycles' default volume sampling, bounces, phases.

A camera at the ground looking 5 degrees up under a 12 degree sun, the default cloud layer
(coverage 0.4, cumulus), 96x54 pixels, no denoising:

1. Set-up: Add Clouds' own time, and a 1-sample 16x9 render (the time before the first sample
   dominates it), ray-marched and unbiased.
2. Time against RMSE: ray-marched steps of 100, 200 and 400 m against unbiased (null scattering)
   sampling at 4, 16 and 64 samples, all against an unbiased reference; 4 volume bounces.
   Unbiased sampling costs a fixed set-up (Cycles builds its majorant structure by evaluating
   the shader) plus cheap samples, so its time for a given error is modelled from its rows as
   set-up + per-sample cost x samples, with RMSE = a / sqrt(samples), not interpolated.
3. Bounces: mean brightness of the sky half of the frame for 0..512 volume bounces (ray-marched,
   100 m), relative to 512.
4. Phase: dual-lobe Henyey-Greenstein against Mie at equal samples.
5. Demo: the demo frame's render time with and without its clouds.
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
BOUNCES = 4
BOUNCE_COUNTS = (0, 1, 2, 4, 8, 16, 32, 64, 128, 256, 512)
SKY = slice(RESOLUTION[1] // 2, None)  # rows are bottom-up: the upper half


def build(bpy, readback, scenes, **clouds):
    session.reset()
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=2000.0)
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.radians(95.0), 0.0, 0.0),
                           lens=20.0)
    camera.data.clip_end = 1e6
    settings = scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth = math.radians(12.0), math.radians(160.0)
    settings.density, settings.use_haze = 0.0, False
    settings.set_exposure = True
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


def compare_to_unbiased(rows):
    """Each ray-marched row against the unbiased time for its RMSE, from a fit to the unbiased rows."""
    unbiased = np.array([(spp, s, e) for n, spp, s, e, _ in rows if n.startswith("unbiased")])
    spp, seconds, errors = unbiased.T
    per_sample, setup = np.polyfit(spp, seconds, 1)
    noise = float(np.exp(np.mean(np.log(errors * np.sqrt(spp)))))  # RMSE = noise / sqrt(spp)
    lines = [f"Unbiased fit: {setup:.1f} s set-up + {per_sample:.3f} s per sample; RMSE = {noise:.4f} / "
             "sqrt(spp)."]
    for name, samples, seconds, error, _ in rows:
        if name.startswith("unbiased"):
            continue
        needed_spp = (noise / error) ** 2
        needed = setup + per_sample * needed_spp
        lines.append(f"- {name}, {samples} spp: {seconds:.2f} s for RMSE {error:.5f}; unbiased needs "
                     f"{needed_spp:.0f} spp, {needed:.1f} s: {needed / seconds:.1f}x.")
    return lines


def sampling(bpy, readback, scenes, quick):
    """Set-up and time against RMSE; returns the section's lines."""
    scene, setup = build(bpy, readback, scenes)
    scene.render.resolution_x, scene.render.resolution_y = 16, 9
    first, _ = render(readback, scene, 1)
    first_unbiased, _ = render(readback, scene, 1, biased=False)
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    reference_spp = 128 if quick else 256
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
    lines = [f"Reference: unbiased at {reference_spp} spp, {BOUNCES} volume bounces; RMSE of linear pixels "
             "clipped at its 99th percentile.\n",
             f"- Set-up: Add Clouds {setup:.3f} s; a 1-sample 16x9 render (mostly the time before the first "
             f"sample) {first:.2f} s ray-marched, {first_unbiased:.2f} s unbiased.\n",
             "| volume sampling | spp | render s | RMSE | finite |", "|---|---|---|---|---|"]
    lines += [f"| {name} | {samples} | {seconds:.2f} | {error:.5f} | {finite} |"
              for name, samples, seconds, error, finite in rows]
    return lines + ["", *compare_to_unbiased(rows), ""]


def bounces(bpy, readback, scenes, _quick):
    """Mean sky brightness against volume bounces; returns the section's lines."""
    scene, _ = build(bpy, readback, scenes, step=100.0)
    brightness = {}
    scene.cycles.max_bounces = 1024  # the total cap (12 by default) would stop the volume bounces
    for count in BOUNCE_COUNTS:
        scene.cycles.volume_bounces = count
        seconds, pixels = render(readback, scene, 16)
        brightness[count] = (float(pixels[SKY].mean()), seconds)
        print(count, brightness[count], flush=True)
    top = brightness[BOUNCE_COUNTS[-1]][0]
    lines = [f"| volume bounces | sky mean | vs {BOUNCE_COUNTS[-1]} bounces | render s (16 spp, 100 m) |",
             "|---|---|---|---|"]
    lines += [f"| {b} | {m:.4f} | {100 * (m / top - 1):+.1f} % | {s:.2f} |"
              for b, (m, s) in brightness.items()]
    return lines + [""]


def phases(bpy, readback, scenes, _quick):
    """Dual lobe against Mie at equal samples; returns the section's lines."""
    lines = ["| phase | render s (16 spp, 100 m) | sky mean |", "|---|---|---|"]
    for phase in ("DUAL_LOBE", "MIE"):
        scene, _ = build(bpy, readback, scenes, step=100.0, phase=phase)
        seconds, pixels = render(readback, scene, 16)
        lines.append(f"| {phase} | {seconds:.2f} | {float(pixels[SKY].mean()):.4f} |")
    return lines


def demo(bpy, readback, _scenes, _quick):
    """The demo's frame 120 at 320x180 (its own Preview preset) with and without its clouds."""
    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 180, 100
    scene.frame_set(120)
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    times = {}
    for shown in (True, False, True):  # the first render also compiles the kernels: keep the second
        layer.hide_render = not shown
        started = time.perf_counter()
        readback.render(scene)
        times[shown] = time.perf_counter() - started
    return [f"- Demo frame 120, 320x180, {scene.cycles.samples} spp, {scene.cycles.volume_bounces} volume "
            f"bounces: {times[True]:.1f} s with its clouds, {times[False]:.1f} s without "
            f"({times[True] / times[False]:.1f}x).", ""]


def _rss_mib():
    for line in pathlib.Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def _noise(readback, scene, renders=2):
    """(seconds of the faster render, per-render noise): renders with other seeds, RMSE of two
    renders' difference / sqrt 2, over display-clipped linear pixels (nan from one render)."""
    times, frames = [], []
    for seed in (1, 2)[:renders]:
        scene.cycles.seed = seed
        started = time.perf_counter()
        frames.append(np.clip(readback.render(scene)[..., :3], 0.0, 1.0))
        times.append(time.perf_counter() - started)
    if renders < 2:
        return times[0], float("nan")
    return min(times), float(np.sqrt(np.mean((frames[0] - frames[1]) ** 2) / 2.0))


def routes(bpy, readback, scenes, _quick):
    """Voxel grid against procedural: Add Clouds (with the geometry evaluated) on the default
    layer, the process memory it adds, and the demo frame with each route and without clouds."""
    from importlib import import_module

    clouds = import_module(f"{session.MODULE}.addon.clouds")
    lines = ["| route | Add Clouds s (default layer) | memory added MiB | voxels |", "|---|---|---|---|"]
    for evaluation in ("GRID", "PROCEDURAL"):
        scene, _ = build(bpy, readback, scenes, coverage=0.0)  # the bench's scene, no layer yet
        before = _rss_mib()
        started = time.perf_counter()
        bpy.ops.sandscape.add_clouds(evaluation=evaluation, coverage=0.4)
        bpy.context.evaluated_depsgraph_get().update()
        seconds = time.perf_counter() - started
        plan = clouds.plan(scene, clouds.scene_settings(scene))
        lines.append(f"| {evaluation.lower()} | {seconds:.2f} | {_rss_mib() - before:.0f} | "
                     f"{plan['voxels']:,} |")
        print(lines[-1], flush=True)
    lines += ["", "| demo frame 120, 320x180 | render s | noise (RMSE of one render) | vs no clouds |",
              "|---|---|---|---|"]
    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 180, 100
    scene.frame_set(120)
    readback.render(scene)  # compiles the kernels
    rows = {}
    for evaluation in (None, "GRID", "PROCEDURAL"):
        layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
        if evaluation is not None:
            scene.sandscape_clouds.evaluation = evaluation
            clouds.apply(scene, clouds.scene_settings(scene))
            layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
        layer.hide_render = evaluation is None
        rows[evaluation] = _noise(readback, scene, 1 if evaluation == "PROCEDURAL" else 2)
        print(evaluation, rows[evaluation], flush=True)
    bare = rows[None][0]
    for evaluation, (seconds, noise) in rows.items():
        lines.append(f"| {'no clouds' if evaluation is None else evaluation.lower()} | {seconds:.1f} | "
                     f"{noise:.4f} | {seconds / bare:.2f}x |")
    marched = "ray-marched" if scene.cycles.volume_biased else "unbiased"
    return lines + [f"\n{scene.cycles.samples} spp, {scene.cycles.volume_bounces} volume bounces, {marched} "
                    "volumes (the demo's own preset).", ""]


PARTS = {"sampling": sampling, "bounces": bounces, "phases": phases, "demo": demo, "routes": routes}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a lower reference")
    parser.add_argument("--part", choices=sorted(PARTS), action="append",
                        help="run only this part (repeatable); default: all")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback, scenes

    flags = (["--quick"] if args.quick else []) + [f"--part {part}" for part in args.part or ()]
    lines = [results.heading("Clouds", flags),
             f"{results.machine()}. {RESOLUTION[0]}x{RESOLUTION[1]}, no denoising, camera at the ground 5 "
             "degrees up, sun at 12 degrees, default layer (coverage 0.4, cumulus).\n"]
    for name in args.part or PARTS:
        lines += PARTS[name](bpy, readback, scenes, args.quick)
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
