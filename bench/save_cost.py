"""What Sandscape adds to saving and to a scene update: its handlers, with the god rays' sun
placed by drivers (nothing keyed, no frame stepped).

Scene: devtools.scenes.long_keyed_shot (1000 frames, a dolly camera aimed at a keyed target, a
side sun, the god rays, one animated modifier elsewhere). Times, as the median of REPEATS:
saving with Sandscape's handlers off (the file alone) and on, saving after the camera's lens
changed, and a scene update after a lens change with the handlers off and on; and the frames
stepped by all of those. Appends the table to bench/RESULTS.md.

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

    def update_after_a_lens_change():
        scene.camera.data.lens += 1.0
        bpy.context.view_layer.update()

    steps = []
    bpy.app.handlers.frame_change_pre.append(lambda *_: steps.append(1))
    save()
    handlers.unregister()
    plain = timed(save)
    plain_update = timed(update_after_a_lens_change)
    handlers.register()
    unchanged = timed(save)
    changed = timed(save_after_a_lens_change)
    update = timed(update_after_a_lens_change)
    rows = [("save, Sandscape's handlers off", plain), ("save, handlers on", unchanged),
            ("save after a lens change", changed),
            ("scene update after a lens change, handlers off", plain_update),
            ("scene update after a lens change, handlers on", update)]
    for name, seconds in rows:
        print(f"save cost: {name}: {seconds * 1000:.1f} ms", flush=True)
    print(f"save cost: frames stepped: {len(steps)}", flush=True)
    flags = [f"--frames {args.frames}"] if args.frames != 1000 else []
    lines = [results.heading("Save and update cost", flags),
             f"{results.machine()}. devtools/scenes.long_keyed_shot: {args.frames} frames, a dolly camera "
             f"aimed at a keyed target, the god rays' sun driven, one animated modifier. "
             f"Median of {REPEATS}.\n",
             "| what | ms |", "|---|---|"]
    lines += [f"| {name} | {seconds * 1000:.1f} |" for name, seconds in rows]
    lines.append(f"\nAdded to a save: {(unchanged - plain) * 1000:.1f} ms; to a scene update: "
                 f"{(update - plain_update) * 1000:.1f} ms. Frames stepped in all of it: {len(steps)}.")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
