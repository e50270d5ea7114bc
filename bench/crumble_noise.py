"""Crumble-noise benchmark: the lattice lookup the painter crumbles prints with, against two
Perlin noises in its place, and its share of the painter's time.

- 4 M texels (2048 x 2048, 7 mm apart), lumps a 4 cm deep print's wall wide: core.sole's
  crumble_noise (two value noises on a fixed 256 x 256 lattice) against two core.noise_perlin
  perlin_2d calls (median of 3 each);
- the painter on the footprint benchmark's 12-print walk at 4k texels (numpy only, the
  walker's prints planned by core.paths): its time, and the share cProfile gives crumble_noise.

Prints the table and appends it to bench/RESULTS.md with the command that made it.
Run: .venv/bin/python bench/crumble_noise.py [--no-append]
"""

import argparse
import cProfile
import pathlib
import pstats
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from bench.footprints import FRAMES, STANCE, STRIDE, walk_path  # noqa: E402
from core import footprints as painter  # noqa: E402
from core import noise_perlin, paths  # noqa: E402
from core import sole as soles  # noqa: E402
from devtools import results  # noqa: E402

TEXELS, TEXEL = 2048, 0.007  # metres
DEPTH = 0.04  # metres: the demo's prints


def walk_inputs(resolution):
    """The 12-print walk as the painter takes it, with the demo's sole (4 cm deep, slumped, crumbled)."""
    frame, positions = walk_path()
    steps = paths.plan_steps(positions, frame, STRIDE, STANCE)
    sole = soles.dry_sand_sole(DEPTH)
    centres = steps["contact"][:, :2]
    up = np.tile([0.0, 0.0, 1.0], (len(centres), 1))
    forward, lateral = paths.print_axes(steps["forward"], up, steps["side"])
    region = painter.fit_region(centres, sole.reach(), resolution, margin=0.05 + sole.rim_width)
    return (centres, forward, lateral, steps["birth"], np.ones(len(centres)), region, sole, FRAMES)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    lump = soles.wall_width(DEPTH)
    x, y = np.meshgrid((np.arange(TEXELS) + 0.5) * TEXEL, (np.arange(TEXELS) + 0.5) * TEXEL)
    lattice = results.median_seconds(lambda: soles.crumble_noise(x, y, lump), 3)[0]
    perlin = results.median_seconds(lambda: (noise_perlin.perlin_2d(x / lump, y / lump),
                                             noise_perlin.perlin_2d(x / lump + 37.1, y / lump + 11.3)), 3)[0]
    inputs = walk_inputs(4096)
    paint = results.median_seconds(lambda: painter.paint(*inputs), 3)[0]
    profile = cProfile.Profile()
    profile.enable()
    painter.paint(*inputs)
    profile.disable()
    stats = pstats.Stats(profile).stats
    total = max(row[3] for row in stats.values())  # the painter's cumulative time
    noise = sum(row[3] for key, row in stats.items() if key[2] == "crumble_noise")
    region = inputs[5]
    lines = [results.heading("Crumble noise"),
             f"{results.machine()}. {TEXELS}x{TEXELS} texels {TEXEL * 1000:g} mm apart, lumps "
             f"{lump * 100:.1f} cm (the wall of a {DEPTH * 100:g} cm deep print); median of 3.\n",
             "| what | seconds |", "|---|---|",
             f"| crumble_noise (lattice lookup, two noises) | {lattice:.3f} |",
             f"| two perlin_2d in its place | {perlin:.3f} ({perlin / lattice:.1f}x) |",
             f"| painter, 12-print walk, {region.width}x{region.height} texels | {paint:.3f} |",
             f"| crumble_noise inside it (cProfile) | {noise:.3f} of {total:.3f} "
             f"({100 * noise / total:.0f} %) |"]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
