"""The clouds' shadow on the ground in EEVEE, whose volumes shadow no surface: a mesh at the
layer's base that only shadow rays see, where the twin says the layer lets less than half the
sun's light through (core.cloud_shadows). Checked against exp(-sigma d), and against Cycles'
shadow through the volume on the same ground.
"""

import math
import types

import bpy
import numpy as np
import pytest
from test_clouds import UP_SIZE, black_sky_and_point_sun

from core import cloud_shadows as twin
from devtools import operators, readback, scenes

SHADOW_SIZE = 64  # pixels of the ground seen from above
# EEVEE against Cycles on 625 m pixels: EEVEE's all-or-nothing shadow against Cycles' share, and
# both engines' noise, differ at the clouds' edges pixel by pixel (0.078 when written); blurred
# over 3x3 pixels the shadows agree.
CYCLES_TOLERANCE = 0.05  # mean |EEVEE - Cycles| of the light let through, both blurred 3x3
CORRELATION_FLOOR = 0.9  # of the two pictures of the light let through, pixel by pixel
MEAN_TOLERANCE = 0.02  # of the light let through over the ground
SHARE_TOLERANCE = 0.04  # the share of ground in shadow (less than half the light)


@pytest.mark.parametrize("elevation_degrees", [45.0, 6.0])
def test_the_map_lets_through_exp_minus_sigma_d(elevation_degrees):
    """A uniform layer: every texel lets exp(-sigma d / sin e) through, d its thickness."""
    elevation = math.radians(elevation_degrees)
    to_sun = (0.0, math.cos(elevation), math.sin(elevation))
    sigma, thickness = 2e-4, 1200.0
    steps = twin.steps_for(thickness, to_sun, 200.0)
    light = twin.transmittance(lambda p: np.full(p.shape[:-1], sigma), (0, 0, 4000, 2000), 1000.0, thickness,
                               to_sun, steps, texels=32)
    assert light.shape == (16, 32)
    assert light == pytest.approx(math.exp(-sigma * thickness / math.sin(elevation)), rel=1e-9)


def _sun_scene(scene, elevation_degrees):
    """Ground seen from above under the artist's sun, as wide as the sky's sun disc (Add
    Atmosphere's; its shadow Jitter off, Blender's default), and a black sky."""
    bpy.ops.mesh.primitive_plane_add(size=3 * UP_SIZE)
    scenes.camera("ORTHO", location=(0.0, 0.0, 500.0), ortho_scale=UP_SIZE)
    scene.camera.data.clip_end = 1e6
    lamp = black_sky_and_point_sun(scene)
    lamp.rotation_euler = (math.radians(90.0 - elevation_degrees), 0.0, math.radians(30.0))
    lamp.data.angle = 0.009512044  # addon.sun_lamp.SKY_SUN_SIZE
    lamp.data.use_shadow_jitter = False
    scene.render.resolution_x = scene.render.resolution_y = SHADOW_SIZE
    return lamp


def _blurred(light):
    """The 3x3 box mean, the frame's edge pixels dropped."""
    return sum(np.roll(np.roll(light, i, 0), j, 1) for i in (-1, 0, 1) for j in (-1, 0, 1))[1:-1, 1:-1] / 9.0


def _caster(scene):
    return next((o for o in scene.objects if o.get("sandscape_object") == "cloud_shadows"), None)


