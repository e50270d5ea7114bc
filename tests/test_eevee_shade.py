"""The sand's EEVEE output in the shade (issue 27): the balance on the sun's light brightens or dims
the sun's light only (its fit corrects how EEVEE lights sand under the sun: Lambert against
Cycles' rough diffuse and sheen), and the shade, lit by the sky and the haze alone, gets the
ambient balance: it comes out as Cycles' shade does; and lit glints keep to where the sun reaches
(EEVEE's world light has no shadow: their facets in the shade mirrored the bright sky round the
sun). Skips where no OpenGL context can be made."""

import math

import bpy
import numpy as np
import pytest
from conftest import EEVEE_SIZE as SIZE  # the eevee_scene fixture's

from core import atmosphere as air
from devtools import readback, scenes

GOAL = 0.15  # issue 27: EEVEE's sand within 15 % of Cycles', in the wall's shadow and in the sun
LIT_GAIN = 1.3  # the balance brightens the lit sand with the sun behind the camera at least this much
LIT_DIM = 0.85  # and dims it under a high sun ahead at least this much
GLINTS_IN_SHADE = 0.005  # what lit glints may add to the shade's brightness in EEVEE (none in Cycles)
GLINTS_IN_SUN = 0.003  # what Journey's lit glints at MIRROR_IOR must add to the sun's in EEVEE


def _masks(scene, camera, to_sun):
    """(in the wall's shadow, in sun) among the ground's pixels, rows bottom-up, from a ray per pixel
    (the dust box, a mesh too, hidden from the rays)."""
    hits = scenes.pixel_hits(scene, camera, *SIZE, to_sun)
    ground = hits["hit"] & (hits["normal_z"] > 0.99)
    return _inner(ground & ~hits["sunlit"]), _inner(ground & hits["sunlit"])


def _inner(mask, steps=2):
    """The mask less `steps` pixels at its edges: the pixel filter and the shadow's soft edge mix
    the two sides there."""
    for _ in range(steps):
        padded = np.pad(mask, 1)
        mask = mask & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
    return mask


def _wall_scene(scene, elevation, azimuth, wall_distance, look="PHYSICAL"):
    """Sand (`look`) on a wide plane under Add Atmosphere's sun, a camera at eye level and a wall
    8 m high, 3 m wide, `wall_distance` sunward of a ground point left of the view's middle, whose
    shadow falls in view: (scene, ground, shade mask, sunlit mask)."""
    bpy.ops.mesh.primitive_plane_add(size=400)
    ground = bpy.context.active_object
    assert bpy.ops.sandscape.add_sand_material(look=look) == {"FINISHED"}
    settings = scene.sandscape_atmosphere
    settings.sun_elevation, settings.sun_azimuth = math.radians(elevation), math.radians(azimuth)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 1.6), rotation=(math.radians(80), 0.0, 0.0), lens=35)
    to_sun = air.sun_direction(math.radians(elevation), math.radians(azimuth))
    level = to_sun[:2] / np.linalg.norm(to_sun[:2])
    base = np.array([-1.5, 9.0]) + wall_distance * level
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(*base, 4.0))
    wall = bpy.context.active_object
    wall.scale = (3.0, 0.3, 8.0)
    wall.rotation_euler.z = math.atan2(level[1], level[0]) + math.pi / 2
    scene.frame_set(1)
    shade, lit = _masks(scene, camera, to_sun)
    assert shade.sum() >= 30 and lit.sum() >= 30, (shade.sum(), lit.sum())
    return scene, ground, shade, lit


def _render(scene):
    return readback.render(scene)[..., :3].astype(np.float64)


# Both suns in make stress (37-44 s each on software OpenGL; make test went past its 10 minutes):
# make test checks the balance through test_eevee.py's sand brightness against Cycles.
@pytest.mark.parametrize("elevation,azimuth,wall_distance",
                         [pytest.param(15.0, 150.0, 12.0, marks=pytest.mark.sweep),
                          pytest.param(50.0, 330.0, 4.0, marks=pytest.mark.sweep)])
