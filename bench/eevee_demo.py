"""The demo frame in EEVEE beside Cycles (issue 27): time per frame and, per region of the frame,
the mean display colour in each engine with EEVEE's brightness, saturation and hue against
Cycles', and how the sky's pixels correlate (the clouds drawn and shaded where Cycles has them).
Regions come from rays cast through the pixel centres, not from the pictures: sky (no surface),
the walker, sand in sun and in shade (a ray to the sun from the hit point), near and far. Both
engines get the compositor built for them (Add Post Effects after the switch), EEVEE the clouds'
shadow layer (Add Clouds after the first switch; Cycles sees it as clear), and the side-by-side
pictures are written to the output folder (docs/eevee_demo.png with --picture).
EEVEE runs on software OpenGL here: its times are a CPU's, not a GPU's.
Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/eevee_demo.py [--frames 60 200] [--samples 16] [--picture] [--no-append]
"""

import argparse
import colorsys
import pathlib
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (160, 90)
FRAMES = (60, 200)  # the poster's frame and the effects bench's: walker, prints, sun, clouds in view
NEAR = 60.0  # metres: sand nearer than this is "near"
REGIONS = ("sky", "walker", "near sand in sun", "near sand in shade", "far sand in sun", "far sand in shade")


def regions(bpy, scene, camera):
    """{region: (H, W) bool mask, rows bottom-up} from one ray per pixel centre (volumes hidden)."""
    from devtools import scenes

    lamp = next(o for o in scene.objects if o.get("sandscape_object") == "sun")
    hits = scenes.pixel_hits(scene, camera, *RESOLUTION, lamp.matrix_world.to_3x3().col[2])
    walker = np.vectorize(_is_walker, otypes=[bool])(hits["object"])
    sand = hits["hit"] & ~walker
    near = hits["distance"] < NEAR
    sun, shade = sand & hits["sunlit"], sand & ~hits["sunlit"]
    return {"sky": ~hits["hit"], "walker": walker,
            "near sand in sun": sun & near, "near sand in shade": shade & near,
            "far sand in sun": sun & ~near, "far sand in shade": shade & ~near}


def _is_walker(obj):
    while obj is not None:
        if obj.get("sandscape_object") == "walker":
            return True
        obj = obj.parent
    return False


def describe(colour):
    """(brightness, saturation, hue in degrees) of a display colour."""
    hue, saturation, value = colorsys.rgb_to_hsv(*np.clip(colour, 0.0, 1.0))
    return float(np.mean(colour)), saturation, hue * 360.0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, nargs="+", default=list(FRAMES))
    parser.add_argument("--samples", type=int, default=16, help="Cycles spp and EEVEE samples")
    parser.add_argument("--picture", action="store_true", help="write docs/eevee_demo.png")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    _, scene = session.demo_scene()
    import bpy

    from devtools import readback

    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.cycles.samples, scene.eevee.taa_render_samples = args.samples, args.samples
    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-eevee-demo-"))
    tables, pictures = [], []
    for frame in args.frames:
        scene.frame_set(frame)
        masks = regions(bpy, scene, scene.camera)
        frames, seconds = {}, {}
        for engine in ("CYCLES", "BLENDER_EEVEE"):
            scene.render.engine = engine
            assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}  # the tree this engine's passes feed
            if engine == "BLENDER_EEVEE" and not any(o.get("sandscape_object") == "cloud_shadows"
                                                     for o in scene.objects):
                assert bpy.ops.sandscape.add_clouds() == {"FINISHED"}  # their shadow, as in an EEVEE scene
            if engine == "BLENDER_EEVEE":
                readback.render_display(scene, out / f"warm-{frame}.png")  # shaders compiled
            started = time.perf_counter()
            frames[engine] = readback.render_display(scene, out / f"{engine.lower()}-{frame}.png")
            seconds[engine] = time.perf_counter() - started
            print(f"eevee demo bench: frame {frame} {engine} {seconds[engine]:.1f} s", flush=True)
        pictures.append(np.concatenate([frames["CYCLES"], frames["BLENDER_EEVEE"]], axis=1))
        rows = []
        for name in REGIONS:
            mask = masks[name]
            if mask.sum() < 8:
                continue
            cycles, eevee = (frames[k][mask].mean(0) for k in ("CYCLES", "BLENDER_EEVEE"))
            (cb, cs, ch), (eb, es, eh) = describe(cycles), describe(eevee)
            hue = (eh - ch + 180.0) % 360.0 - 180.0
            rows.append((name, mask.mean(), cycles, eevee, eb / cb - 1, es - cs, hue))
            print("eevee demo bench:", frame, rows[-1], flush=True)
        sky = masks["sky"]
        luminance = {k: frames[k][..., :3].mean(-1)[sky] for k in frames}
        # Clouds drawn where Cycles draws them, shaded as it shades them: the sky's pixels agree
        correlation = float(np.corrcoef(luminance["CYCLES"], luminance["BLENDER_EEVEE"])[0, 1])
        print(f"eevee demo bench: frame {frame} sky luminance correlation {correlation:.3f}", flush=True)
        tables.append((frame, seconds, rows, correlation))
    plt = results.pyplot("docs/eevee_demo.png not written") if args.picture else None
    if plt is not None:  # Cycles left, EEVEE right, a frame per row, each pixel shown 2x2
        sheet = np.clip(np.concatenate([p[::-1] for p in pictures]), 0.0, 1.0).repeat(2, 0).repeat(2, 1)
        plt.imsave(REPO / "docs" / "eevee_demo.png", sheet)
    publish(args, tables)


def publish(args, tables):
    def colour(c):
        return "(" + ", ".join(f"{v:.3f}" for v in c) + ")"

    flags = [f"--frames {' '.join(map(str, args.frames))}"] if args.frames != list(FRAMES) else []
    flags += ([f"--samples {args.samples}"] if args.samples != 16 else []) + \
        (["--picture"] if args.picture else [])
    lines = [results.heading("EEVEE beside Cycles: the demo frame", flags),
             f"{results.machine()}, EEVEE on software OpenGL (EGL, llvmpipe). Demo frames at "
             f"{RESOLUTION[0]}x{RESOLUTION[1]}, Cycles {args.samples} spp with the demo's settings, EEVEE "
             f"{args.samples} samples, each through the compositor built for it; display values (AgX). "
             f"Regions from a ray per pixel (near: closer than {NEAR:g} m; in sun: a ray to the sun is "
             "free). Saturation and hue of the region's mean colour; EEVEE's first frame also compiles "
             "shaders and is not counted.\n"]
    for frame, seconds, rows, correlation in tables:
        lines += [f"Frame {frame}: Cycles {seconds['CYCLES']:.1f} s, EEVEE {seconds['BLENDER_EEVEE']:.1f} s; "
                  f"the sky's display luminance, pixel by pixel, correlates {correlation:.3f} with Cycles'.",
                  "", "| region | share | Cycles mean colour | EEVEE mean colour | brightness | saturation "
                  "| hue |", "|---|---|---|---|---|---|---|"]
        lines += [f"| {name} | {share:.0%} | {colour(c)} | {colour(e)} | {b:+.1%} | {s:+.3f} | {h:+.1f}° |"
                  for name, share, c, e, b, s, h in rows]
        lines.append("")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
