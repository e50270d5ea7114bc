"""Where the quality bench's reference noise lives: two raw unbiased halves of a demo frame
(bench/quality.py's reference), with the demo's glints and then without (Threshold 1).

Prints each pair's noise (clipped RMSE of the difference / 2), the share of pixels the glints
light and their share of the squared difference. About 8 minutes at the defaults.

Run: .venv/bin/python devtools/reference_noise.py [--frame 120] [--samples 512]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path[:0] = [str(REPO), str(REPO / "bench")]

from devtools import results, session  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frame", type=int, default=120)
    parser.add_argument("--samples", type=int, default=512, help="samples of each half")
    args = parser.parse_args(argv)
    sandscape, scene = session.demo_scene()
    presets, sand = sandscape.addon.presets, sandscape.addon.sand
    import quality

    from devtools import readback

    material = sand.find_sand_material(scene.sandscape_footprints.terrain)
    halves = {}
    for label in ("glints", "no glints"):
        if label == "no glints":
            sand.glint_node(material).inputs["Threshold"].default_value = 1.0
        started = time.perf_counter()
        *halves[label], white = quality.reference_halves(readback, scene, presets, args.frame,
                                                         2 * args.samples)
        noise = results.clipped_rmse(*halves[label], white) / 2
        print(f"{label}: reference noise {noise:.5f} ({time.perf_counter() - started:.0f} s)", flush=True)
    a, b, c, d = (np.minimum(h, white) for h in (*halves["glints"], *halves["no glints"]))
    squared = ((a - b) ** 2).sum(axis=-1)
    lit_by_glints = np.abs(a + b - c - d).max(axis=-1) > 0.05 * white
    print(f"pixels the glints light: {lit_by_glints.mean():.1%}, "
          f"their share of the squared difference: {squared[lit_by_glints].sum() / squared.sum():.1%}")
    plain = ((c - d) ** 2).sum(axis=-1)
    rows = plain.shape[0]  # readback rows run bottom-up
    noisiest = plain > np.quantile(plain, 0.95)
    print(f"without glints: lower half holds {plain[:rows // 2].sum() / plain.sum():.1%}, the noisiest 5 % "
          f"of pixels {plain[noisiest].sum() / plain.sum():.1%}")


if __name__ == "__main__":
    main()
