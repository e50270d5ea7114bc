"""What Sandscape adds to saving and to a render's start: the god rays' sun keys.

Scene: devtools.scenes.long_keyed_shot (1000 frames, a dolly camera aimed at a keyed target, a
side sun, the god rays, one animated modifier elsewhere). Times, as the median of REPEATS:
saving with Sandscape's handlers off (the file alone), saving with them on and nothing changed,
saving after the camera's lens changed (the keys made again), and the render-start handler on
its own with nothing changed. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/save_cost.py [--frames N] [--no-append]
"""

import argparse
import pathlib
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

REPEATS = 5


def timed(action):
    return results.median_seconds(action, REPEATS)[0]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=1000)
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    sandscape = session.start()
    import bpy

    from devtools import scenes

    handlers = sandscape.addon.post_handlers
    session.reset()
    scene = scenes.long_keyed_shot(args.frames)
    path = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-save-")) / "shot.blend"

    def save():
        bpy.ops.wm.save_as_mainfile(filepath=str(path))

    def save_after_a_lens_change():
        scene.camera.data.lens += 1.0
        save()

    save()
    handlers.unregister()
    plain = timed(save)
    handlers.register()
    unchanged = timed(save)
    changed = timed(save_after_a_lens_change)
    render_start = timed(lambda: handlers.refresh_all())
    rows = [("save, Sandscape's handlers off", plain), ("save, nothing changed", unchanged),
            ("save after a lens change (keys made again)", changed),
            ("render-start handler, nothing changed", render_start)]
    for name, seconds in rows:
        print(f"save cost: {name}: {seconds * 1000:.1f} ms", flush=True)
    flags = [f"--frames {args.frames}"] if args.frames != 1000 else []
    lines = [results.heading("Save and render-start cost", flags),
             f"{results.machine()}. devtools/scenes.long_keyed_shot: {args.frames} frames, a dolly camera "
             f"aimed at a keyed target, the god rays keyed, one animated modifier. Median of {REPEATS}.\n",
             "| what | ms |", "|---|---|"]
    lines += [f"| {name} | {seconds * 1000:.1f} |" for name, seconds in rows]
    lines.append(f"\nAdded to a save with nothing changed: {(unchanged - plain) * 1000:.1f} ms.")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
