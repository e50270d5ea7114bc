"""The scene's sun lamp: Sandscape's own, made and turned to the settings, or the artist's, which
stays where they put it unless Aim Your Sun asks (and nothing animates it)."""

import math

import bpy
from mathutils import Euler, Matrix, Vector

from ..core import sun as sky_sun
from . import evaluation
from . import ownership as own

SUN_ENERGY = 4.0  # W/m² of a new sun lamp when its light does not come from the sky model
SKY_SUN_SIZE = 0.009512044  # radians: the Sky Texture's default sun disc, which the lamp copies


def scene_sun(scene):
    """Our sun in this scene, else the scene's first sun lamp, else None."""
    ours = own.scene_object(scene, own.SUN)
    if ours is not None:
        return ours
    return next((o for o in scene.objects if o.type == "LIGHT" and o.data.type == "SUN"), None)


def sun_rotation(elevation, azimuth):
    """Euler rotation of a sun lamp that shines from (elevation, azimuth): its +Z points at the sun."""
    return (math.pi / 2 - elevation, 0.0, math.pi - azimuth)


def sun_angles(scene, sun, evaluated=True):
    """(elevation, azimuth) a sun lamp shines from, as the scene evaluates it (else as its matrix
    stands: a panel's draw evaluates nothing): its world +Z."""
    matrix = evaluation.world_matrix(scene, sun) if evaluated else sun.matrix_world
    axis = matrix.to_3x3() @ Vector((0.0, 0.0, 1.0))
    if axis.length == 0.0:
        return 0.0, 0.0
    axis.normalize()
    return math.asin(max(-1.0, min(1.0, axis.z))), math.atan2(axis.x, axis.y)


def is_ours(sun):
    return sun.get(own.OBJECT_KEY) == own.SUN


def moves(obj):
    """True when keys, drivers or constraints turn the object: what Aim Your Sun set would not last."""
    animation = obj.animation_data
    keyed = animation is not None and (animation.action is not None or len(animation.drivers) > 0)
    return keyed or len(obj.constraints) > 0


def ensure_sun(scene, elevation, azimuth, from_sky=True, aim_theirs=False):
    """The scene's sun lamp and where it shines from: (sun, elevation, azimuth, followed, changes).

    Ours (made when the scene has no sun) is turned to (elevation, azimuth) and, from_sky, given
    the strength and colour of the sky model's own sun there (core/sun.py), so sky and lamp light
    the scene as one. The artist's sun is theirs: it stays as it is and the sky follows it
    (followed True), unless aim_theirs and nothing animates it. changes: what was changed on the
    artist's sun, for the report.
    """
    sun = scene_sun(scene)
    if sun is not None and not is_ours(sun):
        if not aim_theirs or moves(sun):
            return (sun, *sun_angles(scene, sun), True, [])
    if sun is None:
        sun = own.mark(bpy.data.objects.new("Sandscape Sun", bpy.data.lights.new("Sandscape Sun", "SUN")),
                       own.OBJECT_KEY, own.SUN)
        sun.data.energy = SUN_ENERGY
        scene.collection.objects.link(sun)
    world = evaluation.world_matrix(scene, sun)
    light = sun.data
    before = (world.col[2].to_3d(), light.energy, tuple(light.color), light.angle)
    turn = Euler(sun_rotation(elevation, azimuth))
    if is_ours(sun) and sun.parent is None:
        sun.rotation_mode = "XYZ"
        sun.rotation_euler = turn
    else:  # in world space, so a parented sun shines from the angles too; its place and scale stay
        place, _, scale = world.decompose()
        sun.matrix_world = Matrix.LocRotScale(place, turn.to_quaternion(), scale)
    if from_sky:
        light.energy, light.color = sky_sun.lamp(elevation)
        light.angle = SKY_SUN_SIZE
    changes = []
    if not is_ours(sun):
        if before[0].length == 0.0 or (before[0].normalized() - turn.to_matrix().col[2]).length > 1e-6:
            changes.append(f"your sun '{sun.name}' turned to {math.degrees(elevation):.1f}° up, azimuth "
                           f"{math.degrees(azimuth) % 360:.1f}°")
        if abs(before[1] - light.energy) > 1e-6:
            changes.append(f"its strength {before[1]:.4g} → {light.energy:.4g} W/m²")
        if max(abs(a - b) for a, b in zip(before[2], light.color, strict=True)) > 1e-6:
            changes.append(f"its colour ({', '.join(f'{c:.2f}' for c in before[2])}) → "
                           f"({', '.join(f'{c:.2f}' for c in light.color)})")
        if abs(before[3] - light.angle) > 1e-6:
            changes.append(f"its angle {math.degrees(before[3]):.2f}° → {math.degrees(light.angle):.2f}°")
    return sun, elevation, azimuth, False, changes
