"""Sparkles as pinpoints: how many pixels a sparkle covers, and how fast glint pixels converge:
sparkles put into their pixels (splat, with the sharp half-pixel filter and with Blender's
1.5 px one), glint cells sized to the pixel's footprint (cells, the fallback without a render
camera) and one cell per grain (unfiltered).

Scene: devtools.sparkles.sparkling_sand (a wide plane of sand, grains of 4 cm, a 30 degree sun
ahead, the camera 1.6 m up looking 20 degrees down). Sizes: sparkle pixels (over 4x the 5x5
median) grouped 8-connected, at 640x360 and 1280x720, 16 spp; the glints-off row counts what the
measure finds without glints. Convergence: RMSE of display values (linear scaled so the bare
sand's median is 0.5, clipped at 1) against a 1024 spp render of another seed, over the pixels
where that reference with glints differs from one without by more than 0.05, at 160x90.
Appends both tables to bench/RESULTS.md.

Run: .venv/bin/python bench/sparkles.py [--no-append]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

SIZES = ((640, 360), (1280, 720))
CONVERGENCE = (160, 90)
SPP = (16, 64, 256)
REFERENCE_SPP = 1024
GLINT_DIFFERENCE = 0.05
GRAIN = 0.04  # devtools.sparkles' Glint Size
SCENE = ("devtools/sparkles.py: a wide plane of sand, grains of 4 cm, a 30 degree sun ahead, the camera "
         "1.6 m up looking 20 degrees down; splat: sparkles put into their pixels (Glint Splat), with the "
         "sharp 0.5 px pixel filter or Blender's 1.5 px; cells: glint cells sized to the pixel's "
         "footprint "
         "(the splat off); unfiltered: one cell per grain. Sparkles: pixels over 4x the 5x5 median, "
         "8-connected, 16 spp.")
MODES = {  # name -> (pixel footprint, splat, pixel filter width)
    "splat": (True, True, 0.5), "splat, 1.5 px filter": (True, True, 1.5), "cells": (True, False, 1.5),
    "unfiltered": (False, False, 1.5),
}


def near_and_far(bpy, sandscape):
    """Pixels whose ground point lies where a grain spans more than a pixel's footprint, and the rest."""
    from devtools import scenes

    scene = bpy.context.scene
    origins, directions = scenes.camera_rays(scene.camera, *CONVERGENCE)
    down = np.where(directions[..., 2] < 0, directions[..., 2], -1e-9)
    distance = np.where(directions[..., 2] < 0, -origins[..., 2] / down, np.inf)
    footprint = distance * sandscape.addon.sparkle_footprint.pixel_angle(scene)
    near = footprint < GRAIN
    return near, ~near


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    parser.add_argument("--convergence", action="store_true", help="only the convergence table")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    sandscape = session.install_dev_extension(root)
    from devtools import readback, sparkles

    def render(resolution, mode, samples=16, seed=0, glints=True):
        session.reset()
        footprint, splat, filter_width = MODES[mode]
        scene = sparkles.sparkling_sand(sandscape, resolution, footprint, samples, seed)
        scene.cycles.filter_width = filter_width
        node = sandscape.addon.sand.glint_node(bpy.context.scene.objects["Plane"].active_material)
        if not splat:
            for name in ("Resolution X", "Resolution Y"):
                node.inputs[name].driver_remove("default_value")
                node.inputs[name].default_value = 0.0
        if not glints:
            node.inputs["Threshold"].default_value = 1.0
        started = time.perf_counter()
        pixels = readback.render(scene)
        return pixels, time.perf_counter() - started

    size_rows = []
    for resolution in () if args.convergence else SIZES:
        for mode, glints in (*((mode, True) for mode in MODES), ("splat", False)):
            pixels, seconds = render(resolution, mode, glints=glints)
            mode = mode if glints else "off"
            found = sparkles.sparkle_sizes(pixels)
            mean = f"{found.mean():.2f}" if found.size else "-"
            single = f"{np.mean(found == 1):.0%}" if found.size else "-"
            largest = found.max() if found.size else 0
            frame = f"{resolution[0]}x{resolution[1]}"
            size_rows.append(f"| {frame} | {mode} | {found.size} | {mean} | {single} | {largest} | "
                             f"{seconds:.1f} |")
            print(size_rows[-1], flush=True)

    rmse_rows = []
    for mode in MODES:
        reference, _ = render(CONVERGENCE, mode, REFERENCE_SPP, seed=99)
        bands = near_and_far(bpy, sandscape)
        bare, _ = render(CONVERGENCE, mode, REFERENCE_SPP, seed=99, glints=False)
        # The scene keeps exposure 0: display values with the bare sand's median at 0.5.
        scale = 0.5 / float(np.median(bare[..., :3]))
        reference, bare = reference[..., :3] * scale, bare[..., :3] * scale
        glints = np.abs(np.minimum(reference, 1) - np.minimum(bare, 1)).max(-1) > GLINT_DIFFERENCE
        for spp in SPP:
            pixels, seconds = render(CONVERGENCE, mode, spp)
            pixels = pixels[..., :3] * scale
            errors = [results.clipped_rmse(pixels[glints & band], reference[glints & band], 1.0)
                      for band in (np.ones_like(glints), *bands)]
            frame = results.clipped_rmse(pixels, reference, 1.0)
            share = f"{glints.mean():.2%}"
            rmse_rows.append(f"| {mode} | {spp} | {seconds:.2f} | " + " | ".join(f"{e:.4f}" for e in errors)
                             + f" | {frame:.4f} | {share} |")
            print(rmse_rows[-1], flush=True)

    lines = [results.heading("Sparkles as pinpoints"),
             f"{results.machine()}. {SCENE}\n",
             "| frame | glints | sparkles | pixels each | single-pixel | largest | render s |",
             "|---|---|---|---|---|---|---|", *size_rows, "",
             f"Glint pixels against {REFERENCE_SPP} spp (another seed), {CONVERGENCE[0]}x{CONVERGENCE[1]}:\n",
             "| glints | spp | render s | glint RMSE | near (grain > pixel) | far | frame RMSE "
             "| glint pixels |",
             "|---|---|---|---|---|---|---|---|", *rmse_rows]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
