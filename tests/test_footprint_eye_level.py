"""Prints read at eye level, in an artist's own shot: 1.6 m up, 3 m behind where a 10 m walk ends,
looking back along the trail under a side sun 15 degrees up (devtools/print_shot.py).

A print 9-13 m away is about 2 pixels tall at 480x270. What carries it there is the hollow's own
shading (the wall facing the sun lit, the other in shade, both at the angle of repose), not a size
floor: each far print must still change the picture around it, rendered with the prints against
the same shot with them flattened, while the sand between the prints stays as it was.
"""

import numpy as np

from devtools import print_shot, readback

FAR = (9.0, 13.0)  # metres from the camera
AROUND = (10, 3)  # pixels either side of a print's centre: its sole and walls at that distance
REACH = (16, 7)  # pixels either side of a print's centre where its rim and shadow may still fall
PER_PRINT = 12  # changed pixels around each far print (the bench's row: about 27)
ELSEWHERE = 0.01  # the most of the sand away from the prints that may change


def test_prints_ten_metres_away_still_change_the_picture(tmp_path):
    scene, camera = print_shot.build(samples=16)
    centres, distance = print_shot.print_pixels(scene, camera)
    far = centres[(distance >= FAR[0]) & (distance < FAR[1])]
    assert len(far) >= 4, distance
    # Only the box around the far prints is rendered (the rest of the frame stays empty in both).
    width, height = print_shot.RESOLUTION
    low = far.min(axis=0) - np.array(REACH) * 2
    high = far.max(axis=0) + np.array(REACH) * 2
    render = scene.render
    render.use_border, render.use_crop_to_border = True, False
    render.border_min_x, render.border_max_x = max(low[0] / width, 0.0), min(high[0] / width, 1.0)
    render.border_min_y, render.border_max_y = max(low[1] / height, 0.0), min(high[1] / height, 1.0)
    with_prints = readback.render_display(scene, tmp_path / "prints.png")
    print_shot.flatten(scene)
    flat = readback.render_display(scene, tmp_path / "flat.png")
    assert np.isfinite(with_prints).all() and np.isfinite(flat).all()
    changed = np.abs(with_prints - flat).max(axis=-1) > print_shot.PIXEL_CHANGE
    def around(centre, half):
        column, row = np.round(centre).astype(int)
        rows = slice(max(row - half[1], 0), row + half[1] + 1)
        return rows, slice(max(column - half[0], 0), column + half[0] + 1)

    counts = [int(changed[around(centre, AROUND)].sum()) for centre in far]
    near_a_print = np.zeros_like(changed)
    for centre in centres:  # nearer and farther prints may fall in the box too
        near_a_print[around(centre, REACH)] = True
    rows, columns = np.indices(changed.shape)
    inside = ((columns >= low[0]) & (columns <= high[0]) & (rows >= low[1]) & (rows <= high[1]))
    between = inside & ~near_a_print
    print(f"changed pixels around each far print: {counts}; between them {changed[between].mean():.4f}")
    assert min(counts) >= PER_PRINT, counts
    assert changed[between].mean() <= ELSEWHERE
