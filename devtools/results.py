"""Benchmark output: print the table, and append it to bench/RESULTS.md unless told not to."""

import datetime
import os
import pathlib
import platform
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
RESULTS = REPO / "bench" / "RESULTS.md"


def publish(lines, append=True):
    text = "\n".join(lines) + "\n"
    print(text)
    if append:
        with open(RESULTS, "a") as results:
            results.write(text)


def blender():
    """The Blender the bench ran on, as it names itself ("5.2.3 LTS")."""
    import bpy

    return bpy.app.version_string


def heading(title, flags=()):
    """A section heading: what, when, on which Blender, and the command that ran it.

    The command names the venv's python, which is what picks the Blender (.venv: 5.2, .venv-5.0: 5.0).
    """
    prefix = pathlib.Path(sys.prefix)
    python = prefix.relative_to(REPO) / "bin" / "python" if REPO in prefix.parents else pathlib.Path(
        sys.executable)
    script = pathlib.Path(sys.argv[0]).resolve()
    script = script.relative_to(REPO) if REPO in script.parents else script
    command = " ".join([str(python), str(script), *flags])
    return f"\n## {title} — {datetime.date.today()} — Blender {blender()} — `{command}`\n"


def machine():
    return f"Machine: {platform.machine()}, {len(os.sched_getaffinity(0))} cores, Blender {blender()}"


def display_rmse(pixels, reference, exposure):
    """RMSE of linear pixels clipped at the display's white (2^-exposure).

    A sun disc in frame is thousands of times brighter than white; unclipped, the noise of its
    sub-pixel coverage alone made the RMSE (128 at 64 spp in the demo).
    """
    return clipped_rmse(pixels, reference, 2.0 ** -exposure)


def clipped_rmse(pixels, reference, white):
    """RMSE of linear pixels with both images clipped at `white`."""
    difference = np.minimum(np.asarray(pixels, np.float64), white) - np.minimum(reference, white)
    return float(np.sqrt(np.mean(difference ** 2)))


def pyplot(without):
    """matplotlib.pyplot on the Agg backend, or None (saying `without`) when it is not installed."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"{without}: matplotlib is missing (pip install -r requirements-bench.txt)")
        return None
    return plt


def median_seconds(action, repeats):
    """(median wall time of `repeats` runs of action(), its last result)."""
    import statistics
    import time

    seconds, out = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        out = action()
        seconds.append(time.perf_counter() - started)
    return statistics.median(seconds), out
