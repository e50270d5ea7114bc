"""Far haze benchmark: what the far haze costs a demo frame, and how much of the sky it changes.

The demo at FRAME, RESOLUTION, its Draft preset, through its compositor, rendered with the far
haze and without it in turn, REPEATS times each (alternating, so a warm cache favours neither):
the median render time of each, and the share of the upper half's 4x4 blocks (the sky and the
far land) that move by more than effects.BLOCK_CHANGE. With --engine eevee, in EEVEE at its Draft
preset (its compositor rebuilt for it; one untimed render first compiles the shaders), and the
mean change of the upper half's colour. Appends to bench/RESULTS.md.

Run: .venv/bin/python bench/far_haze.py [--frame F] [--repeats N] [--engine cycles|eevee] [--no-append]
"""

import argparse
import pathlib
import statistics
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from bench.effects import BLOCK, BLOCK_CHANGE, RESOLUTION, block_change, build_demo  # noqa: E402
from devtools import results, session  # noqa: E402

FRAME = 60
REPEATS = 2


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frame", type=int, default=FRAME)
    parser.add_argument("--repeats", type=int, default=REPEATS)
    parser.add_argument("--engine", choices=("cycles", "eevee"), default="cycles")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import importlib
    import tempfile

    import bpy

    session.install_dev_extension(root)
    from devtools import readback

    ownership = importlib.import_module(f"{session.MODULE}.addon.ownership")
    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-far-haze-"))
    scene = build_demo(bpy, None, args.frame)
    shell = ownership.scene_object(scene, ownership.FAR_HAZE)
    samples = f"{scene.cycles.samples} spp"
    if args.engine == "eevee":
        scene.render.engine = "BLENDER_EEVEE"
        assert bpy.ops.sandscape.apply_quality_preset(preset="DRAFT") == {"FINISHED"}
        assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}  # the tree EEVEE's passes feed
        readback.render_display(scene, out / "warm.png")
        samples = f"EEVEE Draft, {scene.eevee.taa_render_samples} samples"
    seconds, pixels = {True: [], False: []}, {}
    for repeat in range(args.repeats):
        for hazed in (True, False):
            shell.hide_render = not hazed
            started = time.perf_counter()
            pixels[hazed] = readback.render_display(scene, out / f"{hazed}-{repeat}.png")
            seconds[hazed].append(time.perf_counter() - started)
            print(f"far haze {'on' if hazed else 'off'}: {seconds[hazed][-1]:.1f} s", flush=True)
    upper = RESOLUTION[1] // 2  # rows bottom-up: the upper half is the second
    share = block_change(pixels[True][upper:], pixels[False][upper:])
    moved = (pixels[True][upper:] - pixels[False][upper:])[..., :3].mean(axis=(0, 1)) * 255
    on, off = (statistics.median(seconds[k]) for k in (True, False))
    flags = [f"--frame {args.frame}"] if args.frame != FRAME else []
    flags += [f"--repeats {args.repeats}"] if args.repeats != REPEATS else []
    flags += ["--engine eevee"] if args.engine == "eevee" else []
    lines = [results.heading("Far haze", flags),
             f"{results.machine()}. Demo frame {args.frame}, {RESOLUTION[0]}x{RESOLUTION[1]}, "
             f"{samples}, through its compositor, {args.repeats} renders each, "
             f"alternating. A block changes when its {BLOCK}x{BLOCK} mean moves by over {BLOCK_CHANGE}; "
             "the upper half's mean colour change in display levels (of 255), red, green, blue.\n",
             "| far haze | median render | upper half's blocks changed | upper half's colour moved |",
             "|---|---|---|---|",
             f"| on | {on:.1f} s ({on / off - 1:+.1%}) | {share * 100:.1f} % | "
             f"{moved[0]:+.2f} / {moved[1]:+.2f} / {moved[2]:+.2f} |",
             f"| off | {off:.1f} s | - | - |"]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
