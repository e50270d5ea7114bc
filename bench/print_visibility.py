"""Print visibility at eye level: do the prints read in an artist's own shot, not only the demo's?

Flat sand, a walker crossing 10 m, its prints painted (5 cm deep, 6 mm rim), a sun 15 degrees up
from the side, and a camera at eye level (1.6 m) 3 m behind where the walk ends, looking along
the trail. Rendered with the prints and again with them flattened (depth and rim 0, same seed):
the pixels whose display value moves by more than PIXEL_CHANGE, in all and per metre of trail
distance band. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/print_visibility.py [--samples N] [--no-append]
"""

import argparse
import math
import pathlib
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (480, 270)
PIXEL_CHANGE = 0.05
DEPTH, RIM = 0.05, 0.006
BANDS = ((3.0, 6.0), (6.0, 9.0), (9.0, 13.0))  # metres from the camera along the trail


def build(bpy, readback, scenes, samples):
    session.reset()
    terrain = scenes.height_field(40.0, 40, name="Their Sand")
    walker = scenes.keyframed_walker(lambda f: (0.0, -5.0 + 10.0 * (f - 1) / 168.0, 0.0), range(1, 170))
    scenes.footprint_settings(terrain, walker, (1, 169), depth=DEPTH, rim=RIM, resolution=2048)
    bpy.context.view_layer.objects.active = terrain
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    camera = scenes.camera("PERSP", location=(0.0, 8.0, 1.6),
                           rotation=(math.radians(80.0), 0.0, math.radians(180.0)), lens=35.0)
    camera.data.clip_end = 1e5
    scene = bpy.context.scene
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(15.0), math.radians(90.0)
    air.density, air.dust_density = 0.003, 0.002  # the demo's air
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    readback.cycles_scene(scene, RESOLUTION, samples)  # a new file renders with EEVEE
    scene.cycles.use_denoising = True
    scene.frame_set(169)
    return scene, camera


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=16)
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback, scenes

    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-prints-"))
    scene, camera = build(bpy, readback, scenes, args.samples)
    started = time.perf_counter()
    with_prints = readback.render_display(scene, out / "prints.png")
    seconds = time.perf_counter() - started
    print(f"print visibility: {seconds:.1f} s a render", flush=True)
    steps = scene.sandscape_footprints
    steps.depth = steps.rim = 0.0
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    scene.frame_set(169)
    flat = readback.render_display(scene, out / "flat.png")
    changed = np.abs(with_prints[..., :3] - flat[..., :3]).max(axis=-1) > PIXEL_CHANGE
    # Each changed pixel's distance along the trail: where its ray meets the ground.
    origins, directions = scenes.camera_rays(camera, *RESOLUTION)
    t = -origins[..., 2] / np.where(directions[..., 2] < 0, directions[..., 2], -1e-9)
    distance = np.where(directions[..., 2] < 0, t * np.hypot(directions[..., 0], directions[..., 1]), np.inf)
    rows = [(f"{low:g}-{high:g} m", int((changed & (distance >= low) & (distance < high)).sum()))
            for low, high in BANDS]
    print(f"prints change {changed.sum()} of {changed.size} pixels; {rows}", flush=True)
    flags = [f"--samples {args.samples}"] if args.samples != 16 else []
    lines = [results.heading("Print visibility", flags),
             f"{results.machine()}. Eye level (1.6 m), 3 m behind the end of a 10 m walk on flat sand, "
             f"sun 15° up from the side, {RESOLUTION[0]}x{RESOLUTION[1]}, {args.samples} spp denoised "
             f"({seconds:.1f} s a render); prints {DEPTH * 100:g} cm deep, rim {RIM * 1000:g} mm, against "
             f"the same shot with them flattened. A pixel changes when a display channel moves by more "
             f"than {PIXEL_CHANGE}.\n",
             "| trail distance | pixels changed |", "|---|---|"]
    lines += [f"| {band} | {count} |" for band, count in rows]
    lines.append(f"| all | {int(changed.sum())} of {changed.size} |")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
