"""The cloud layer's shadow in EEVEE (core.cloud_shadows): one mesh at the layer's base, "Sandscape
Cloud Shadows", seen by shadow rays only, covering where the clouds above let less than half the
sun's light through (outlined from a map of that light, made from the clouds' twin for the
scene's sun when the clouds are added). Opaque in EEVEE; Cycles sees it as fully transparent: it
shadows through the volume itself. Built only for a scene that renders with
EEVEE (Add Clouds again after switching engine, or after turning the sun); it drifts with the
wind as the clouds do.
"""

import bpy
import numpy as np

from ..core import atmosphere as air_twin
from ..core import cloud_shadows as twin
from ..node_groups import helper as h
from . import cloud_grid, cloud_sunlight, sky_eevee_ground
from . import ownership as own
from .shot import frames_per_second
from .sun_lamp import scene_sun, sun_angles

# The mesh covers where the clouds let less than this through: all or nothing, as EEVEE draws a
# partly transparent caster's shadow through a fixed stochastic pattern unless the sun's shadow
# Jitter redraws it every sample (a weight of 0.5 let 0.39 to 0.68 through, by the view; with
# Jitter 0.52, at three times the demo frame's time here), and a transparent caster over the
# whole sky cost the demo frame in EEVEE 2.5 times its time; an opaque mesh costs little.
HALF = 0.5
STALE_COSINE = 0.99995  # made for a sun over about half a degree from the scene's: remade
LOWEST_SUN = 0.5  # degrees: below it the layer's shadow falls beyond any box and none is cast


def wanted(scene):
    return scene.render.engine == "BLENDER_EEVEE"


def unshaded(scene):
    """The scene renders with EEVEE's Volume Shadows off and has a sun and a cloud layer whose grid
    carries no sun's light (procedural, or built before the sun or for Cycles): a cloud's
    underside gets the whole sun. The Volume Shadows are the artist's."""
    layer = own.scene_object(scene, own.CLOUDS)
    return (wanted(scene) and not scene.eevee.use_volumetric_shadows and layer is not None
            and not cloud_sunlight.baked(layer) and scene_sun(scene) is not None)


def caster(scene):
    return own.scene_object(scene, own.CLOUD_SHADOWS)


def remove(scene):
    sky_eevee_ground.set_sun_let_through(scene, 1.0)
    found = caster(scene)
    if found is None:
        return
    cloud_grid.stop_drift(found)
    own.remove_with_data(found)


def to_sun(scene, evaluated=True):
    """Unit vector towards the scene's sun lamp as the scene evaluates it (else as its matrix
    stands: a panel's draw evaluates nothing), or None (no sun, or one too low to cast the
    layer's shadow anywhere near)."""
    sun = scene_sun(scene)
    if sun is None:
        return None
    elevation, azimuth = sun_angles(scene, sun, evaluated)
    if elevation < np.radians(LOWEST_SUN):
        return None
    return air_twin.sun_direction(elevation, azimuth)


def stale(scene, evaluated=True):
    """True when the scene renders with EEVEE and its cloud shadows were made for another sun
    (or none were made for a layer that is there): Add Clouds would remake them."""
    if not wanted(scene) or own.scene_object(scene, own.CLOUDS) is None:
        return False
    found, direction = caster(scene), to_sun(scene, evaluated)
    if found is None or direction is None:
        return (found is None) != (direction is None)
    made_for = np.asarray(found.get("sandscape_sun_direction", (0.0, 0.0, 0.0)), np.float64)
    return float(np.dot(made_for, direction)) < STALE_COSINE


def _mesh(light, box, height):
    """The shaded ground's polygons (core.cloud_shadows.shadow_polygons) at the layer's base."""
    vertices, polygons = twin.shadow_polygons(twin.smoothed(light), box, HALF)
    mesh = bpy.data.meshes.new("Sandscape Cloud Shadows")
    mesh.from_pydata([(x, y, height) for x, y in vertices], [], polygons)
    mesh.validate()
    return mesh


def _ensure_object(scene, mesh):
    found = caster(scene)
    if found is None:
        found = bpy.data.objects.new("Sandscape Cloud Shadows", mesh)
        own.mark(found, own.OBJECT_KEY, own.CLOUD_SHADOWS)
        scene.collection.objects.link(found)
    else:
        own.replace_mesh(found, mesh)
    found.display_type = "WIRE"
    # Seen by EEVEE's shadow maps only: never by the camera, a reflection or a bounce.
    found.visible_camera = found.visible_diffuse = found.visible_glossy = False
    found.visible_transmission = found.visible_volume_scatter = False
    found.visible_shadow = True
    return found


def _build_material(found):
    """Opaque in EEVEE (an opaque caster costs its shadow maps least), clear in Cycles."""
    material = own.slot_material(found, own.CLOUD_SHADOWS)
    if material is None:
        material = own.mark(bpy.data.materials.new("Sandscape Cloud Shadows"), own.MATERIAL_KEY,
                            own.CLOUD_SHADOWS)
        found.data.materials.clear()
        found.data.materials.append(material)
    tree = material.node_tree
    tree.nodes.clear()
    opaque = h.add_node(tree, "ShaderNodeBsdfDiffuse", name="Sandscape Cloud Shadow Opaque",
                        inputs={"Color": (0.0, 0.0, 0.0, 1.0)})
    eevee = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape EEVEE Output", target="EEVEE")
    h.link(tree, opaque.outputs[0], eevee.inputs["Surface"])
    clear = h.add_node(tree, "ShaderNodeBsdfTransparent", name="Sandscape Cloud Shadow Cycles")
    cycles = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Cycles Output", target="CYCLES")
    h.link(tree, clear.outputs[0], cycles.inputs["Surface"])
    h.arrange(tree, set_widths=False)
    return material


def apply(scene, box, base, thickness, step, density_at, wind):
    """Build or update the shadow layer over box (xmin, ymin, xmax, ymax, in the clouds' frame-0
    space) for the layer from `base` up `thickness`, whose extinction is density_at(points) at
    frame 0; remove it where the scene does not render with EEVEE or has no sun high enough.
    Returns what was made (the object, the map's texels) or None."""
    direction = to_sun(scene) if wanted(scene) else None
    if direction is None:
        remove(scene)
        return None
    steps = twin.steps_for(thickness, direction, step)
    light = twin.transmittance(density_at, box, base, thickness, direction, steps)
    found = _ensure_object(scene, _mesh(light, box, base))
    _build_material(found)
    cloud_grid.drift_with_wind(found, wind, frames_per_second(scene))
    found["sandscape_sun_direction"] = [float(v) for v in direction]  # what the map was made for
    sky_eevee_ground.set_sun_let_through(scene, float(light.mean()))
    return {"object": found, "texels": light.shape}
