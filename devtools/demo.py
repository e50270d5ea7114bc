"""`make demo`: build the desert demo headless, save out/demo.blend, render out/demo.png and a few
animation frames that show the prints appearing as the walker passes. The still renders at the
preset of --quality (draft by default, so a newcomer sees the desert in minutes; preview at
640x360; final is the poster, 1280x720 at the Final preset), the animation at the draft preset
and half the still's size.

The committed demo.blend is generated here and nowhere else (never edit it by hand): only
`make demo-blend` (--blend demo.blend --build-only) writes it; tests/test_demo_blend.py checks that
it matches a fresh build.
"""

import argparse
import pathlib
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import session  # noqa: E402

# Start, middle and end: the clouds reaching the horizon cost each Draft frame 1.5x, and five kept
# `make demo` past its 3 minutes.
ANIMATION_FRAMES = (1, 120, 240)
# The still and the poster: the trail in the sun from the frame's foot to the walker, its shadow
# running beside it (on frames 80-150 the trail lies in that shadow), the low sun and clouds in view.
HERO_FRAME = 60
QUALITIES = {"draft": ("DRAFT", 640, 360), "preview": ("PREVIEW", 640, 360), "final": ("FINAL", 1280, 720)}


def revealed_print_texels(image, frames):
    """How many print-map texels are lowered or raised at each frame (the group's reveal rule)."""
    import numpy as np

    from core import footprints

    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, 4)
    frame_range = tuple(image["frame_range"])
    return [int(np.count_nonzero(footprints.revealed_height(pixels, 1.0, 1.0, frame, frame_range)))
            for frame in frames]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blend", default=str(REPO / "out" / "demo.blend"), help="the .blend to write")
    parser.add_argument("--build-only", action="store_true", help="save the .blend, render nothing")
    parser.add_argument("--output", default="out/demo.png", help="the still to render")
    parser.add_argument("--quality", choices=sorted(QUALITIES), default="draft",
                        help="the still's preset and size: " + ", ".join(
                            f"{name} {preset.lower()} {w}x{h}" for name, (preset, w, h) in QUALITIES.items()))
    parser.add_argument("--width", type=int, help="the still's width (with --height), not the quality's")
    parser.add_argument("--height", type=int)
    parser.add_argument("--samples", type=int, help="override the preset's samples for the still")
    parser.add_argument("--frame", type=int, default=HERO_FRAME, help="frame of the still")
    parser.add_argument("--no-animation", action="store_true", help="skip the animation frames")
    args = parser.parse_args(argv)
    preset, width, height = QUALITIES[args.quality]
    if (args.width is None) != (args.height is None):
        parser.error("give --width and --height together")
    width, height = (args.width, args.height) if args.width else (width, height)

    stages = []
    started = time.perf_counter()
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    session.reset()
    stages.append(("start Blender, install the extension", time.perf_counter() - started))
    mark = time.perf_counter()
    bpy.ops.sandscape.build_demo_scene()
    stages.append(("build the scene", time.perf_counter() - mark))
    mark = time.perf_counter()
    blend = pathlib.Path(args.blend).resolve()
    blend.parent.mkdir(parents=True, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=str(blend), compress=True)
    stages.append((f"save {blend.name}", time.perf_counter() - mark))
    if args.build_only:
        print(f"demo: saved {blend} in {time.perf_counter() - started:.1f} s")
        return

    scene = bpy.context.scene
    output = pathlib.Path(args.output).resolve()
    output.parent.mkdir(parents=True, exist_ok=True)
    scene.render.image_settings.file_format = "PNG"
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    # The scene (and demo.blend) keeps the Preview preset it is built with; only the renders change.
    bpy.ops.sandscape.apply_quality_preset(preset=preset)
    if args.samples:
        scene.cycles.samples = args.samples
    # One evaluated scene for every render here: the clouds' grid is synced into Cycles once.
    scene.render.use_persistent_data = True
    scene.frame_set(args.frame)
    scene.render.filepath = str(output)
    mark = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    still = f"render {width}x{height} at {scene.cycles.samples} spp ({preset.lower()})"
    stages.append((still, time.perf_counter() - mark))

    if not args.no_animation:
        mark = time.perf_counter()
        scene.render.resolution_x, scene.render.resolution_y = width // 2, height // 2
        bpy.ops.sandscape.apply_quality_preset(preset="DRAFT")
        for frame in ANIMATION_FRAMES:
            scene.frame_set(frame)
            scene.render.filepath = str(output.with_name(f"{output.stem}_{frame:04d}{output.suffix}"))
            bpy.ops.render.render(write_still=True)
        stages.append((f"render {len(ANIMATION_FRAMES)} animation frames", time.perf_counter() - mark))
        image = next(i for i in bpy.data.images if i.get("sandscape_image") == "print_map")
        counts = revealed_print_texels(image, ANIMATION_FRAMES)
        print("demo: print-map texels revealed per frame: "
              + ", ".join(f"{frame}: {count}" for frame, count in zip(ANIMATION_FRAMES, counts, strict=True)))
    for name, seconds in stages:
        print(f"demo: {name}: {seconds:.1f} s")
    print(f"demo: total {time.perf_counter() - started:.1f} s -> {output}, {args.blend}")


if __name__ == "__main__":
    main()
