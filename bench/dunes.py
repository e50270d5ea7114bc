"""Dune field benchmark: Add Dunes' run time and peak memory beside what the field measures.

Cases: the operator's defaults (200 x 200 m at 0.5 m cells, dunes 30 m apart, 3 % sand, the
horizon ring out to 20 km); a 1 km x 1 km field at 1 m cells; scarce sand (barchans); two
winds 120 degrees apart (linear dunes). Each runs in a fresh Python (a clean Blender, nothing
kept from another case), so the peak resident memory it reports is its own: the process's peak
less its peak before the operator ran. Beside the cost, the field's own figures: the steepest
triangle, the median slip face and windward slope (the lee and windward triangles as
tests/test_dune_model.py classes them) and the spacing against the one asked for.
Goals (issue 23): the default field in at most 20 s; 1 km x 1 km at 1 m in at most 60 s and 2 GB.

Run: .venv/bin/python bench/dunes.py [--case NAME ...] [--no-append]
"""

import argparse
import json
import math
import pathlib
import resource
import subprocess
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

CASES = {
    "default": {},
    "1 km": {"width": 1000.0, "depth": 1000.0, "cell_size": 1.0},
    "barchans": {"sand_supply": 0.8},
    "linear": {"use_second_wind": True, "second_wind_angle": math.radians(120.0), "second_wind_share": 0.5},
}
GOALS = {"default": (20.0, None), "1 km": (60.0, 2048.0)}


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def field_figures(field, wind_angle, spacing_asked, spacing_found):
    from core import dune_surface

    count = len(field.data.vertices)
    vertices = np.empty(count * 3, np.float32)
    field.data.vertices.foreach_get("co", vertices)
    vertices = vertices.reshape(-1, 3).astype(np.float64)
    loops = np.empty(len(field.data.polygons) * 4, np.int32)
    field.data.polygons.foreach_get("vertices", loops)
    triangles = dune_surface.quad_triangles(loops.reshape(-1, 4))
    normal = np.cross(vertices[triangles[:, 1]] - vertices[triangles[:, 0]],
                      vertices[triangles[:, 2]] - vertices[triangles[:, 0]])
    normal *= np.sign(normal[:, 2:3])
    flat = np.hypot(normal[:, 0], normal[:, 1])
    slope = np.degrees(np.arctan2(flat, normal[:, 2]))
    along = (normal[:, :2] @ np.array([math.cos(wind_angle), math.sin(wind_angle)])) / np.maximum(flat, 1e-12)
    slip, windward = (along > 0.5) & (slope > 20.0), (along < -0.5) & (slope > 2.0)
    return {"max_slope": float(slope.max()), "slip": float(np.median(slope[slip])) if slip.any() else None,
            "windward": float(np.median(slope[windward])) if windward.any() else None,
            "spacing_error": spacing_found / spacing_asked - 1.0}


def run_case(name):
    """One case in this (fresh) process; prints its figures as one JSON line."""
    root = session.isolate()
    import bpy

    from core import dunes

    session.install_dev_extension(root)
    session.reset()
    values = CASES[name]
    before = peak_mib()
    started = time.perf_counter()
    assert bpy.ops.sandscape.add_dunes(**values) == {"FINISHED"}
    seconds = time.perf_counter() - started
    peak = peak_mib() - before
    scene = bpy.context.scene
    field = bpy.context.active_object
    ring = next(o for o in scene.objects if o.get("sandscape_object") == "dune_horizon")
    settings = scene.sandscape_dunes
    wind = scene.sandscape_atmosphere.wind
    _, facts = dunes.grow_surface(settings.width, settings.depth, settings.cell_size, settings.spacing,
                                  settings.sand_supply, settings.seed, math.atan2(wind[1], wind[0]),
                                  settings.second_wind_angle if settings.use_second_wind else None,
                                  settings.second_wind_share)  # kept from the run: costs nothing
    figures = field_figures(field, math.atan2(wind[1], wind[0]) + facts["frame"], settings.spacing,
                            facts["spacing"])
    print(json.dumps({"case": name, "seconds": seconds, "peak_mib": peak, "field": len(field.data.vertices),
                      "ring": len(ring.data.vertices), "lattice": f"{facts['coarse']}² coarse, "
                      f"{facts['fine']}² fine", **figures}))


def row(figures):
    time_goal, memory_goal = GOALS.get(figures["case"], (None, None))
    verdicts = []
    if time_goal is not None:
        verdicts.append(f"≤ {time_goal:g} s: {'met' if figures['seconds'] <= time_goal else 'missed'}")
    if memory_goal is not None:
        met = figures["peak_mib"] <= memory_goal
        verdicts.append(f"≤ {memory_goal / 1024:g} GB: {'met' if met else 'missed'}")

    def degrees(value):
        return "-" if value is None else f"{value:.1f}°"

    return (f"| {figures['case']} | {figures['lattice']} | {figures['field']:,} + {figures['ring']:,} | "
            f"{figures['seconds']:.1f} | {figures['peak_mib']:.0f} | {degrees(figures['max_slope'])} | "
            f"{degrees(figures['slip'])} | {degrees(figures['windward'])} | "
            f"{100 * figures['spacing_error']:+.0f} % | "
            f"{'; '.join(verdicts) or '-'} |")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", action="append", choices=sorted(CASES), help="run only these cases")
    parser.add_argument("--no-append", action="store_true", help="print only, leave bench/RESULTS.md")
    parser.add_argument("--one", help=argparse.SUPPRESS)  # a single case in a fresh process
    args = parser.parse_args(argv)
    if args.one:
        run_case(args.one)
        return
    rows = []
    for name in args.case or list(CASES):
        done = subprocess.run([sys.executable, __file__, "--one", name], capture_output=True, text=True,
                              check=True)
        line = next(text for text in done.stdout.splitlines() if text.startswith("{"))
        rows.append(row(json.loads(line)))
        print(rows[-1], flush=True)
    root = session.isolate()
    import bpy  # noqa: F401 (for the heading's Blender version)

    del root
    flags = [f"--case {name!r}" for name in args.case or ()]
    results.publish([
        results.heading("Dunes", flags),
        f"{results.machine()}. Add Dunes from an empty file, each case in a fresh process (nothing kept "
        "between cases); peak is the process's peak resident memory less its peak before the operator. "
        "Slopes of the field's triangles (both ways of cutting each quad): steepest, median slip face "
        "(downwind-facing, over 20°) and median windward (upwind-facing, over 2°); spacing as the "
        "run measured it across the crests, whichever way they run, against the setting.",
        "",
        "| case | lattice | vertices (field + ring) | s | peak MiB | steepest | slip face | windward | "
        "spacing | goal |",
        "|---|---|---|---|---|---|---|---|---|---|",
        *rows,
    ], append=not args.no_append)


if __name__ == "__main__":
    main()