@pytest.mark.sweep  # 60-70 s with EEVEE's first render; the map's own checks stay in make test
def test_eevee_shades_the_ground_under_the_clouds_as_cycles_does(eevee_scene):
    """Ground seen from above under Add Clouds' grid and a sun at 40 degrees, a black sky: the
    light let through, pixel by pixel, in EEVEE (through the shadow layer) against Cycles (through
    the volume). Without the layer EEVEE lets everything through."""
    scene = eevee_scene
    scene.eevee.taa_render_samples = 8  # an opaque caster's shadow: only the edges' anti-aliasing
    _sun_scene(scene, 40.0)
    values = {"coverage": 0.5, "seed": 5, "map_scale": 2000.0, "reach": 1.0, "voxel": 200.0}
    lit_eevee = readback.render(scene)[..., 0]
    assert bpy.ops.sandscape.add_clouds(**values) == {"FINISHED"}
    caster = _caster(scene)
    assert caster is not None and not caster.visible_camera and caster.visible_shadow
    eevee = readback.render(scene)[..., 0] / lit_eevee
    caster.hide_render = True
    bare = readback.render(scene)[..., 0] / lit_eevee
    caster.hide_render = False
    readback.cycles_scene(scene, (SHADOW_SIZE, SHADOW_SIZE), samples=4)
    scene.cycles.volume_biased = True  # ray marching, as the quality presets set it
    scene.cycles.volume_bounces = scene.cycles.max_bounces = 0
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    layer.hide_render = True
    lit_cycles = readback.render(scene)[..., 0]
    layer.hide_render = False
    cycles = readback.render(scene)[..., 0] / lit_cycles
    error = np.abs(_blurred(eevee) - _blurred(cycles))
    correlation = np.corrcoef(eevee.ravel(), cycles.ravel())[0, 1]
    print(f"cloud shadows: EEVEE against Cycles, 3x3-blurred mean |error| {error.mean():.3f}, per pixel "
          f"{np.abs(eevee - cycles).mean():.3f}, correlation {correlation:.3f}; ground in shadow "
          f"{(eevee < 0.5).mean():.3f} / {(cycles < 0.5).mean():.3f}, light let through "
          f"{eevee.mean():.3f} / {cycles.mean():.3f}")
    assert np.isfinite(eevee).all()
    assert bare.mean() > 0.95  # EEVEE's volume shadows no surface: the layer does
    assert 0.2 < (cycles < 0.5).mean() < 0.8
    assert correlation >= CORRELATION_FLOOR
    assert error.mean() <= CYCLES_TOLERANCE
    assert eevee.mean() == pytest.approx(cycles.mean(), abs=MEAN_TOLERANCE)
    assert (eevee < 0.5).mean() == pytest.approx((cycles < 0.5).mean(), abs=SHARE_TOLERANCE)


def _shadow_things():
    return (sum(o.get("sandscape_object") == "cloud_shadows" for o in bpy.data.objects),
            sum(m.get("sandscape_material") == "cloud_shadows" for m in bpy.data.materials),
            sum(m.name.startswith("Sandscape Cloud Shadows") for m in bpy.data.meshes))


def _shaded_area(caster):
    """The area the caster's polygons cover, in the scene's units squared (x-y, at its base)."""
    mesh = caster.data
    points = np.array([v.co[:2] for v in mesh.vertices])
    area = 0.0
    for polygon in mesh.polygons:
        x, y = points[list(polygon.vertices)].T
        area += 0.5 * (x @ np.roll(y, -1) - y @ np.roll(x, -1))
    return area


def test_the_shadow_layer_is_made_for_eevee_once_and_goes_with_it():
    """Only a scene that renders with EEVEE gets the layer; Add Clouds again updates it (one
    object, material and mesh); back in Cycles it goes, leaving nothing behind."""
    scene = bpy.context.scene
    _sun_scene(scene, 40.0)
    values = {"coverage": 0.5, "seed": 5, "map_scale": 2000.0, "reach": 1.0, "voxel": 400.0}
    scene.render.engine = "CYCLES"
    assert bpy.ops.sandscape.add_clouds(**values) == {"FINISHED"}
    assert _shadow_things() == (0, 0, 0)
    scene.render.engine = "BLENDER_EEVEE"
    result, reports = operators.run_execute("sandscape.add_clouds", **values)
    assert result == {"FINISHED"}
    assert _shadow_things() == (1, 1, 1)
    assert any("INFO" in kinds and "EEVEE's shadow of it" in text for kinds, text in reports)
    assert len(_caster(scene).data.polygons) > 10 and _shaded_area(_caster(scene)) > 0
    assert bpy.ops.sandscape.add_clouds(**{**values, "coverage": 0.6}) == {"FINISHED"}
    assert _shadow_things() == (1, 1, 1)
    scene.render.engine = "CYCLES"
    assert bpy.ops.sandscape.add_clouds(**values) == {"FINISHED"}
    assert _shadow_things() == (0, 0, 0)


