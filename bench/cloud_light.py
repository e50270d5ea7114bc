"""The clouds' light on level ground, Cycles against the twin EEVEE's lighting world holds
(core/cloud_light.py): on the weather map the table was measured on (the demo's seed) and on
maps it was not (other seeds), so the row says how far one layer's light strays from the
table's. Measured as devtools/cloud_light_table.py measures (a white plane 30 km square under
the layer, or --plane metres, the lamp's direct light kept off it): the change the layer makes
to the light on level ground against the twin's, per channel, as a share of the clear sky's
light. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/cloud_light.py [--seeds 51 7 23] [--plane 30000] [--no-append]
"""

import argparse
import math
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import cloud_light_table, results, session  # noqa: E402

CASES = ((6, 0.4), (30, 0.7), (15, 0.3))  # sun elevation in degrees, coverage
SEEDS = (51, 7, 23)  # the demo's (the table's) first


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=list(SEEDS))
    parser.add_argument("--plane", type=float, default=cloud_light_table.PLANE_SIZE,
                        help="the plane's side in metres (the table's: the mean under 30 km of sky; "
                        "6000: one place's)")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    _, scene = session.demo_scene()
    import bpy

    from core import cloud_light
    from devtools import readback, scenes

    cloud_light_table.PLANE_SIZE = args.plane
    scene.frame_set(cloud_light_table.FRAME)
    camera = cloud_light_table.probe(bpy, scene, scenes)
    stored = scene.sandscape_clouds
    depth = stored.density * stored.thickness
    rows = []
    for seed in args.seeds:
        stored.seed = seed
        for degrees, coverage in CASES:
            start = time.perf_counter()
            row = cloud_light_table.measure(bpy, np, readback, scene, camera, degrees, coverage,
                                            stored.density)
            sun, with_, without = (np.asarray(row[k]) for k in ("sun", "with", "without"))
            twin = cloud_light.level_change(math.radians(degrees), coverage, depth, sun, without)
            measured = with_ - without
            error = np.abs(twin - measured).max() / without.max()
            none = np.abs(measured).max() / without.max()  # EEVEE's world with no cloud light
            seconds = time.perf_counter() - start
            rows.append((seed, degrees, coverage, measured, twin, without, error, none, seconds))
            print("cloud light bench:", rows[-1], flush=True)
    publish(args, rows)


def publish(args, rows):
    def colour(c):
        return "(" + ", ".join(f"{v:+.2f}" for v in c) + ")"

    flags = [f"--seeds {' '.join(map(str, args.seeds))}"] if args.seeds != list(SEEDS) else []
    flags += [f"--plane {args.plane:g}"] if args.plane != 30000.0 else []
    lines = [results.heading("Cloud light: Cycles against the twin of EEVEE's lighting world", flags),
             f"{results.machine()}. The demo at frame {cloud_light_table.FRAME}, its cumulus layer at "
             f"the seed and coverage given, a white plane {args.plane / 1000:g} km square under it (its "
             f"irradiance, the lamp's direct light kept off it, {cloud_light_table.PIXELS}² pixels at "
             f"{cloud_light_table.SAMPLES} spp). "
             "Change: with the layer less without it, per channel; error: the largest channel's "
             "difference over the clear sky's brightest channel; without: the same with no cloud light "
             "(the change itself). The table was measured on seed 51.\n",
             "| seed | sun | coverage | Cycles' change | twin's change | clear sky | error | without "
             "| time |",
             "|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {seed} | {degrees}° | {coverage:.1f} | {colour(m)} | {colour(t)} | {colour(c)} | "
              f"{error:.1%} | {none:.1%} | {seconds:.0f} s |"
              for seed, degrees, coverage, m, t, c, error, none, seconds in rows]
    errors, nones = [r[6] for r in rows], [r[7] for r in rows]
    held_out = [r[6] for r in rows if r[0] != 51]
    held_out_none = [r[7] for r in rows if r[0] != 51]
    lines += ["", f"Largest error {max(errors):.1%}, mean {np.mean(errors):.1%} (without cloud light "
              f"{np.mean(nones):.1%}); on the seeds the table did not see, mean "
              f"{np.mean(held_out) if held_out else float('nan'):.1%} (without "
              f"{np.mean(held_out_none) if held_out_none else float('nan'):.1%}), largest "
              f"{max(held_out) if held_out else float('nan'):.1%}.", ""]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
