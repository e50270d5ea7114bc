"""Sandscape from the command line, through the bpy module (`./sandscape --help`).

Subcommands:
  build-demo   build the desert demo from an empty file and save it as a .blend
  render       render a .blend (a frame, or several) to an image file
  bench        run a benchmark script from bench/

Long work prints progress lines; bad input exits with status 2 and one clear line.
With the full Blender instead of the bpy module, the same .blend renders with
`blender -b demo.blend -o //out/frame_ -F PNG -f 1` (see the README).
"""

import argparse
import os
import pathlib
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
MAX_FRAME = 1048574  # Blender's frame limit (MAXFRAME), both signs


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


# Output formats by file extension: the file written is what its name says.
FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".exr": "OPEN_EXR", ".tif": "TIFF",
           ".tiff": "TIFF", ".webp": "WEBP"}


def writable(path):
    """The path resolved, its folder made; UsageError when it cannot be written there."""
    path = pathlib.Path(path).resolve()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise UsageError(f"cannot write to '{path.parent}': {error.strerror}") from error
    if not os.access(path.parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise UsageError(f"cannot write '{path}': permission denied")
    return path


def build_demo(args):
    if pathlib.Path(args.output).suffix != ".blend":
        raise UsageError(f"the output must be a .blend file, got '{args.output}'")
    output = writable(args.output)
    started = time.perf_counter()
    bpy, session = blender()
    session.reset()
    progress("building the desert demo")
    bpy.ops.sandscape.build_demo_scene()
    bpy.ops.wm.save_as_mainfile(filepath=str(output), compress=True)
    progress(f"saved {output} in {time.perf_counter() - started:.1f} s")


def render_checks(args):
    """Everything about the arguments that can be wrong, before Blender starts."""
    source = pathlib.Path(args.file).resolve()
    if not source.is_file():
        raise UsageError(f"no such .blend file: '{args.file}'")
    with open(source, "rb") as handle:
        magic = handle.read(7)
    # Plain, gzip- or zstd-compressed .blend files.
    if not (magic.startswith(b"BLENDER") or magic[:2] == b"\x1f\x8b" or magic[:4] == b"\x28\xb5\x2f\xfd"):
        raise UsageError(f"'{args.file}' is not a .blend file")
    outside = [frame for frame in args.frame or [] if abs(frame) > MAX_FRAME]
    if outside:  # Blender's own range: negative frames are frames too
        raise UsageError(f"frames must lie in -{MAX_FRAME}..{MAX_FRAME}, got {outside[0]}")
    if args.samples is not None and args.samples < 1:
        raise UsageError(f"samples must be at least 1, got {args.samples}")
    if (args.width is None) != (args.height is None):
        raise UsageError("give --width and --height together, or neither")
    if args.width is not None and not (1 <= args.width <= 65536 and 1 <= args.height <= 65536):
        raise UsageError(f"--width and --height must lie in 1..65536, got {args.width}x{args.height}")
    suffix = pathlib.Path(args.output).suffix.lower()
    if suffix not in FORMATS:
        raise UsageError(f"the output's extension picks the format: one of {', '.join(FORMATS)}, "
                         f"got '{args.output}'")
    return source, writable(args.output), FORMATS[suffix]


def render(args):
    source, output, file_format = render_checks(args)
    frames = args.frame or []
    bpy, _ = blender()
    try:
        bpy.ops.wm.open_mainfile(filepath=str(source))
    except RuntimeError as error:
        raise UsageError(f"cannot open '{args.file}': {str(error).strip()}") from error
    scene = bpy.context.scene
    if scene.camera is None:
        raise UsageError(f"'{source.name}' has no scene camera to render from")
    if args.width is not None:
        scene.render.resolution_x, scene.render.resolution_y = args.width, args.height
        scene.render.resolution_percentage = 100
    if args.preset:
        bpy.ops.sandscape.apply_quality_preset(preset=args.preset.upper())
    if args.samples is not None:  # the file's engine's samples
        scene.cycles.samples = scene.eevee.taa_render_samples = args.samples
    scene.render.image_settings.file_format = file_format
    scene.render.use_file_extension = False  # the name given is the name written
    # Frames after the first reuse the evaluated scene (the file is not saved): the clouds' voxel
    # grid and the terrain are synced into Cycles once, not once per frame.
    scene.render.use_persistent_data = len(frames) > 1 or scene.render.use_persistent_data
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
    frames = commands.add_parser("render", help="render a .blend to an image file")
    frames.add_argument("file", help="the .blend to render")
    frames.add_argument("--output", default="out/render.png",
                        help="image path; its extension picks the format (.png, .jpg, .exr, .tif, .webp); "
                        "several frames get _NNNN")
    frames.add_argument("--frame", type=int, action="append", help="frame to render (repeatable)")
    frames.add_argument("--width", type=int, help="override the resolution (with --height)")
    frames.add_argument("--height", type=int, help="override the resolution (with --width)")
    frames.add_argument("--preset", choices=("draft", "preview", "final"),
                        help="a measured quality preset (bench/quality.py)")
    frames.add_argument("--samples", type=int, help="override the Cycles samples (after any preset)")
    frames.set_defaults(run=render)
    timing = commands.add_parser("bench", help="run bench/NAME.py")
    timing.add_argument("name", help="glints, footprints, footprint_dicing, atmosphere, optimize, quality")
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