def test_add_clouds_says_when_eevee_would_render_them_unshaded(sandscape):
    """A grid built with a sun lamp carries its sun's light (addon/cloud_sunlight.py); a procedural
    layer does not, and with EEVEE's Volume Shadows off (the artist's; the presets leave them off)
    its undersides get the whole sun: Add Clouds says so, and the Clouds section, until the
    shadows are on (in Cycles nothing is said)."""
    from test_ui import RecordingLayout

    def labels():
        layout = RecordingLayout()
        bpy.types.SANDSCAPE_PT_clouds.draw(types.SimpleNamespace(layout=layout), bpy.context)
        return [c[1] for c in layout.calls if c[0] == "label"]

    scene = bpy.context.scene
    _sun_scene(scene, 40.0)
    values = {"coverage": 0.5, "seed": 5, "map_scale": 2000.0, "reach": 1.0, "voxel": 400.0}
    scene.render.engine = "BLENDER_EEVEE"
    assert operators.run_execute("sandscape.apply_quality_preset", preset="DRAFT")[0] == {"FINISHED"}
    assert not scene.eevee.use_volumetric_shadows
    assert sandscape.ui.panels.CLOUDS_UNSHADED_IN_EEVEE not in labels()  # no clouds yet
    result, reports = operators.run_execute("sandscape.add_clouds", **values)
    assert result == {"FINISHED"} and not any("unshaded" in text for _, text in reports)
    assert sandscape.ui.panels.CLOUDS_UNSHADED_IN_EEVEE not in labels()
    result, reports = operators.run_execute("sandscape.add_clouds", evaluation="PROCEDURAL", **values)
    assert result == {"FINISHED"} and not scene.eevee.use_volumetric_shadows
    assert any("in EEVEE unshaded" in text for _, text in reports)
    assert sandscape.ui.panels.CLOUDS_UNSHADED_IN_EEVEE in labels()
    scene.eevee.use_volumetric_shadows = True
    assert sandscape.ui.panels.CLOUDS_UNSHADED_IN_EEVEE not in labels()
    scene.render.engine, scene.eevee.use_volumetric_shadows = "CYCLES", False
    assert sandscape.ui.panels.CLOUDS_UNSHADED_IN_EEVEE not in labels()


def test_the_shadow_layer_drifts_with_the_clouds_in_plain_blender(tmp_path):
    """Saved and opened with Sandscape off and Python auto-run off, as on a farm: the mesh moves
    with the clouds' grid at a later frame, and its outline is in the file."""
    from devtools import session

    scene = bpy.context.scene
    _sun_scene(scene, 40.0)
    scene.sandscape_atmosphere.wind = (4.0, -2.0, 0.0)
    scene.render.engine = "BLENDER_EEVEE"
    assert bpy.ops.sandscape.add_clouds(coverage=0.5, seed=5, map_scale=2000.0, reach=1.0,
                                        voxel=400.0) == {"FINISHED"}
    path = tmp_path / "shadows.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    with session.extension_off():
        bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=False)
        scene = bpy.context.scene
        scene.frame_set(100)
        caster = _caster(scene)
        layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
        seconds = 100 / (scene.render.fps / scene.render.fps_base)
        drifted = (4.0 * seconds, -2.0 * seconds)
        assert tuple(caster.matrix_world.translation)[:2] == pytest.approx(drifted, abs=1e-3)
        assert tuple(caster.matrix_world.translation) == pytest.approx(tuple(layer.matrix_world.translation))
        assert 0.2 < _shaded_area(caster) / UP_SIZE**2 < 0.9  # the clouds' shadows, in the file


