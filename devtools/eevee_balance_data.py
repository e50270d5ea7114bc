"""Measure Cycles' brightness of our sand over EEVEE's and fit core.eevee_balance's coefficients.

A flat plane of the default sand (Physical Sand, lit glints, no ripples; one output for both
engines, no balance) under Add Atmosphere's sun and sky (no haze, no dust), seen through a long
lens from 1.6 m at each view elevation and azimuth from the sun, rendered in Cycles (64 spp) and
EEVEE (16 samples), and a Lambert plane of the sand's colour in EEVEE lit by the sun alone (no
world: the balance's boost adds the sun's light only); linear means. Prints the fitted
coefficients (paste them into core/eevee_balance.py) and the fit's error.

Run: .venv/bin/python devtools/eevee_balance_data.py [--json OUT] [--from-json IN] [--add-sun-light]
(devtools/eevee_balance.json holds the measurements the coefficients were fitted to; --add-sun-light
measures the sun-only Lambert plane for measurements made before it was recorded.)
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

SUN_ELEVATIONS = (10, 20, 35, 55, 80)
VIEW_ELEVATIONS = (3, 8, 15, 30, 50, 80)
AZIMUTHS = (0, 90, 180)  # the camera's heading from the sun's: 0 looks towards the sun
PLAIN_OFFSET = 5000.0


def _calibration_scene():
    """A session with the measurements' scene: the sand plane (no ripples, its EEVEE output taken
    away: what the balance corrects), Add Atmosphere's settings without haze or dust, the long-lens
    camera, and far off a plane of EEVEE's Lambert diffuse in the sand's colour (switching
    materials would recompile EEVEE's shaders). Returns (bpy, readback, the scene, the camera)."""
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
    sandscape.addon.sand_eevee.attach(material, scene, sandscape.addon.sand.look_node(material), None)
    readback.cycles_scene(scene, (24, 12), 64)
    scene.eevee.taa_render_samples = 16
    plain = bpy.data.materials.new("Plain Diffuse")
    plain.node_tree.nodes.clear()
    bsdf = plain.node_tree.nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = sandscape_look_colour(material)
    out = plain.node_tree.nodes.new("ShaderNodeOutputMaterial")
    plain.node_tree.links.new(bsdf.outputs[0], out.inputs["Surface"])
    bpy.ops.mesh.primitive_plane_add(size=2000, location=(PLAIN_OFFSET, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(plain)
    return bpy, readback, scene, camera


def measure():
    bpy, readback, scene, camera = _calibration_scene()
    settings = scene.sandscape_atmosphere
    rows = []
    for sun in SUN_ELEVATIONS:
        settings.sun_elevation = math.radians(sun)
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        for view in VIEW_ELEVATIONS:
            for azimuth in AZIMUTHS:
                camera.rotation_euler = (math.radians(90 - view), 0.0, math.radians(azimuth))
                means = []
                for engine, x in (("CYCLES", 0.0), ("BLENDER_EEVEE", 0.0), ("BLENDER_EEVEE", PLAIN_OFFSET)):
                    scene.render.engine = engine
                    camera.location.x = x
                    means.append(readback.render(scene)[..., :3].reshape(-1, 3).mean(0).tolist())
                camera.location.x = 0.0
                rows.append({"sun": sun, "view": view, "az": azimuth, "cycles": means[0], "eevee": means[1],
                             "eevee_diffuse": means[2]})
                print(f"balance data: {rows[-1]}", flush=True)
        _sun_light_rows(bpy, scene, camera, [row for row in rows if row["sun"] == sun])
    return rows


def _sun_light_rows(bpy, scene, camera, rows):
    """Record in each row EEVEE's Lambert plane lit by the sun alone (the world taken away), seen
    from the first row's view: a Lambert surface's brightness does not depend on the view."""
    from devtools import readback

    world, scene.world = scene.world, None
    scene.render.engine = "BLENDER_EEVEE"
    camera.rotation_euler = (math.radians(90 - rows[0]["view"]), 0.0, math.radians(rows[0]["az"]))
    camera.location.x = PLAIN_OFFSET
    try:
        sun_only = readback.render(scene)[..., :3].reshape(-1, 3).mean(0).tolist()
    finally:
        scene.world, camera.location.x = world, 0.0
    for row in rows:
        row["eevee_diffuse_sun"] = sun_only
    print(f"balance data: sun {rows[0]['sun']}: the Lambert plane lit by the sun alone "
          f"{np.round(sun_only, 3)}", flush=True)


def add_sun_light(rows):
    """Measure the sun-only Lambert plane for rows recorded without it (the same scene rebuilt)."""
    bpy, readback, scene, camera = _calibration_scene()
    settings = scene.sandscape_atmosphere
    for sun in sorted({row["sun"] for row in rows}):
        settings.sun_elevation = math.radians(sun)
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        same = [row for row in rows if row["sun"] == sun]
        scene.render.engine = "BLENDER_EEVEE"
        camera.rotation_euler = (math.radians(90 - same[0]["view"]), 0.0, math.radians(same[0]["az"]))
        camera.location.x = PLAIN_OFFSET
        now = readback.render(scene)[..., :3].reshape(-1, 3).mean(0)
        camera.location.x = 0.0
        print(f"balance data: sun {sun}: the Lambert plane with the world {now.round(3)}, recorded "
              f"{np.round(same[0]['eevee_diffuse'], 3)}", flush=True)
        _sun_light_rows(bpy, scene, camera, same)
    return rows


def sandscape_look_colour(material):
    look = material.node_tree.nodes["Sandscape Look"]
    return tuple(look.inputs["Color"].default_value)


def directions(row):
    """(towards the camera, towards the sun) of a row, as the scene had them."""
    tilt, heading = math.radians(90 - row["view"]), math.radians(row["az"])
    view = (math.sin(tilt) * math.sin(heading), -math.sin(tilt) * math.cos(heading), math.cos(tilt))
    return np.array(view), air.sun_direction(math.radians(row["sun"]), 0.0)


def measured_balance(rows):
    """(towards the camera, towards the sun, the balance that was needed) of the rows, as arrays."""
    view, light = (np.array(side) for side in zip(*[directions(row) for row in rows], strict=True))
    means = (np.array([np.mean(row[k]) for row in rows]) for k in ("cycles", "eevee", "eevee_diffuse_sun"))
    return view, light, twin.target(*means)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", help="write the measurements here")
    parser.add_argument("--from-json", help="fit these measurements instead of rendering")
    parser.add_argument("--add-sun-light", action="store_true",
                        help="measure the sun-only Lambert plane for --from-json's rows")
    args = parser.parse_args(argv)
    rows = json.loads(pathlib.Path(args.from_json).read_text()) if args.from_json else measure()
    if args.add_sun_light:
        rows = add_sun_light(rows)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1))
    view, light, ratio = measured_balance(rows)
    v, l_, a = twin.angles(view, light, (0.0, 0.0, 1.0))
    coefficients = twin.fit(v, l_, a, ratio)
    fitted = twin.balance(view, light, (0.0, 0.0, 1.0), coefficients)
    error = fitted / ratio - 1.0
    print(f"balance fit: COEFFICIENTS = {tuple(round(c, 4) for c in coefficients)}")
    print(f"balance fit: balance {ratio.min():.2f}..{ratio.max():.2f}; fitted against measured: "
          f"mean |error| {np.abs(error).mean():.1%}, largest {np.abs(error).max():.1%}")


if __name__ == "__main__":
    main()
