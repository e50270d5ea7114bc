"""Footprint benchmark: Sandscape's painter against Blender's Dynamic Paint and a memory floor.

The walk: 12 prints at a 0.7 m stride over frames 1..120, straight across a 20 m plane,
alternating feet 0.2 m apart (the walk of shared/blender-5.0-notes.md).

Per resolution (1k, 2k, 4k texels along the longer side):
  - Sandscape painter: the numpy paint of the 12 prints (median of 5);
  - Sandscape operator: bpy.ops.sandscape.paint_footprints end to end (paint, EXR, pack, patch);
  - floor: one numpy write of an image of the same shape (np.full, median of 5);
  - throughput: 10,000 prints over the same region, prints per second;
  - Dynamic Paint: the same 12 prints stamped by two box feet (volume brushes) on a
    displace image canvas of res x res over the whole plane, baked for frames 1..120. The
    bake runs on a worker thread with no end signal in a bpy-module process, so it runs in a
    child process that waits for its worker thread to end and the 120th file to be complete.

Prints the table and appends it to bench/RESULTS.md with the command that made it.
Run: .venv/bin/python bench/footprints.py [--quick] [--no-append]
"""

import argparse
import functools
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from core import paths  # noqa: E402
from devtools import results, session  # noqa: E402

FRAMES = (1, 120)
STRIDE, STANCE, PRINTS = 0.7, 0.2, 12
PLANE = 20.0
FOOT = (0.27, 0.10, 0.06)  # Dynamic Paint box foot: length, width, height (metres)
PRESS = 0.02  # how far a Dynamic Paint foot sinks below the canvas


def walk_path(frames=FRAMES):
    length = STRIDE * (PRINTS - 1)
    frame = np.arange(frames[0], frames[1] + 1, dtype=float)
    x = -length / 2 + length * (frame - frames[0]) / (frames[1] - frames[0])
    return frame, np.stack([x, np.zeros_like(x), np.zeros_like(x)], 1)


def median_time(function, repeats=5):
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        function()
        times.append(time.perf_counter() - started)
    return statistics.median(times)


# ------------------------------------------------------------------ Dynamic Paint (child)

def dynamic_paint_child(resolution, output):
    """Bake Dynamic Paint for the walk; print a JSON line; leave through os._exit."""
    session.isolate()
    import bpy
    from bpy_extras import anim_utils

    session.reset()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = FRAMES
    bpy.ops.mesh.primitive_plane_add(size=PLANE)
    canvas = bpy.context.active_object
    modifier = canvas.modifiers.new("Dynamic Paint", "DYNAMIC_PAINT")
    modifier.ui_type = "CANVAS"
    with bpy.context.temp_override(object=canvas, active_object=canvas):
        bpy.ops.dpaint.type_toggle(type="CANVAS")
    surface = modifier.canvas_settings.canvas_surfaces[0]
    surface.surface_format = "IMAGE"
    surface.surface_type = "DISPLACE"
    surface.image_resolution = resolution
    surface.uv_layer = canvas.data.uv_layers[0].name
    surface.image_fileformat = "OPENEXR"
    surface.image_output_path = output
    surface.frame_start, surface.frame_end = FRAMES
    surface.depth_clamp = 0.05

    frame, positions = walk_path()
    steps = paths.plan_steps(positions, frame, STRIDE, STANCE)
    for side in (paths.LEFT, paths.RIGHT):
        bpy.ops.mesh.primitive_cube_add(size=1.0)
        foot = bpy.context.active_object
        foot.scale = (FOOT[0], FOOT[1], FOOT[2])
        brush = foot.modifiers.new("Dynamic Paint", "DYNAMIC_PAINT")
        brush.ui_type = "BRUSH"
        with bpy.context.temp_override(object=foot, active_object=foot):
            bpy.ops.dpaint.type_toggle(type="BRUSH")
        brush.brush_settings.paint_source = "VOLUME"
        mine = steps["side"] == side
        foot.location = (0.0, 0.0, 1.0)
        foot.keyframe_insert("location", frame=FRAMES[0] - 1)
        for contact, birth in zip(steps["contact"][mine], steps["birth"][mine], strict=True):
            down = int(round(birth))
            pressed = FOOT[2] / 2 - PRESS
            for key_frame, z in ((down - 1, 1.0), (down, pressed), (down + 3, pressed), (down + 4, 1.0)):
                foot.location = (contact[0], contact[1], z)
                foot.keyframe_insert("location", frame=key_frame)
        animation = foot.animation_data
        bag = anim_utils.action_get_channelbag_for_slot(animation.action, animation.action_slot)
        for curve in bag.fcurves:
            for key in curve.keyframe_points:
                key.interpolation = "CONSTANT"

    tasks = set(os.listdir("/proc/self/task"))
    started = time.perf_counter()
    with bpy.context.temp_override(object=canvas, active_object=canvas):
        bpy.ops.dpaint.bake()
    expected = FRAMES[1] - FRAMES[0] + 1
    seen_worker = False
    while time.perf_counter() - started < 1800:
        workers = set(os.listdir("/proc/self/task")) - tasks
        seen_worker = seen_worker or bool(workers)
        files = sorted(pathlib.Path(output).glob("*.exr"))
        if seen_worker and not workers and len(files) >= expected:
            break
        time.sleep(0.02)
    seconds = time.perf_counter() - started
    files = sorted(pathlib.Path(output).glob("*.exr"))
    print(json.dumps({"seconds": seconds, "files": len(files),
                      "bytes": sum(f.stat().st_size for f in files)}), flush=True)
    os._exit(0)


