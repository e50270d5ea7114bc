"""Which cloud seeds leave the demo's low sun in a gap: for each seed, the largest cloudiness of the
numpy twin (core.clouds) along the sun's ray from the walker, and along rays 0.6 degrees round it,
through the layer on every 40th frame (> 0 is cloud: the sand would lie in the clouds' shade),
and how many rays 2-6 degrees from the sun meet cloud on the hero frame (the gap's edges).

How addon/demo.py's CLOUDS seed was chosen. Run:
    .venv/bin/python devtools/cloud_gap.py [--seeds 0 100] [--coverage 0.4]
"""

import argparse
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import session  # noqa: E402
from devtools.demo import HERO_FRAME  # noqa: E402

ROUND_SUN = 0.6  # degrees: the sky round the disc, kept clear
NEAR_SUN = (2.0, 4.0, 6.0)  # degrees: where the gap's edges should hold cloud


def cone(axis, degrees, count=8):
    """`count` unit directions `degrees` off `axis`, evenly round it."""
    side = np.cross(axis, (0.0, 0.0, 1.0))
    side /= np.linalg.norm(side)
    up = np.cross(side, axis)
    turns = np.linspace(0.0, 2.0 * np.pi, count, endpoint=False)
    rays = axis + np.tan(np.radians(degrees)) * (np.cos(turns)[:, None] * side + np.sin(turns)[:, None] * up)
    return rays / np.linalg.norm(rays, axis=1, keepdims=True)


def worst_cloudiness(twin, p, origin, rays, samples=300):
    """The largest cloudiness on rays from origin between the layer's base and top."""
    low, high = p["base"], p["base"] + p["thickness"]
    worst = -np.inf
    for ray in rays:
        distances = np.linspace((low - origin[2]) / ray[2], (high - origin[2]) / ray[2], samples)
        worst = max(worst, float(twin.cloudiness(origin + distances[:, None] * ray, p).max()))
    return worst


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, nargs=2, default=(0, 100), help="first and past-last seed")
    parser.add_argument("--coverage", type=float, help="the demo's coverage unless given")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    module = session.install_dev_extension(root)
    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    addon = module.addon
    sun = addon.atmosphere.scene_sun(scene)
    toward = np.array(sun.matrix_world.col[2][:3])
    toward /= np.linalg.norm(toward)
    walker = scene.sandscape_footprints.walker
    frames = list(range(scene.frame_start, scene.frame_end + 1, 40))
    places = {}
    for frame in frames + [HERO_FRAME]:
        scene.frame_set(frame)
        places[frame] = np.array(walker.matrix_world.translation)
    fps = addon.shot.frames_per_second(scene)
    settings = addon.clouds.scene_settings(scene)
    from core import clouds as twin

    base = addon.clouds.parameters(scene, settings)
    if args.coverage is not None:
        base["coverage"] = args.coverage
    round_sun = np.vstack([toward, cone(toward, ROUND_SUN)])
    near_sun = np.vstack([cone(toward, degrees) for degrees in NEAR_SUN])
    clear = []
    for seed in range(*args.seeds):
        p = {**base, "seed": seed}
        worst = max(worst_cloudiness(twin, {**p, "time": frame / fps}, places[frame], round_sun)
                    for frame in frames)
        hero = {**p, "time": HERO_FRAME / fps}
        edges = sum(worst_cloudiness(twin, hero, places[HERO_FRAME], ray[None]) > 0 for ray in near_sun)
        print(f"seed {seed}: round the sun {worst:+.4f}, cloud on {edges} of {len(near_sun)} rays "
              "2-6 deg off", flush=True)
        if worst <= 0.0:
            clear.append(seed)
    print(f"coverage {base['coverage']:.2f}: the sun clear with seeds {clear}")


if __name__ == "__main__":
    main()
