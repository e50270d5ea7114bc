"""Measure Cycles' brightness of our sand against EEVEE's and fit core.eevee_balance's coefficients
(the balance on the sun's light, the ambient balance on the rest and that one's tint per channel).

A flat plane of the default sand (Physical Sand, lit glints, no ripples; one output for both
engines, no balance) under Add Atmosphere's sun and sky (no haze, no dust), seen through a long
lens from 1.6 m at each view elevation and azimuth from the sun, rendered in Cycles (64 spp) and
EEVEE (16 samples), with the sun lamp and without it (the sky alone); and, per sun, far off a
plane showing the ambient light at its normal as the sand's EEVEE output finds it (four unlit
probes; a white Lambert surface's). Linear means. W(v), what EEVEE's sand adds to that light
times its colour, is fitted to the sky-alone renders; core.eevee_balance.solve then finds the two
balances per view, and the sky-alone renders per channel the ambient balance's tint. Prints the
fitted coefficients (paste them into core/eevee_balance.py) and the fits' errors.

Run: .venv/bin/python devtools/eevee_balance_data.py [--json OUT] [--from-json IN]
(devtools/eevee_balance.json holds the measurements the coefficients were fitted to.)
"""

import argparse
import json
import math
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from core import atmosphere as air  # noqa: E402
from core import eevee_balance as twin  # noqa: E402
from core.sand import SAND_COLOR  # noqa: E402

SUN_ELEVATIONS = (5, 10, 20, 35, 55, 80)
VIEW_ELEVATIONS = (3, 8, 15, 30, 50, 80)
AZIMUTHS = (0, 20, 40, 60, 90, 180)  # the camera's heading from the sun's: 0 looks towards the sun
PLAIN_OFFSET = 5000.0


