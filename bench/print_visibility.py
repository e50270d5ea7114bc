"""Print visibility at eye level: do the prints read in an artist's own shot, not only the demo's?

Flat sand, a walker crossing 10 m, its prints painted (5 cm deep, 6 mm rim), a sun 15 degrees up
from the side, and a camera at eye level (1.6 m) 3 m behind where the walk ends, looking along
the trail. Rendered with the prints and again with them flattened (depth and rim 0, same seed):
the pixels whose display value moves by more than PIXEL_CHANGE, in all and per metre of trail
distance band. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/print_visibility.py [--samples N] [--no-append]
"""

import argparse
import pathlib
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

BANDS = ((3.0, 6.0), (6.0, 9.0), (9.0, 13.0))  # metres from the camera along the trail


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=16)
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy  # noqa: F401 (after isolate: Blender's modules come with it)

    session.install_dev_extension(root)
    from devtools import print_shot as shot
    from devtools import readback

    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-prints-"))
    scene, camera = shot.build(args.samples)
    started = time.perf_counter()
    with_prints = readback.render_display(scene, out / "prints.png")
    seconds = time.perf_counter() - started
    print(f"print visibility: {seconds:.1f} s a render", flush=True)
    shot.flatten(scene)
    flat = readback.render_display(scene, out / "flat.png")
    changed = np.abs(with_prints[..., :3] - flat[..., :3]).max(axis=-1) > shot.PIXEL_CHANGE
    distance = shot.trail_distance(camera)
    rows = [(f"{low:g}-{high:g} m", int((changed & (distance >= low) & (distance < high)).sum()))
            for low, high in BANDS]
    print(f"prints change {changed.sum()} of {changed.size} pixels; {rows}", flush=True)
    flags = [f"--samples {args.samples}"] if args.samples != 16 else []
    width, height = shot.RESOLUTION
    lines = [results.heading("Print visibility", flags),
             f"{results.machine()}. Eye level (1.6 m), 3 m behind the end of a 10 m walk on flat sand, "
             f"sun 15° up from the side, {width}x{height}, {args.samples} spp denoised "
             f"({seconds:.1f} s a render); prints {shot.DEPTH * 100:g} cm deep, rim {shot.RIM * 1000:g} mm, "
             f"against the same shot with them flattened. A pixel changes when a display channel moves "
             f"by more than {shot.PIXEL_CHANGE}.\n",
             "| trail distance | pixels changed |", "|---|---|"]
    lines += [f"| {band} | {count} |" for band, count in rows]
    lines.append(f"| all | {int(changed.sum())} of {changed.size} |")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