def test_the_balance_brings_the_sun_and_the_shade_to_cycles(eevee_scene, sandscape, elevation, azimuth,
                                                            wall_distance):
    """Sand under a 15 degree sun behind the camera (where the balance is largest) or a 50 degree
    sun ahead (where it is smallest), and a wall whose shadow falls across the ground in view
    (glints off): the balance lifts the lit sand by at least LIT_GAIN, or dims it to LIT_DIM or
    less, and both the lit sand and the wall's shadow come within GOAL of Cycles'. The first
    build, a diffuse, lifted the shade's sky light with the sun's (x2.04 at 15 degrees); where the
    balance dims it scaled the shade too (x0.753 at 50 degrees). When written (5.2): at 15 degrees
    lit -11.1 %, shadow +2.9 % of Cycles (without the balance -59.6 %, -17.4 %); at 50 degrees lit
    +3.7 %, shadow +11.8 % (+68.3 %, +4.6 %: EEVEE's world light on the shadow is not blocked by
    the wall, Cycles' is). With the glints on, they add at most GLINTS_IN_SHADE to the shadow
    (+0.00 % when written; +3.4 % before they kept to the sun)."""
    scene, ground, shade, lit = _wall_scene(eevee_scene, elevation, azimuth, wall_distance)

    glinting = _render(scene)
    material = ground.active_material
    sandscape.addon.sand.glint_node(material).inputs["Threshold"].default_value = 1.0  # no grain glints
    balanced = _render(scene)
    scene.render.engine, scene.cycles.samples, scene.cycles.use_denoising = "CYCLES", 16, False
    cycles = _render(scene)
    scene.render.engine = "BLENDER_EEVEE"
    sandscape.addon.sand_eevee.attach(material, scene, sandscape.addon.sand.look_node(material), None)
    plain = _render(scene)
    lit_gain = balanced[lit].mean() / plain[lit].mean()
    shade_error = balanced[shade].mean() / cycles[shade].mean() - 1.0
    lit_error = balanced[lit].mean() / cycles[lit].mean() - 1.0
    glints_in_shade = glinting[shade].mean() / balanced[shade].mean() - 1.0
    print(f"the balance, sun {elevation:g} degrees: lit sand x{lit_gain:.3f}, the wall's shadow "
          f"x{balanced[shade].mean() / plain[shade].mean():.3f}; against Cycles: lit {lit_error:+.1%}, "
          f"shadow {shade_error:+.1%} (without the balance "
          f"{plain[lit].mean() / cycles[lit].mean() - 1.0:+.1%}, "
          f"{plain[shade].mean() / cycles[shade].mean() - 1.0:+.1%}); the glints add "
          f"{glints_in_shade:+.2%} to the shadow, {glinting[lit].mean() / balanced[lit].mean() - 1.0:+.2%} "
          "to the sun")
    assert np.isfinite(glinting).all() and np.isfinite(balanced).all()
    assert lit_gain >= LIT_GAIN if elevation < 30.0 else lit_gain <= LIT_DIM
    assert abs(lit_error) <= GOAL and abs(shade_error) <= GOAL
    assert abs(glints_in_shade) <= GLINTS_IN_SHADE


@pytest.mark.sweep  # make test checks the lit glints' blend on Physical Sand (test_eevee.py)
def test_journeys_glints_keep_to_the_sun_in_eevee(eevee_scene, sandscape):
    """Journey's EEVEE output under a 15 degree sun behind the camera: its glints add at most
    GLINTS_IN_SHADE to the wall's shadow (+2.19 % before they kept to the sun, as the physical
    sand's do, more than the +0.88 % they added to the sun; now +0.00 %) and still sparkle in the
    sun (+0.85 %, 5.0 +0.89 %, when written with full mirrors). The facets get MIRROR_IOR: with the
    sun behind the camera quartz's face-on 4.5 % added +0.17 %, and the test follows where glints
    go, not how bright they are (at it, +0.49 %)."""
    from test_lit_glints import MIRROR_IOR

    scene, ground, shade, lit = _wall_scene(eevee_scene, 15.0, 150.0, 12.0, look="JOURNEY")
    sandscape.addon.sand.glint_node(ground.active_material).inputs["IOR"].default_value = MIRROR_IOR
    glinting = _render(scene)
    sandscape.addon.sand.glint_node(ground.active_material).inputs["Threshold"].default_value = 1.0
    plain = _render(scene)
    in_shade = glinting[shade].mean() / plain[shade].mean() - 1.0
    in_sun = glinting[lit].mean() / plain[lit].mean() - 1.0
    print(f"Journey in EEVEE: the glints add {in_shade:+.2%} to the wall's shadow, {in_sun:+.2%} to the sun")
    assert np.isfinite(glinting).all()
    assert abs(in_shade) <= GLINTS_IN_SHADE and in_sun > GLINTS_IN_SUN
