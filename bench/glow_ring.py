"""Where the glow round the clouds comes from: the demo's frame, each post effect alone.

The demo.blend frame at 320x180 (its own Preview preset) rendered raw with its clouds, raw without
them, and with the denoiser, the gated blur (with and without its guide, the environment pass)
and the god rays each alone, then all together. Sky:
pixels whose camera ray rises more than 1 degree (the dunes stand below that) and away from the
sun disc; the clouds are where they change the raw sky by more than 5 %. The glow of a step is
its change to the sky's luminance 1-2, 3-6 and 7-15 pixels outside the clouds, relative to the
raw frame's there, and in brackets what is left after taking out what the far sky at the same
distance from the sun gets (the ring's own share); "the sky" row is what the clouds themselves
do to the sky near them (raw with clouds against raw without).
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

BANDS = ((1, 2), (3, 6), (7, 15))
VARIANTS = {"denoise": ("use_denoise",), "gated blur, unguided (before)": ("use_blur", "unguided"),
            "gated blur": ("use_blur",), "god rays": ("use_god_rays",),
            "all three": ("use_denoise", "use_blur", "use_god_rays")}


def distance_outside(mask, far=16):
    """Chebyshev pixel distance of every pixel outside mask to it, up to `far` (numpy dilation)."""
    distance = np.full(mask.shape, far + 1, np.int32)
    grown = mask.copy()
    distance[mask] = 0
    for step in range(1, far + 1):
        padded = np.pad(grown, 1)
        grown = np.zeros_like(mask)
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                grown |= padded[1 + dy:1 + dy + mask.shape[0], 1 + dx:1 + dx + mask.shape[1]]
        distance[grown & (distance > step)] = step
    return distance


def luminance(image):
    return image[..., :3] @ np.array([0.2126, 0.7152, 0.0722])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frame", type=int, default=120)
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy
    import mathutils

    session.install_dev_extension(root)
    from devtools import readback, scenes

    post = __import__(f"{session.MODULE}.addon.post", fromlist=["post"])
    bpy.ops.wm.open_mainfile(filepath=str(REPO / "demo.blend"))
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 180, 100
    scene.frame_set(args.frame)
    settings = scene.sandscape_post
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    switches = ("use_denoise", "use_blur", "use_god_rays")

    def render(on=()):
        for name in switches:
            setattr(settings, name, name in on)
        tree = post.apply_post_effects(scene, settings)["tree"]
        if "unguided" in on:  # the blur as it was: nothing tells it where the sky is hidden
            guide = tree.nodes["Sandscape Gated Blur"].inputs["Guide"]
            tree.links.remove(guide.links[0])
        started = time.perf_counter()
        image = readback.render(scene)
        print(f"{on or 'raw'}: {time.perf_counter() - started:.1f} s", flush=True)
        return luminance(image)

    raw = render()
    layer.hide_render = True
    clear = render()
    layer.hide_render = False
    _, directions = scenes.camera_rays(scene.camera, 320, 180)
    toward_sun = post.atmosphere.scene_sun(scene).matrix_world.to_quaternion() @ mathutils.Vector((0, 0, 1))
    sun = np.array(toward_sun)
    sky = (directions[..., 2] > np.sin(np.radians(1.0))) & (directions @ sun < np.cos(np.radians(3.0)))
    mask = sky & (np.abs(raw - clear) > 0.05 * np.maximum(clear, 1e-3))
    distance = distance_outside(mask)
    rows = ["| step | " + " | ".join(f"{a}-{b} px" for a, b in BANDS) + " | far sky |",
            "|---|" + "---|" * (len(BANDS) + 1)]
    far = sky & (distance > BANDS[-1][1])
    bands = [sky & (distance >= a) & (distance <= b) for a, b in BANDS] + [far]

    # A step can brighten the sky with the distance to the sun (the god rays do): what the far sky
    # gets at the same distance is taken out, bin by degree, so what is left belongs to the clouds.
    sun_bin = np.degrees(np.arccos(np.clip(directions @ sun, -1.0, 1.0))).astype(int)

    def line(name, change, reference):
        far_mean = {b: change[far & (sun_bin == b)].mean() for b in np.unique(sun_bin[far])}
        cells = []
        for band in bands:
            known = band & np.isin(sun_bin, list(far_mean))
            if not known.any():
                cells.append("none")
                continue
            expected = np.vectorize(far_mean.get)(sun_bin[known])
            excess = (change[known] - expected).mean() / reference[known].mean()
            cells.append(f"{change[band].mean() / reference[band].mean():+.1%} ({excess:+.1%})")
        rows.append(f"| {name} | " + " | ".join(cells) + " |")
        print(rows[-1], flush=True)

    line("the sky (raw with clouds against raw without)", raw - clear, clear)
    for name, on in VARIANTS.items():
        line(name, render(on) - raw, raw)
    lines = [results.heading("Glow ring", [f"--frame {args.frame}"]),
             f"{results.machine()}. demo.blend frame {args.frame}, 320x180, its Preview preset; mean change "
             f"of the sky's luminance by distance outside the clouds, relative ({int(sky.sum())} sky pixels, "
             f"{int(mask.sum())} of them cloud).\n", *rows, ""]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
