"""Rig contacts: how long finding where a rig's feet land takes over a long shot.

The walking rig of devtools/rigs.py (its feet keyed through a walk, a turn and a stop) with a
keyed chain of body bones standing in for the rest of a character, on flat sand, over 1000
frames: the time of addon/rig_feet.steps (stepping the frames, reading the soles, finding the
ground under them, the contacts), median of 3, at several body sizes. The issue's bound: 2 s.
Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/rig_contacts.py [--no-append]
"""

import argparse
import functools
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

FRAMES = 1000
REPEATS = 3


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    sandscape = session.start()
    import bpy

    from devtools import rigs, scenes

    rows = []
    for body in (0, 60, 200):
        session.reset()
        terrain = scenes.height_field(8.0, 16, name="Sand")
        armature = rigs.walking_rig("metarig", frames=90, extra_bones=body)
        scene = bpy.context.scene
        frames = np.arange(1, FRAMES + 1)
        steps = functools.partial(sandscape.addon.rig_feet.steps, scene, armature, terrain, frames)
        seconds, found = results.median_seconds(steps, REPEATS)
        rows.append((len(armature.data.bones), seconds, len(found["birth"])))
        print(f"rig contacts: {rows[-1][0]} bones, {rows[-1][1]:.3f} s, {rows[-1][2]} contacts", flush=True)
    lines = [results.heading("Rig contacts"),
             f"{results.machine()}. devtools/rigs.walking_rig (metarig names) with a keyed chain of body "
             f"bones, flat sand, {FRAMES} frames; rig_feet.steps, median of {REPEATS}.\n",
             "| bones | s | contacts |", "|---|---|---|"]
    lines += [f"| {bones} | {seconds:.3f} | {count} |" for bones, seconds, count in rows]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