def run_dynamic_paint(resolution):
    with tempfile.TemporaryDirectory(prefix="sandscape-dpaint-") as output:
        result = subprocess.run([sys.executable, __file__, "--dynamic-paint-child", str(resolution), output],
                                capture_output=True, text=True, timeout=3600)
        for line in result.stdout.splitlines()[::-1]:
            if line.startswith("{"):
                return json.loads(line)
        raise RuntimeError(f"Dynamic Paint child failed:\n{result.stdout}\n{result.stderr}")


# ------------------------------------------------------------------ Sandscape

def sandscape_rows(resolutions):
    root = session.isolate()
    import bpy

    sandscape = session.install_dev_extension(root)
    painter = sandscape.core.footprints
    from devtools import scenes

    session.reset()
    frame, positions = walk_path()
    terrain = scenes.height_field(PLANE, 40, name="Sand")
    walker = scenes.keyframed_walker(lambda f: tuple(positions[int(f) - FRAMES[0]]), frame.astype(int))
    settings = scenes.footprint_settings(terrain, walker, FRAMES, stride=STRIDE, stance=STANCE)
    rows = []
    for resolution in resolutions:
        settings.resolution = resolution
        operator = median_time(lambda: bpy.ops.sandscape.paint_footprints(), repeats=3)
        points_obj = sandscape.addon.footprints.find_object(bpy.context.scene, "footprints", terrain)
        points = sandscape.addon.footprints.read_points(points_obj)
        assert len(points["co"]) == PRINTS
        sole = sandscape.addon.footprints.sole_from(settings)
        centres = points["co"][:, :2]
        region = painter.fit_region(centres, sole.reach(), resolution, margin=0.05 + sole.rim_width)
        forward, lateral = sandscape.addon.footprints.print_axes(points)

        def paint_walk(c=centres, f=forward, la=lateral, r=region, s=sole, p=points):
            return painter.paint(c, f, la, p["birth_frame"], p["depth_scale"], r, s, FRAMES)

        painted = median_time(paint_walk)
        shape = (region.height, region.width, 4)
        floor = median_time(lambda s=shape: np.full(s, 0.0, np.float32))
        canvas_floor = median_time(lambda r=resolution: np.full((r, r, 4), 0.0, np.float32), repeats=3)
        rng = np.random.default_rng(0)
        many = 10_000
        low = np.array([region.x0, region.y0]) + 0.2
        extent = np.array(region.extent()) - 0.4
        spread = low + rng.random((many, 2)) * extent
        angle = rng.uniform(0, 2 * np.pi, many)
        axis = np.stack([np.cos(angle), np.sin(angle)], 1)
        side = np.stack([-axis[:, 1], axis[:, 0]], 1)
        births = rng.uniform(*FRAMES, many)
        throughput_seconds = median_time(functools.partial(
            painter.paint, spread, axis, side, births, 1.0, region, sole, FRAMES), repeats=3)
        rows.append({"resolution": resolution, "shape": shape, "texel": region.texel, "painter": painted,
                     "operator": operator, "floor": floor, "canvas_floor": canvas_floor,
                     "prints_per_second": many / throughput_seconds})
        print(rows[-1], flush=True)
    return rows, bpy.app.version_string


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip Dynamic Paint at 4k (about 3 minutes)")
    parser.add_argument("--no-append", action="store_true", help="do not write bench/RESULTS.md")
    parser.add_argument("--dynamic-paint-child", nargs=2, metavar=("RES", "DIR"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.dynamic_paint_child:
        dynamic_paint_child(int(args.dynamic_paint_child[0]), args.dynamic_paint_child[1])
        return
    resolutions = (1024, 2048, 4096)
    rows, version = sandscape_rows(resolutions)
    for row in rows:
        if args.quick and row["resolution"] > 2048:
            row["dynamic_paint"] = None
            continue
        row["dynamic_paint"] = run_dynamic_paint(row["resolution"])
        print(row["resolution"], row["dynamic_paint"], flush=True)

    lines = [results.heading("Footprints", ["--quick"] if args.quick else []),
             f"{results.machine()}. Walk: "
             f"{PRINTS} prints, stride {STRIDE} m, frames {FRAMES[0]}..{FRAMES[1]}. "
             f"Dynamic Paint: two box feet (volume brushes) on a {PLANE:g} m displace canvas of res x res, "
             "EXR per frame. Sandscape: one print map over the prints' region (res texels along its "
             "longer side).\n",
             "Floors: one `np.full` write of the Sandscape map, and of a res x res RGBA float32 canvas like "
             "Dynamic Paint's.\n",
             "| Blender | res | Sandscape map | texel mm | painter s | map floor s | painter / map floor | "
             "canvas floor s | painter / canvas floor | operator s | prints/s (10k) | Dynamic Paint s | "
             "DP / painter | DP / operator |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for row in rows:
        dp = row["dynamic_paint"]
        dp_cells = ("not run (--quick)", "", "") if dp is None else (
            f"{dp['seconds']:.2f} ({dp['files']} files)", f"{dp['seconds'] / row['painter']:.0f}x",
            f"{dp['seconds'] / row['operator']:.0f}x")
        lines.append(f"| {version} | {row['resolution']} | {row['shape'][1]}x{row['shape'][0]} | "
                     f"{row['texel'] * 1000:.2f} | {row['painter']:.4f} | {row['floor']:.5f} | "
                     f"{row['painter'] / row['floor']:.1f} | "
                     f"{row['canvas_floor']:.4f} | {row['painter'] / row['canvas_floor']:.2f} | "
                     f"{row['operator']:.3f} | {row['prints_per_second']:.0f} | "
                     + " | ".join(dp_cells) + " |")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