def _calibration_scene():
    """A session with the measurements' scene: the sand plane (no ripples, its EEVEE output taken
    away: what the balances correct), Add Atmosphere's settings without haze or dust, the
    long-lens camera, and far off a plane of the same sand whose EEVEE output emits the ambient
    light its probes find (switching materials would recompile EEVEE's shaders). Returns (bpy,
    the scene, the camera)."""
    from devtools import session

    root = session.isolate()
    import bpy

    from devtools import readback, scenes

    sandscape = session.install_dev_extension(root)
    session.reset()
    bpy.ops.mesh.primitive_plane_add(size=2000)
    ground = bpy.context.active_object
    scene = bpy.context.scene
    settings = scene.sandscape_atmosphere
    settings.density = settings.dust_density = 0.0
    settings.use_haze = settings.set_exposure = False
    settings.sun_azimuth = 0.0
    camera = scenes.camera("PERSP", location=(0, 0, 1.6), lens=300)
    camera.data.clip_end = 1e4
    bpy.context.view_layer.objects.active = ground
    assert bpy.ops.sandscape.add_sand_material(ripples=False) == {"FINISHED"}
    material = ground.active_material
    sand, sand_eevee = sandscape.addon.sand, sandscape.addon.sand_eevee
    probed = material.copy()
    sand_eevee.attach(material, scene, sand.look_node(material), None)
    sand_eevee.attach(probed, scene, sand.look_node(probed), "PHYSICAL")
    tree = probed.node_tree
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(tree.nodes[sand_eevee.AMBIENT].outputs[0], emission.inputs["Color"])
    tree.links.new(emission.outputs[0], tree.nodes[sand_eevee.OUTPUT].inputs["Surface"])
    readback.cycles_scene(scene, (24, 12), 64)
    scene.eevee.taa_render_samples = 16
    bpy.ops.mesh.primitive_plane_add(size=2000, location=(PLAIN_OFFSET, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(probed)
    return bpy, scene, camera


def _mean(scene):
    from devtools import readback

    return readback.render(scene)[..., :3].reshape(-1, 3).mean(0)


def measure(azimuths=AZIMUTHS):
    bpy, scene, camera = _calibration_scene()
    settings = scene.sandscape_atmosphere
    rows = []
    for sun in SUN_ELEVATIONS:
        settings.sun_elevation = math.radians(sun)
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        lamp = next(obj for obj in scene.objects if obj.type == "LIGHT")
        same = []
        for view in VIEW_ELEVATIONS:
            for azimuth in azimuths:
                camera.rotation_euler = (math.radians(90 - view), 0.0, math.radians(azimuth))
                row = {"sun": sun, "view": view, "az": azimuth}
                for hidden, tag in ((False, ""), (True, "_sky")):
                    lamp.hide_render = hidden
                    for engine, key in (("CYCLES", "cycles"), ("BLENDER_EEVEE", "eevee")):
                        scene.render.engine = engine
                        row[key + tag] = _mean(scene).tolist()
                lamp.hide_render = False
                rows.append(row)
                same.append(row)
                print(f"balance data: {row}", flush=True)
        ambient = _ambient(scene, camera, lamp)
        for row in same:
            row.update(ambient)
        print(f"balance data: sun {sun}: {ambient}", flush=True)
    return rows


def _ambient(scene, camera, lamp):
    """The ambient light the probes find on the far plane, with the sun and without it: on flat
    ground it does not depend on the view."""
    camera.location.x = PLAIN_OFFSET
    scene.render.engine = "BLENDER_EEVEE"
    measured = {}
    try:
        for hidden, tag in ((False, ""), (True, "_sky")):
            lamp.hide_render = hidden
            measured["ambient" + tag] = _mean(scene).tolist()
    finally:
        lamp.hide_render, camera.location.x = False, 0.0
    return measured


def directions(row):
    """(towards the camera, towards the sun) of a row, as the scene had them."""
    tilt, heading = math.radians(90 - row["view"]), math.radians(row["az"])
    view = (math.sin(tilt) * math.sin(heading), -math.sin(tilt) * math.cos(heading), math.cos(tilt))
    return np.array(view), air.sun_direction(math.radians(row["sun"]), 0.0)


def view_cosine(row):
    return math.sin(math.radians(row["view"]))


def sheen_excess(rows):
    """(N·V, W) of the rows: what EEVEE's sand under the sky alone adds, per unit of the ambient
    light at its normal, to the sand's colour."""
    excess = [np.array(row["eevee_sky"]) / np.array(row["ambient_sky"]) - np.array(SAND_COLOR[:3])
              for row in rows]
    return np.array([view_cosine(row) for row in rows]), np.array(excess)


def _lights(row, sheen):
    """The row's brightnesses for core.eevee_balance.solve, channels summed, under sun and sky and
    under the sky alone; the sand's ambient with W(v) from `sheen`'s coefficients."""
    tint = np.array(SAND_COLOR[:3]) + twin.sheen_ambient(view_cosine(row), sheen)
    return [{"cycles": float(np.sum(row["cycles" + tag])), "eevee": float(np.sum(row["eevee" + tag])),
             "ambient": float(np.sum(np.array(row["ambient" + tag]) * tint))} for tag in ("", "_sky")]


def measured_balance(rows, sheen=twin.SHEEN_AMBIENT):
    """(towards the camera, towards the sun, the balance and the ambient balance that were
    needed) of the rows, as arrays, W(v) from `sheen`'s coefficients."""
    view, light = (np.array(side) for side in zip(*[directions(row) for row in rows], strict=True))
    balance, ambient = np.array([twin.solve(*_lights(row, sheen)) for row in rows]).T
    return view, light, balance, ambient


def measured_tint(rows, balance, ambient, sheen=twin.SHEEN_AMBIENT):
    """The ambient balance needed per channel over the scalar one (rows, 3), under the sky alone
    with the scalar balance: s E + (K_c - s) A = C per channel, s = min(balance, 1)."""
    ratios = []
    for row, g, k in zip(rows, balance, ambient, strict=True):
        tint = np.array(SAND_COLOR[:3]) + twin.sheen_ambient(view_cosine(row), sheen)
        scale, light = min(g, 1.0), np.array(row["ambient_sky"]) * tint
        needed = scale + (np.array(row["cycles_sky"]) - scale * np.array(row["eevee_sky"])) / light
        ratios.append(needed / k)
    return np.array(ratios)


def predicted(rows, view, light):
    """EEVEE's output as the twin's W(v) and fitted balances make it, per row and channel, under
    sun and sky (the sun reaching) and under the sky alone: two arrays (rows, 3)."""
    balance = twin.balance(view, light, (0.0, 0.0, 1.0))
    ambient_balance = twin.ambient_balance(view, light, (0.0, 0.0, 1.0))[:, None] * \
        twin.ambient_tint(view, light, (0.0, 0.0, 1.0))
    lit, sky = [], []
    for row, g, k in zip(rows, balance, ambient_balance, strict=True):
        for tag, reach, out in (("", 1.0, lit), ("_sky", 0.0, sky)):
            ambient = twin.sand_ambient(row["ambient" + tag], SAND_COLOR, view_cosine(row))
            out.append(twin.surface(row["eevee" + tag], ambient, g, k, reach))
    return np.array(lit), np.array(sky)


def fit_all(rows):
    """(SHEEN_AMBIENT, COEFFICIENTS, AMBIENT_COEFFICIENTS, AMBIENT_TINT_COEFFICIENTS) fitted to
    the rows: W(v) first, then the two balances it implies, then the ambient balance's tint; the
    balance weighted by how much of Cycles' brightness its sun's part makes (a change in the
    balance changes the brightness by that much)."""
    v_cos, excess = sheen_excess(rows)
    sheen = twin.fit_sheen_ambient(v_cos, excess)
    view, light, balance, ambient = measured_balance(rows, sheen)
    angles = twin.angles(view, light, (0.0, 0.0, 1.0))
    full = [_lights(row, sheen)[0] for row in rows]
    share = [abs(lit["eevee"] - lit["ambient"]) / lit["cycles"] for lit in full]
    weights = np.maximum(balance * np.array(share), 0.02)
    tint = twin.fit_tint(*angles, measured_tint(rows, balance, ambient, sheen))
    return sheen, twin.fit(*angles, balance, weights), twin.fit(*angles, ambient), tint


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", help="write the measurements here")
    parser.add_argument("--from-json", help="fit these measurements instead of rendering")
    parser.add_argument("--azimuths", type=float, nargs="+", default=list(AZIMUTHS),
                        help="measure these azimuths (with --from-json: added to its rows)")
    args = parser.parse_args(argv)
    rows = json.loads(pathlib.Path(args.from_json).read_text()) if args.from_json else []
    if not args.from_json or args.azimuths != list(AZIMUTHS):
        rows += measure(args.azimuths)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1))
    sheen, balance_fit, ambient_fit, tint_fit = fit_all(rows)
    v_cos, excess = sheen_excess(rows)
    print(f"balance fit: SHEEN_AMBIENT = {sheen}")
    print(f"balance fit: W {excess.min():.3f}..{excess.max():.3f}, fitted against measured: largest "
          f"{np.abs(twin.sheen_ambient(v_cos, sheen) - excess).max():.4f}")
    view, light, balance, ambient = measured_balance(rows, sheen)
    for name, needed, fitted_with, coefficients in (
            ("COEFFICIENTS", balance, twin.balance, balance_fit),
            ("AMBIENT_COEFFICIENTS", ambient, twin.ambient_balance, ambient_fit)):
        error = fitted_with(view, light, (0.0, 0.0, 1.0), coefficients) / needed - 1.0
        print(f"balance fit: {name} = {tuple(round(c, 4) for c in coefficients)}")
        print(f"balance fit: needed {needed.min():.2f}..{needed.max():.2f}; fitted against needed: "
              f"mean |error| {np.abs(error).mean():.1%}, largest {np.abs(error).max():.1%}")
    print(f"balance fit: AMBIENT_TINT_COEFFICIENTS = {tuple(round(c, 4) for c in tint_fit)}")
    needed = measured_tint(rows, balance, ambient, sheen)
    error = twin.ambient_tint(view, light, (0.0, 0.0, 1.0), tint_fit) / needed - 1.0
    print(f"balance fit: the tint against the per-channel ratio needed: largest |error| "
          f"{np.abs(error).max():.1%}")
    parts = ("sun and sky", "sky alone")
    for part, out, key in zip(parts, predicted(rows, view, light), ("cycles", "cycles_sky"),
                              strict=True):
        error = out / np.array([row[key] for row in rows]) - 1.0
        print(f"balance fit (the coefficients in core/eevee_balance.py), {part}: EEVEE against Cycles per "
              f"channel, mean |error| {np.abs(error).mean():.1%}, largest {np.abs(error).max():.1%}")


if __name__ == "__main__":
    main()
