"""The demo's palette against its exposure: does a low sun read golden or milky?

Renders demo frames at 320x180 and the Preview preset through the compositor, once each to a
32-bit EXR, then writes that render through the scene's view transform at several exposure
shifts from the demo's own (image.save_render, no new render) and measures the display values
an artist's eye weighs: the frame's 5th-95th percentile brightness, the lit lower half's median
hue and saturation (devtools/look.py, as bench/effects.py), and the shade's (the lower half's
darkest quarter) median brightness and saturation. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/palette.py [--frames 20 120 200] [--shifts 0.7 0 -0.3 -0.7 -1] [--no-append]
"""

import argparse
import pathlib
import sys
import tempfile

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import look, results, session  # noqa: E402

FRAMES = (20, 120, 200)
SHIFTS = (0.7, 0.0, -0.3, -0.7)  # stops from the demo's exposure (0.7: Add Atmosphere's grey card)
RESOLUTION = (320, 180)
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec. 709 weights of display RGB


def palette(pixels):
    """(p5, p95 brightness, lit hue, lit saturation, shade brightness, shade saturation)."""
    brightness = pixels[..., :3] @ LUMINANCE
    hue, saturation = look.lit_lower_half(pixels)
    lower = pixels[: pixels.shape[0] // 2, :, :3].reshape(-1, 3)  # rows bottom-up
    lower_brightness = lower @ LUMINANCE
    shade = lower[lower_brightness <= np.percentile(lower_brightness, 25)]
    _, shade_saturation = look.hue_saturation(shade)
    return (*np.percentile(brightness, (5, 95)), hue, saturation,
            float(np.median(shade @ LUMINANCE)), float(np.median(shade_saturation)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, nargs="+", default=list(FRAMES))
    parser.add_argument("--shifts", type=float, nargs="+", default=list(SHIFTS))
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    sandscape, scene = session.demo_scene()
    import bpy

    from devtools import readback

    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    bpy.ops.sandscape.apply_quality_preset(preset="PREVIEW")
    demo_exposure = scene.view_settings.exposure
    settings = scene.render.image_settings
    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-palette-"))
    rows = []
    for frame in args.frames:
        scene.frame_set(frame)
        settings.file_format, settings.color_depth = "OPEN_EXR", "32"
        scene.render.filepath = str(out / f"{frame}.exr")
        bpy.ops.render.render(write_still=True, scene=scene.name)
        settings.file_format, settings.color_depth, settings.color_mode = "PNG", "16", "RGB"
        for shift in args.shifts:
            scene.view_settings.exposure = demo_exposure + shift
            render = bpy.data.images.load(str(out / f"{frame}.exr"), check_existing=False)
            path = out / f"{frame}_{shift:+.1f}.png"
            render.save_render(str(path), scene=scene)
            bpy.data.images.remove(render)
            rows.append((frame, shift, palette(readback.read_image(path, "Non-Color")[..., :3])))
            print(rows[-1], flush=True)
        scene.view_settings.exposure = demo_exposure
    flags = [f"--frames {' '.join(map(str, args.frames))}"] if args.frames != list(FRAMES) else []
    flags += [f"--shifts {' '.join(f'{s:g}' for s in args.shifts)}"] if args.shifts != list(SHIFTS) else []
    lines = [results.heading("Palette against exposure", flags),
             f"{results.machine()}. Demo frames at {RESOLUTION[0]}x{RESOLUTION[1]}, Preview preset, "
             f"through the compositor, AgX {scene.view_settings.look}; the demo's exposure "
             f"{demo_exposure:+.2f}, shifted. Display values: brightness (Rec. 709 weights) percentiles "
             "over the frame; lit = the lower half's brighter half, shade = its darkest quarter.\n",
             "| frame | shift (stops) | brightness p5-p95 | lit hue | lit saturation | shade brightness "
             "| shade saturation |", "|---|---|---|---|---|---|---|"]
    for frame, shift, (p5, p95, hue, saturation, shade, shade_saturation) in rows:
        lines.append(f"| {frame} | {shift:+.1f} | {p5:.2f}-{p95:.2f} | {hue:.1f}° | {saturation:.3f} "
                     f"| {shade:.2f} | {shade_saturation:.3f} |")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
