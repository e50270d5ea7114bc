"""Sandscape from the command line, through the bpy module (`./sandscape --help`).

Subcommands:
  build-demo   build the desert demo from an empty file and save it as a .blend
  render       render a .blend (a frame, or several) to PNG
  bench        run a benchmark script from bench/

Long work prints progress lines; bad input exits with status 2 and one clear line.
With the full Blender instead of the bpy module, the same .blend renders with
`blender -b demo.blend -o //out/frame_ -F PNG -f 1` (see the README).
"""

import argparse
import pathlib
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent


class UsageError(Exception):
    """Bad input: reported in one line, exit status 2."""


def progress(message):
    print(f"sandscape: {message}", flush=True)


def blender():
    """An isolated bpy session with the working tree installed as the extension."""
    from devtools import session

    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    return bpy, session


def build_demo(args):
    output = pathlib.Path(args.output).resolve()
    if output.suffix != ".blend":
        raise UsageError(f"the output must be a .blend file, got '{args.output}'")
    started = time.perf_counter()
    bpy, session = blender()
    session.reset()
    progress("building the desert demo")
    bpy.ops.sandscape.build_demo_scene()
    output.parent.mkdir(parents=True, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=str(output), compress=True)
    progress(f"saved {output} in {time.perf_counter() - started:.1f} s")


def render(args):
    source = pathlib.Path(args.file).resolve()
    if not source.is_file():
        raise UsageError(f"no such .blend file: '{args.file}'")
    frames = args.frame or []
    if any(frame < 0 for frame in frames):
        raise UsageError("frames must be 0 or more")
    if args.samples is not None and args.samples < 1:
        raise UsageError(f"samples must be at least 1, got {args.samples}")
    bpy, _ = blender()
    bpy.ops.wm.open_mainfile(filepath=str(source))
    scene = bpy.context.scene
    if scene.camera is None:
        raise UsageError(f"'{source.name}' has no scene camera to render from")
    if args.width and args.height:
        scene.render.resolution_x, scene.render.resolution_y = args.width, args.height
        scene.render.resolution_percentage = 100
    if args.preset:
        bpy.ops.sandscape.apply_quality_preset(preset=args.preset.upper())
    if args.samples is not None:
        scene.cycles.samples = args.samples
    output = pathlib.Path(args.output).resolve()
    output.parent.mkdir(parents=True, exist_ok=True)
    scene.render.image_settings.file_format = "PNG"
    for index, frame in enumerate(frames or [scene.frame_current]):
        scene.frame_set(frame)
        target = output if len(frames) <= 1 else output.with_name(f"{output.stem}_{frame:04d}{output.suffix}")
        scene.render.filepath = str(target)
        started = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        seconds = time.perf_counter() - started
        progress(f"frame {frame} ({index + 1}/{max(len(frames), 1)}) in {seconds:.1f} s -> {target}")


def bench(args):
    script = REPO / "bench" / f"{args.name}.py"
    if not script.is_file():
        names = ", ".join(sorted(p.stem for p in (REPO / "bench").glob("*.py")))
        raise UsageError(f"no benchmark '{args.name}'; there are: {names}")
    command = [sys.executable, str(script), *(["--quick"] if args.quick else []),
               *(["--no-append"] if args.no_append else [])]
    progress(" ".join(command[1:]))
    return subprocess.call(command)


def parser():
    top = argparse.ArgumentParser(prog="sandscape", description=__doc__.splitlines()[0])
    commands = top.add_subparsers(dest="command", required=True)
    build = commands.add_parser("build-demo", help="build the desert demo and save it as a .blend")
    build.add_argument("--output", default="demo.blend", help="the .blend to write (default: demo.blend)")
    build.set_defaults(run=build_demo)
    frames = commands.add_parser("render", help="render a .blend to PNG")
    frames.add_argument("file", help="the .blend to render")
    frames.add_argument("--output", default="out/render.png", help="PNG path; several frames get _NNNN")
    frames.add_argument("--frame", type=int, action="append", help="frame to render (repeatable)")
    frames.add_argument("--width", type=int, help="override the resolution (with --height)")
    frames.add_argument("--height", type=int)
    frames.add_argument("--preset", choices=("draft", "preview", "final"),
                        help="a measured quality preset (bench/quality.py)")
    frames.add_argument("--samples", type=int, help="override the Cycles samples (after any preset)")
    frames.set_defaults(run=render)
    timing = commands.add_parser("bench", help="run bench/NAME.py")
    timing.add_argument("name", help="glints, footprints, footprint_dicing, atmosphere")
    timing.add_argument("--quick", action="store_true")
    timing.add_argument("--no-append", action="store_true", help="do not write bench/RESULTS.md")
    timing.set_defaults(run=bench)
    return top


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        status = args.run(args)
    except UsageError as error:
        print(f"sandscape: error: {error}", file=sys.stderr)
        return 2
    return status or 0


if __name__ == "__main__":
    sys.path.insert(0, str(REPO))
    sys.exit(main())
