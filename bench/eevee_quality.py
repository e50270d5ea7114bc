"""EEVEE quality benchmark: render time against error for the demo in EEVEE, to choose its presets.

The demo frames at 160x90 in EEVEE through the compositor rebuilt for EEVEE (god rays, gated blur),
against EEVEE's own converged render of each frame (REFERENCE_SAMPLES, the finest volume tiles):
the error a preset leaves is EEVEE's noise and volume blur, not the engines' difference (that is
bench/eevee.py). Rows: render samples, and the volume tile size at a few sample counts; each
EEVEE preset. EEVEE's sampling is deterministic (no seed), so the reference's own noise cannot be
measured by a second render and is not taken out. EEVEE runs on software OpenGL here: the times
are a CPU's. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/eevee_quality.py [--frames 120 200] [--presets-only] [--no-append]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (160, 90)
FRAMES = (120, 200)  # the poster's and the effects bench's frames: walker, prints, sun, clouds in view
REFERENCE_SAMPLES, REFERENCE_TILE = 256, "2"
SAMPLES = (1, 2, 4, 8, 16, 32, 64)
TILES = ("8", "4", "2")


def render(readback, scene, presets, settings):
    presets.apply_eevee(scene, settings)
    started = time.perf_counter()
    pixels = readback.render(scene)[..., :3]
    return time.perf_counter() - started, pixels


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, nargs="+", default=list(FRAMES))
    parser.add_argument("--presets-only", action="store_true", help="the reference and the presets only")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import importlib

    import bpy

    session.install_dev_extension(root)
    presets = importlib.import_module(f"{session.MODULE}.addon.presets")
    from devtools import readback

    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}  # the tree EEVEE's passes feed
    white = 2.0 ** -scene.view_settings.exposure
    flags = (["--frames", *map(str, args.frames)] if args.frames != list(FRAMES) else []) + \
        (["--presets-only"] if args.presets_only else [])
    lines = [results.heading("EEVEE quality", flags),
             f"{results.machine()}, EEVEE on software OpenGL. Demo frames at {RESOLUTION[0]}x"
             f"{RESOLUTION[1]} through the compositor built for EEVEE; reference: EEVEE at "
             f"{REFERENCE_SAMPLES} samples, volume tiles of {REFERENCE_TILE} px; RMSE of linear pixels "
             f"clipped at the display's white ({white:g}). The first render of a frame also compiles "
             "shaders: a warm-up render comes first and is not counted.\n",
             "| frame | settings | render s | RMSE |", "|---|---|---|---|"]
    for frame in args.frames:
        scene.frame_set(frame)
        render(readback, scene, presets, {"taa_render_samples": 1})  # shaders compiled
        reference_seconds, reference = render(readback, scene, presets, {
            "taa_render_samples": REFERENCE_SAMPLES, "volumetric_tile_size": REFERENCE_TILE})
        rows = [("reference", reference_seconds, 0.0)]
        grid = [] if args.presets_only else \
            [(s, "8") for s in SAMPLES] + [(s, t) for s in (4, 16, 64) for t in TILES if t != "8"]
        for samples, tile in grid:
            seconds, pixels = render(readback, scene, presets,
                                     {"taa_render_samples": samples, "volumetric_tile_size": tile})
            rows.append((f"{samples} samples, tiles {tile} px", seconds,
                         results.clipped_rmse(pixels, reference, white)))
            print(frame, rows[-1], flush=True)
        for name, settings in presets.EEVEE_PRESETS.items():
            seconds, pixels = render(readback, scene, presets, settings)
            rows.append((f"preset {name.lower()}: " + ", ".join(f"{k}={v}" for k, v in settings.items()),
                         seconds, results.clipped_rmse(pixels, reference, white)))
            print(frame, rows[-1], flush=True)
        lines += [f"| {frame} | {label} | {seconds:.2f} | {error:.5f} |" for label, seconds, error in rows]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
