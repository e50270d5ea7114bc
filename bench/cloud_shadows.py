"""EEVEE's cloud shadow map (core.cloud_shadows): time to make it against its error, by steps along
the sun's ray and texels, against a map of 128 steps. Numpy (the clouds' twin), nothing
rendered. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/cloud_shadows.py [--no-append]
"""

import argparse
import math
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from core import atmosphere as air  # noqa: E402
from core import cloud_shadows as twin  # noqa: E402
from core import clouds  # noqa: E402
from devtools import results  # noqa: E402

# Add Clouds' defaults (cumulus, 6 km weather, 1.2 km shapes) over a 16 km box, coverage 0.45.
P = {"base": 1500.0, "thickness": 1200.0, "coverage": 0.45, "map_scale": 6000.0, "shape_scale": 1200.0,
     "detail_scale": 200.0, "erosion": 0.5, "curl": 0.5, "skew": 0.0, "density": 0.02, "precipitation": 0.0,
     "cloud_type": 0.5, "seed": 2, "wind": (0.0, 0.0, 0.0), "time": 0.0, "region": (0, 0, 16000, 16000, 800)}
BOX = (0.0, 0.0, 16000.0, 16000.0)
ELEVATIONS = (45.0, 6.0)
STEPS = (8, 16, 32, 48)
REFERENCE_STEPS = 128
TEXELS = (96, 192)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    density = lambda points: clouds.density(points, P)  # noqa: E731
    rows = []
    for elevation in ELEVATIONS:
        to_sun = air.sun_direction(math.radians(elevation), math.radians(30.0))
        for texels in TEXELS:
            reference = twin.transmittance(density, BOX, P["base"], P["thickness"], to_sun, REFERENCE_STEPS,
                                           texels)
            for steps in STEPS:
                started = time.perf_counter()
                light = twin.transmittance(density, BOX, P["base"], P["thickness"], to_sun, steps, texels)
                seconds = time.perf_counter() - started
                flipped = float(np.mean((light < 0.5) != (reference < 0.5)))  # what EEVEE's layer shows
                error, shaded = float(np.abs(light - reference).mean()), float(np.mean(reference < 0.5))
                rows.append((elevation, texels, steps, seconds, error, flipped, shaded))
                print("cloud shadow bench:", rows[-1], flush=True)
    lines = [results.heading("EEVEE cloud shadow map: steps and texels"),
             f"{results.machine()}. The map over a 16 km box at Add Clouds' defaults (coverage 0.45), "
             f"against {REFERENCE_STEPS} steps at the same texels; flipped: texels on the other side of the "
             "layer's half-light threshold (what EEVEE's shadow shows).", "",
             "| sun | texels | steps | time | mean abs error | texels flipped (in / out of shadow) "
             "| in shadow |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {e:.0f}° | {t} | {s} | {sec:.2f} s | {err:.4f} | {flip:.2%} | {shade:.2%} |"
              for e, t, s, sec, err, flip, shade in rows]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
