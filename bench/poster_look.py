"""The poster's look, measured on its committed pictures: the shaded slopes' glitter, the crest's
sun sparkles and the nearest print's lit wall, now and at an earlier commit.

Nothing is rendered: the figures come from docs/poster.png (1280x720, demo frame 60) and
docs/print_rim.png (two 520x340 crops of the poster's prints stacked 6 px apart, the prints at
the README's two rims), read as display luminance (PIL's "L", 0-255).
- Shade glitter: in the shaded slopes' box, over the pixels whose 9x9 median is under 118 (the
  shade, not its sunlit edges), the share standing more than 5 and more than 10 levels over it.
- Crest sparkles: in the lit crest's box, the specks (pixels the brightest of their 3x3 and more
  than 30 levels over their 9x9 median), their count, the brightest four, and their arms (the
  four pixels beside each over the median, against its own: the pixel filter's plus).
- The nearest print's lit wall: its box's 99.5th percentile, in each half of print_rim.png.

Run: .venv/bin/python bench/poster_look.py [--before COMMIT] [--no-append]
"""

import argparse
import io
import pathlib
import subprocess
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results  # noqa: E402

POSTER = "docs/poster.png"
PRINT_RIM = "docs/print_rim.png"
SHADE_BOX = (900, 230, 1220, 390)  # x0, y0, x1, y1 of the poster
SHADE_MEDIAN = 118
GLITTER_LEVELS = (5, 10)
CREST_BOX = (300, 180, 500, 300)  # the lit crest left of the figure (its cloak edge at x 527-533 is no speck)
SPECK_LEVELS = 30
RIM_CROP_HEIGHT, RIM_GAP = 340, 6
NEAREST_PRINT_BOX = (20, 200, 270, 340)  # in each 520x340 crop
LIT_WALL_PERCENTILE = 99.5
BEFORE = "2c506eb~1"  # the poster with full-mirror facets and 4 cm rims


def luminance(data):
    from PIL import Image

    return Image.open(io.BytesIO(data)).convert("L")


def picture_bytes(path, commit=None):
    if commit is None:
        return (REPO / path).read_bytes()
    return subprocess.run(["git", "-C", str(REPO), "show", f"{commit}:{path}"], check=True,
                          capture_output=True).stdout


def picture(path, commit=None):
    return luminance(picture_bytes(path, commit))


def rgb_mean(data):
    from PIL import Image

    return float(np.mean(np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), np.float64)))


def over_median(image, box):
    from PIL import ImageFilter

    x0, y0, x1, y1 = box
    lum = np.asarray(image, np.float64)[y0:y1, x0:x1]
    median = np.asarray(image.filter(ImageFilter.MedianFilter(9)), np.float64)[y0:y1, x0:x1]
    return lum, median


def shade_glitter(image):
    lum, median = over_median(image, SHADE_BOX)
    shade = median < SHADE_MEDIAN
    over = (lum - median)[shade]
    return int(shade.sum()), [100.0 * float(np.mean(over > level)) for level in GLITTER_LEVELS]


def crest_specks(image):
    lum, median = over_median(image, CREST_BOX)
    over = lum - median
    padded = np.pad(over, 1, constant_values=-np.inf)
    h, w = over.shape
    peak = np.ones(over.shape, bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dy or dx:
                peak &= over >= padded[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]
    found = peak & (over > SPECK_LEVELS)
    found[0, :] = found[-1, :] = found[:, 0] = found[:, -1] = False
    y, x = np.nonzero(found)
    arms = (over[y - 1, x] + over[y + 1, x] + over[y, x - 1] + over[y, x + 1]) / 4 / over[y, x]
    specks = np.sort(lum[found])[::-1]
    return len(specks), [int(v) for v in specks[:4]], float(np.median(arms)) if len(arms) else float("nan")


def lit_walls(image):
    lum = np.asarray(image, np.float64)
    x0, y0, x1, y1 = NEAREST_PRINT_BOX
    walls = []
    for top in (0, RIM_CROP_HEIGHT + RIM_GAP):
        walls.append(float(np.percentile(lum[top + y0:top + y1, x0:x1], LIT_WALL_PERCENTILE)))
    return walls


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default=BEFORE,
                        help="the commit whose poster to compare (default %(default)s)")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    flags = ["--before", args.before] if args.before != BEFORE else []
    head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"], check=True,
                          capture_output=True, text=True).stdout.strip()
    rows = []
    for name, commit in ((f"now ({head})", None), (f"before ({args.before})", args.before)):
        data = picture_bytes(POSTER, commit)
        poster = luminance(data)
        pixels, glitter = shade_glitter(poster)
        count, brightest, arms = crest_specks(poster)
        mean = rgb_mean(data)
        rows.append(f"| {name} | {pixels} | {glitter[0]:.2f} % / {glitter[1]:.2f} % | {count} "
                    f"({', '.join(map(str, brightest))}) | {arms:.2f} | {mean:.1f} |")
    x0, y0, x1, y1 = SHADE_BOX
    cx0, cy0, cx1, cy1 = CREST_BOX
    walls = lit_walls(picture(PRINT_RIM))
    results.publish([
        results.heading("Poster look", flags), "",
        f"{results.machine()}. Measured on the committed {POSTER} (demo frame 60, 1280x720 Preview) as "
        f"display luminance, nothing rendered. Shade: x {x0}-{x1}, y {y0}-{y1}, the pixels whose 9x9 median "
        f"is under {SHADE_MEDIAN}; glitter: their share more than {GLITTER_LEVELS[0]} / {GLITTER_LEVELS[1]} "
        f"levels over that median. Crest: x {cx0}-{cx1}, y {cy0}-{cy1}; specks: 3x3 peaks more than "
        f"{SPECK_LEVELS} levels over their 9x9 median (the brightest four's levels); their arms: the four "
        f"pixels beside each, over that median, against the speck's own (the median over the specks: "
        f"the pixel filter's plus).", "",
        "| poster | shaded pixels | glitter > 5 / > 10 | crest specks (brightest) | their arms "
        "| frame's RGB mean |",
        "|---|---|---|---|---|---|", *rows, "",
        f"{PRINT_RIM}: the nearest print's {LIT_WALL_PERCENTILE}th percentile (x {NEAREST_PRINT_BOX[0]}-"
        f"{NEAREST_PRINT_BOX[2]}, y {NEAREST_PRINT_BOX[1]}-{NEAREST_PRINT_BOX[3]} of each crop): "
        f"{walls[0]:.0f} with the 4 cm rim (above), {walls[1]:.0f} with the 8 cm rim (below).",
    ], append=not args.no_append)


if __name__ == "__main__":
    main()