def test_turning_the_sun_remakes_the_shadows_or_says_so(sandscape):
    """Add Atmosphere turning the sun remakes EEVEE's cloud shadows for it (reported); a sun
    turned by hand makes the Clouds section say they are out of date; a sun under half a degree
    takes them away."""
    from test_ui import RecordingLayout

    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=3 * UP_SIZE)
    scenes.camera("ORTHO", location=(0.0, 0.0, 500.0), ortho_scale=UP_SIZE).data.clip_end = 1e6
    scene.render.engine = "BLENDER_EEVEE"
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(40.0), math.radians(30.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    assert bpy.ops.sandscape.add_clouds(coverage=0.5, seed=5, map_scale=2000.0, reach=1.0,
                                        voxel=400.0) == {"FINISHED"}
    shadows = sandscape.addon.cloud_shadows
    assert not shadows.stale(scene)

    def made_for():
        return np.array(list(_caster(scene)["sandscape_sun_direction"]))

    first = made_for()
    air.sun_elevation, air.sun_azimuth = math.radians(25.0), math.radians(240.0)
    result, reports = operators.run_execute("sandscape.add_atmosphere")
    assert result == {"FINISHED"} and ("remade for this sun" in " ".join(text for _, text in reports))
    assert made_for() @ shadows.to_sun(scene) > 0.99999 and made_for() @ first < 0.9
    sun = next(o for o in scene.objects if o.get("sandscape_object") == "sun")
    sun.rotation_euler[0] += math.radians(10.0)  # turned by hand
    bpy.context.view_layer.update()
    layout = RecordingLayout()
    bpy.types.SANDSCAPE_PT_clouds.draw(types.SimpleNamespace(layout=layout), bpy.context)
    assert ("label", sandscape.ui.panels.CLOUD_SHADOWS_STALE) in [c[:2] for c in layout.calls]
    air.sun_elevation = math.radians(0.2)
    result, reports = operators.run_execute("sandscape.add_atmosphere")
    assert _caster(scene) is None and any("removed" in text for _, text in reports)


def _map_in(scale):
    """Add Clouds' shadows in a scene whose unit is `scale` metres: the ground, camera and sun of
    the other tests at the same size in metres; (their area in m², their vertices in metres)."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.scale_length = scale
    _sun_scene(scene, 40.0)
    for obj in scene.objects:
        obj.location = obj.location / scale
    ground = next(o for o in scene.objects if o.type == "MESH")
    ground.scale = ground.scale / scale
    scene.camera.data.ortho_scale = UP_SIZE / scale
    scene.camera.data.clip_end = 1e6 / scale
    scene.render.engine = "BLENDER_EEVEE"
    values = {"coverage": 0.5, "seed": 5, "map_scale": 2000.0 / scale, "reach": 1.0 / scale,
              "voxel": 400.0 / scale}
    assert bpy.ops.sandscape.add_clouds(**values) == {"FINISHED"}
    caster = _caster(scene)
    return _shaded_area(caster) * scale**2, np.array([v.co[:] for v in caster.data.vertices]) * scale


def test_a_centimetre_scene_gets_the_same_shadows():
    """Unit scale 0.01 (a unit is a centimetre), the same sky and ground in metres: the same
    shadows over the same ground."""
    area, corners = _map_in(1.0)
    centimetre_area, centimetre_corners = _map_in(0.01)
    assert 0.2 < area / UP_SIZE**2 < 0.9
    assert centimetre_area == pytest.approx(area, rel=0.005)
    assert corners.min(0) == pytest.approx(centimetre_corners.min(0), rel=1e-3, abs=1.0)
