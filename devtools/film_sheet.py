"""The whole demo animation on one sheet: every STEP-th frame of the demo, rendered at the Draft
preset through its compositor, in a grid (docs/film.png), to look at every part of the film.
With --engine EEVEE the film is rendered as EEVEE renders it: its compositor, the clouds' shadow
layer and its Draft preset (docs/film_eevee.png unless --output says otherwise).

Run: .venv/bin/python devtools/film_sheet.py [--step 20] [--width 320] [--engine CYCLES|EEVEE]
     [--output docs/film.png]
"""

import argparse
import pathlib
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

COLUMNS = 4


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step", type=int, default=20)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--preset", default="DRAFT", choices=("DRAFT", "PREVIEW", "FINAL"))
    parser.add_argument("--engine", default="CYCLES", choices=("CYCLES", "EEVEE"))
    parser.add_argument("--output")
    args = parser.parse_args(argv)
    name = "film.png" if args.engine == "CYCLES" else "film_eevee.png"
    args.output = args.output or str(REPO / "docs" / name)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback

    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = args.width, args.width * 9 // 16
    scene.render.resolution_percentage = 100
    if args.engine == "EEVEE":
        scene.render.engine = "BLENDER_EEVEE"
        assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}  # the tree EEVEE's passes feed
        assert bpy.ops.sandscape.add_clouds() == {"FINISHED"}  # their shadow layer, as in an EEVEE scene
    bpy.ops.sandscape.apply_quality_preset(preset=args.preset)
    frames = list(range(scene.frame_start, scene.frame_end + 1, args.step))
    if frames[-1] != scene.frame_end:
        frames.append(scene.frame_end)
    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-film-"))
    pictures = []
    for frame in frames:
        started = time.perf_counter()
        scene.frame_set(frame)
        pictures.append((frame, readback.render_display(scene, out / f"{frame:04d}.png")))
        print(f"film sheet: frame {frame}: {time.perf_counter() - started:.1f} s", flush=True)
    plt = results.pyplot("film sheet: no sheet")
    if plt is None:
        return
    rows = -(-len(pictures) // COLUMNS)
    figure, axes = plt.subplots(rows, COLUMNS, figsize=(3.2 * COLUMNS, 1.95 * rows), dpi=100, squeeze=False)
    for axis in axes.ravel():
        axis.axis("off")
    for axis, (frame, pixels) in zip(axes.ravel(), pictures, strict=False):
        axis.imshow(pixels[::-1, :, :3].clip(0.0, 1.0))
        axis.set_title(f"frame {frame}", fontsize=8)
    figure.tight_layout()
    figure.savefig(args.output)
    print(f"film sheet -> {args.output}")


if __name__ == "__main__":
    main()
