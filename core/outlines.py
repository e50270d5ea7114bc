"""The fractal dimension of cloud outlines by the area-perimeter method (Lovejoy 1982): over many
clouds, perimeter grows as area^(D/2); D is 1 for smooth shapes and about 1.35 for real clouds.
"""

import numpy as np


def regions(mask):
    """Label the 4-connected regions of a bool image: (labels (0 = none), count)."""
    mask = np.asarray(mask, bool)
    labels = np.zeros(mask.shape, np.int64)
    count = 0
    rows, cols = mask.shape
    for start in zip(*np.nonzero(mask), strict=True):
        if labels[start]:
            continue
        count += 1
        labels[start] = count
        stack = [start]
        while stack:
            r, c = stack.pop()
            for nr, nc in ((r - 1, c), (r + 1, c), (r, c - 1), (r, c + 1)):
                if 0 <= nr < rows and 0 <= nc < cols and mask[nr, nc] and not labels[nr, nc]:
                    labels[nr, nc] = count
                    stack.append((nr, nc))
    return labels, count


def areas_and_perimeters(mask):
    """Area (pixels) and perimeter (pixel edges between cloud and clear) of every region that
    does not touch the image's border (a cut cloud's outline is not its own)."""
    labels, count = regions(mask)
    padded = np.pad(labels, 1)
    area = np.bincount(labels.ravel(), minlength=count + 1)
    perimeter = np.zeros(count + 1, np.int64)
    for axis in (0, 1):
        size = padded.shape[axis]
        a, b = np.take(padded, range(size - 1), axis), np.take(padded, range(1, size), axis)
        edge = a != b
        perimeter += np.bincount(a[edge], minlength=count + 1) + np.bincount(b[edge], minlength=count + 1)
    border = np.unique(np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]]))
    keep = np.ones(count + 1, bool)
    keep[0] = False
    keep[border] = False
    return area[keep].astype(np.float64), perimeter[keep].astype(np.float64)


def dimension(masks, min_area=12):
    """D from the least-squares slope of log perimeter on log area, over the regions of one or
    more masks of at least min_area pixels (smaller ones are all pixel staircase); with the
    number of regions used."""
    areas, perimeters = [], []
    for mask in masks:
        a, p = areas_and_perimeters(mask)
        areas.append(a[a >= min_area])
        perimeters.append(p[a >= min_area])
    areas, perimeters = np.concatenate(areas), np.concatenate(perimeters)
    if len(areas) < 3 or np.ptp(np.log(areas)) < 1.0:
        return float("nan"), len(areas)
    slope = np.polyfit(np.log(areas), np.log(perimeters), 1)[0]
    return float(2.0 * slope), len(areas)
