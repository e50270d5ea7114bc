"""The bpy side of the cloud layer: one object, "Sandscape Clouds", over the sky the scene camera
can see from wherever it stands over the shot, out to Reach in every direction (so turning the
camera or changing the frame size leaves no edge in view). The density fades to zero inside
the box's sides (core.clouds.region_window), so no side of the box ever shows.

An object volume, not a world volume: a world volume would block the sun lamp. Two routes:
- Voxel Grid (default): geometry nodes evaluate Weather Map -> Cloud Density once per voxel
  (addon/cloud_grid.py); the material reads the grid. The grid drifts with the wind.
- Procedural: a box whose material evaluates Weather Map -> Cloud Density at every step; its
  Frame inputs are driven by the expression `frame`, evaluated without Python auto-run.
Either way the density scatters with a dual-lobe or Mie phase.
"""

import math

import bpy
import numpy as np

from ..core import cloud_shadows as shadow_twin
from ..core import clouds as twin
from ..node_groups import cloud_density, weather_map
from ..node_groups import helper as h
from . import cloud_grid, cloud_shadows, cloud_sunlight, evaluation, far_haze, sky_eevee_clouds, units
from . import ownership as own
from .shot import camera_views, frames_per_second, reach_points
from .sun_lamp import scene_sun

# A grid finer than this many voxels is followed by the exact twin (evaluating the twin at every
# voxel takes about 8 s a million here; so fine a grid holds most of the exact twin's detail).
SHADOW_TWIN_VOXELS = 2_000_000
SAMPLES = 192  # points along each side of the layer's box where the weather map is checked for cloud

def scene_settings(scene):
    """scene.sandscape_clouds as apply() takes it: lengths in scene units, the image by name."""
    stored = scene.sandscape_clouds
    values = {p.identifier: getattr(stored, p.identifier) for p in stored.bl_rna.properties
              if p.identifier not in ("rna_type", "name", "weather_image")}
    values["weather_image"] = stored.weather_image.name if stored.weather_image else ""
    return values


def parameters(scene, s):
    """The twin's parameters (core.clouds.density) in scene units from settings s (scene units)."""
    per_unit = units.metres_per_unit(scene)
    return {"base": s["base"], "thickness": s["thickness"], "coverage": s["coverage"],
            "map_scale": s["map_scale"], "shape_scale": s["shape_scale"], "detail_scale": s["detail_scale"],
            "erosion": s["erosion"], "curl": s["curl"], "skew": s["skew"], "density": s["density"] * per_unit,
            "precipitation": s["precipitation"],
            "cloud_type": None if s["cloud_type"] == "MIXED" else twin.TYPE_VALUES[s["cloud_type"]],
            "seed": s["seed"], "wind": tuple(scene.sandscape_atmosphere.wind), "time": 0.0}


def coverage_function(s, image):
    """Coverage at ground points xy (..., 2), at frame 0: the procedural map's twin or the image."""
    if s["weather_source"] == "IMAGE":
        red = sky_eevee_clouds.weather_red(image)
        height, width = red.shape

        def from_image(xy):
            uv = xy / s["map_size"] + 0.5
            col = np.clip((uv[..., 0] % 1.0 * width).astype(int), 0, width - 1)
            row = np.clip((uv[..., 1] % 1.0 * height).astype(int), 0, height - 1)
            return red[row, col]
        return from_image

    def procedural(xy):
        return twin.map_coverage(twin.weather_noise(xy, s["map_scale"], s["seed"]), s["coverage"])
    return procedural


def layer_box(scene, s):
    """The layer's horizontal box (xmin, ymin, xmax, ymax), scene units, and its fade width: what
    the camera can see out to Reach in every direction from wherever it stands over the shot
    (so a turned camera or another frame size stays inside), padded by the fade."""
    bpy.context.view_layer.update()  # matrix_world of a lamp or camera moved by a script
    views = camera_views(scene, scene.camera)
    cameras = np.array([view["matrix"][:2, 3] for view in views])
    seen = reach_points(views, s["reach"])[:, :2]
    fade = twin.fade_width(s["shape_scale"], s["reach"])
    return twin.layer_region(cameras, seen, s["reach"], fade), fade


def twin_density(scene, s, image, done):
    """The layer's extinction at frame 0 as the twin gives it: density_at(points (..., 3)); for a
    grid, the twin's cloudiness at its voxels interpolated as Cycles does (between voxels the
    exact density holds detail the grid does not). A painted map's coverage is read as the shader
    reads it; its precipitation and type are the settings'."""
    p = {**parameters(scene, s), "region": (*done["region"], done["fade"])}
    if s["weather_source"] == "IMAGE":
        cover_at = coverage_function(s, image)
        p["cloud_type"] = 0.5 if p["cloud_type"] is None else p["cloud_type"]

        def cloudiness(points):
            return twin.shaped_cloudiness(points, p, cover_at(np.asarray(points)[..., :2]))
    else:
        def cloudiness(points):
            return twin.cloudiness(points, p)
    if s["evaluation"] != "GRID" or done["voxels"] > SHADOW_TWIN_VOXELS:
        return lambda points: twin.density_from_cloudiness(cloudiness(points), p)
    corner, _, counts = done["box"]
    axes = [corner[axis] + np.arange(counts[axis]) * done["voxel"] for axis in range(3)]
    voxels = cloudiness(np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1))
    return lambda points: twin.density_from_cloudiness(
        shadow_twin.trilinear(voxels, corner, done["voxel"], points), p)


def shot_seconds(scene):
    fps = frames_per_second(scene)
    return scene.frame_start / fps, scene.frame_end / fps


def remove_layer(scene):
    layer = own.scene_object(scene, own.CLOUDS)
    if layer is not None:
        cloud_grid.remove_modifier(layer)
        own.remove_with_data(layer)
    cloud_shadows.remove(scene)
    far_haze.remove(scene)
    sky_eevee_clouds.follow_scene(scene)


def ensure_layer(scene):
    layer = own.scene_object(scene, own.CLOUDS)
    if layer is None:
        layer = own.new_volume_object(scene, "Sandscape Clouds", own.CLOUDS)
    if layer.active_material is None or layer.active_material.get(own.MATERIAL_KEY) != own.CLOUD_MATERIAL:
        material = own.mark(bpy.data.materials.new("Sandscape Clouds"), own.MATERIAL_KEY, own.CLOUD_MATERIAL)
        layer.data.materials.clear()
        layer.data.materials.append(material)
    return layer


def _drive_frame(node):
    evaluation.drive_by_frame(node.inputs["Frame"])


def density_inputs(scene, s, region, fade, frame_zero):
    """The Cloud Density group's inputs for settings s, fading out inside region."""
    p = parameters(scene, s)
    fps = frames_per_second(scene)
    xmin, ymin, xmax, ymax = region
    return {"Base": p["base"], "Thickness": p["thickness"], "Density": p["density"],
            "Shape Scale": p["shape_scale"], "Detail Scale": p["detail_scale"], "Erosion": p["erosion"],
            "Curl": p["curl"], "Skew": p["skew"], "Seed": float(s["seed"]), "FPS": fps,
            "Wind": tuple(scene.sandscape_atmosphere.wind), "Region Min": (xmin, ymin, 0.0),
            "Region Max": (xmax, ymax, 0.0), "Region Fade": fade, "Precipitation": s["precipitation"],
            "Type": 0.5 if p["cloud_type"] is None else p["cloud_type"],
            **({"Frame": 0.0} if frame_zero else {})}


def weather_inputs(scene, s):
    """The Weather Map group's inputs and the outputs linked on to the density (one type
    everywhere: the type's noise stays unlinked, so it is never evaluated)."""
    p = parameters(scene, s)
    mixed = s["cloud_type"] == "MIXED"
    fps = frames_per_second(scene)
    inputs = {"Coverage": s["coverage"], "Precipitation": s["precipitation"],
              "Type": 0.5 if mixed else p["cloud_type"], "Mixed Types": float(mixed),
              "Map Scale": p["map_scale"], "Seed": float(s["seed"]), "FPS": fps,
              "Wind": tuple(scene.sandscape_atmosphere.wind)}
    return {"inputs": inputs, "linked": ("Coverage", "Type") if mixed else ("Coverage",),
            "uv_scale": (1 / s["map_size"], 1 / s["map_size"], 0.0)}


def scattering(tree, density, s):
    """density socket -> Volume Scatter with the chosen phase; returns the volume socket."""
    if s["phase"] == "MIE":
        scatter = h.add_node(tree, "ShaderNodeVolumeScatter", name="Sandscape Cloud Droplets",
                             label="Droplets (Mie)", phase="MIE",
                             inputs={"Color": (1.0, 1.0, 1.0, 1.0), "Diameter": s["droplet_size"]})
        h.link(tree, density, scatter.inputs["Density"])
        return scatter.outputs[0]
    lobes = []
    for label, g in (("Forward Lobe", s["forward"]), ("Back Lobe", s["back"])):
        lobe = h.add_node(tree, "ShaderNodeVolumeScatter", name=f"Sandscape Cloud {label}", label=label,
                          phase="HENYEY_GREENSTEIN", inputs={"Color": (1, 1, 1, 1), "Anisotropy": g})
        h.link(tree, density, lobe.inputs["Density"])
        lobes.append(lobe)
    blend = h.add_node(tree, "ShaderNodeMixShader", name="Sandscape Cloud Lobes", label="Back Share",
                       inputs={"Fac": s["back_weight"]})
    h.link(tree, lobes[0].outputs[0], blend.inputs[1])
    h.link(tree, lobes[1].outputs[0], blend.inputs[2])
    return blend.outputs[0]


def _clear(tree):
    if tree.animation_data is not None:
        tree.animation_data_clear()
    tree.nodes.clear()


def grid_wet(s):
    """The grid's clamp: a painted map's precipitation varies over the ground, so the wettest cloud's."""
    return float(twin.wet(1.0 if s["weather_source"] == "IMAGE" else s["precipitation"]))


def grid_material(material, scene, s, sun=None):
    """The grid's cloudiness (interpolated by Cycles), clamped to 0..wet, x Density -> scattering
    (core.clouds.density_from_cloudiness); with a sun lamp, the output Cycles renders, beside
    EEVEE's from the sun's light baked in the grid (cloud_sunlight)."""
    tree = material.node_tree
    _clear(tree)
    grid = h.add_node(tree, "ShaderNodeAttribute", name="Sandscape Cloud Grid", label="Cloudiness Grid",
                      attribute_type="GEOMETRY", attribute_name="density")
    positive = h.add_node(tree, "ShaderNodeClamp", label="Where Cloud: 0..Wet",
                          inputs={"Min": 0.0, "Max": grid_wet(s)})
    h.link(tree, grid.outputs["Fac"], positive.inputs["Value"])
    density = h.math(tree, "MULTIPLY", positive.outputs[0], parameters(scene, s)["density"], label="Density")
    density.name = "Sandscape Grid Density"
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Output")
    h.link(tree, scattering(tree, density.outputs[0], s), output.inputs["Volume"])
    if sun is not None:
        output.target = "CYCLES"
        cloud_sunlight.eevee_output(tree, density.outputs[0], lambda tree, lit: scattering(tree, lit, s),
                                    scene, sun, s["base"], s["thickness"])
    h.arrange(tree, set_widths=False)


def procedural_material(material, scene, s, image, region, fade):
    """Weather map (or image) -> Cloud Density -> scattering, evaluated at every step."""
    tree = material.node_tree
    _clear(tree)
    density = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Cloud Density", label="Cloud Density",
                         node_tree=h.ensure_group(cloud_density),
                         inputs=density_inputs(scene, s, region, fade, False))
    _drive_frame(density)
    weather = weather_inputs(scene, s)
    if s["weather_source"] == "IMAGE":
        position = h.add_node(tree, "ShaderNodeNewGeometry", name="Sandscape Weather Position")
        to_uv = h.add_node(tree, "ShaderNodeMapping", name="Sandscape Weather Mapping", label="World → UV",
                           inputs={"Location": (0.5, 0.5, 0.0), "Scale": weather["uv_scale"][:2] + (1.0,)})
        h.link(tree, position.outputs["Position"], to_uv.inputs["Vector"])
        texture = h.add_node(tree, "ShaderNodeTexImage", name="Sandscape Weather Image", label="Weather",
                             image=image, interpolation="Linear", extension="REPEAT")
        h.link(tree, to_uv.outputs["Vector"], texture.inputs["Vector"])
        channels = h.add_node(tree, "ShaderNodeSeparateColor", name="Sandscape Weather Channels")
        h.link(tree, texture.outputs["Color"], channels.inputs["Color"])
        for name, channel in (("Coverage", "Red"), ("Precipitation", "Green"), ("Type", "Blue")):
            h.link(tree, channels.outputs[channel], density.inputs[name])
    else:
        node = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Weather Map", label="Weather Map",
                          node_tree=h.ensure_group(weather_map), inputs=weather["inputs"])
        _drive_frame(node)
        for name in weather["linked"]:
            h.link(tree, node.outputs[name], density.inputs[name])
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Output")
    h.link(tree, scattering(tree, density.outputs["Density"], s), output.inputs["Volume"])
    h.arrange(tree, set_widths=False)


def step_rate(region, low, high, step):
    """The material's step rate for a ray-marching step of `step` scene units: Cycles steps a
    procedural volume by 0.1 x the mean side of its bounds x the rate."""
    xmin, ymin, xmax, ymax = region
    mean_side = ((xmax - xmin) + (ymax - ymin) + (high - low)) / 3.0
    return step / (0.1 * mean_side)


def plan(scene, s, image=None):
    """What apply() would build, without changing anything: region, fade, the grid's box and
    voxel size and count (coarser than asked, with a warning, past the budget), and whether the
    weather map has any cloud there."""
    low, high = s["base"], s["base"] + s["thickness"]
    region, fade = layer_box(scene, s)
    wind = np.asarray(scene.sandscape_atmosphere.wind, np.float64)
    carried = twin.carried_region(region, wind, *shot_seconds(scene))  # frame-0 space over the shot
    cloudy = twin.has_cloud(carried, SAMPLES, coverage_function(s, image))
    done = {"region": region, "fade": fade, "has_cloud": cloudy, "voxels": 0, "warning": None,
            "carried": carried}
    if s["evaluation"] == "GRID":
        done["voxel"] = s["voxel"]
        done["box"] = cloud_grid.box_and_resolution(carried, low, high, done["voxel"])
        wanted = math.prod(done["box"][2])
        while math.prod(done["box"][2]) > cloud_grid.MAX_VOXELS:  # coarser until within the budget
            done["voxel"] *= 1.02 * (math.prod(done["box"][2]) / cloud_grid.MAX_VOXELS) ** (1 / 3)
            done["box"] = cloud_grid.box_and_resolution(carried, low, high, done["voxel"])
        while done["voxel"] != s["voxel"]:  # back down in 1 % steps: whole voxel counts overshoot
            finer = max(done["voxel"] / 1.01, s["voxel"])
            box = cloud_grid.box_and_resolution(carried, low, high, finer)
            if math.prod(box[2]) > cloud_grid.MAX_VOXELS:
                break
            done["voxel"], done["box"] = finer, box
        done["voxels"] = math.prod(done["box"][2])
        if done["voxel"] != s["voxel"]:
            asked, used = (units.length_text(scene, v) for v in (s["voxel"], done["voxel"]))
            done["warning"] = (f"Voxel Size {asked} would make {wanted:,} voxels over this sky and shot: "
                               f"raised to {used} ({cloud_grid.MAX_VOXELS:,} at most). Shorten Reach, the "
                               "wind's drift over the frame range or the layer's Thickness for finer voxels")
    return done


def clip_warning(scene, s):
    """Why the camera cannot see the layer out to Reach, and what to change; or None."""
    camera = scene.camera
    if camera is None or camera.type != "CAMERA":
        return None
    z = float(camera.matrix_world.translation.z)
    height = max(s["base"] - z, z - s["base"] - s["thickness"], 0.0)
    if camera.data.clip_end >= math.hypot(s["reach"], height):
        return None
    needed = math.hypot(s["reach"], max(abs(s["base"] - z), abs(s["base"] + s["thickness"] - z)))
    clips, away = units.distinct_length_texts(scene, [camera.data.clip_end, height])
    return (f"Camera '{camera.name}' clips at {clips}: it sees "
            f"{'none' if camera.data.clip_end < height else 'only the nearest part'} of the cloud layer "
            f"{away} away. Raise its Clip End (Camera ▸ Lens) to "
            f"{units.length_text(scene, units.round_up(needed))} to see the clouds out to Reach")


def refresh_shadows(scene):
    """Remake EEVEE's cloud shadows for the scene's sun as it is now (after Add Atmosphere turned
    it), leaving the layer as it is; returns what was made (None: no layer, or not EEVEE)."""
    layer = own.scene_object(scene, own.CLOUDS)
    if layer is None or not cloud_shadows.wanted(scene):
        return None
    s = scene_settings(scene)
    image = bpy.data.images.get(s["weather_image"]) if s["weather_source"] == "IMAGE" else None
    if s["weather_source"] == "IMAGE" and image is None:
        return None
    return _apply_shadows(scene, s, image, plan(scene, s, image))


def _apply_shadows(scene, s, image, done):
    return cloud_shadows.apply(scene, done["carried"], s["base"], s["thickness"], s["step"],
                               twin_density(scene, s, image, done), scene.sandscape_atmosphere.wind)


def apply(scene, s, image=None, done=None):
    """Build or update the layer from settings s (a dict, scene units); returns what was done."""
    low, high = s["base"], s["base"] + s["thickness"]
    done = done or plan(scene, s, image)
    if not done["has_cloud"]:  # coverage 0: no cell holds cloud
        remove_layer(scene)
        return {**done, "layer": None, "changes": []}
    layer = ensure_layer(scene)
    material = layer.active_material
    changes = []  # of the scene's render settings, for the report
    if s["evaluation"] == "GRID":
        own.set_mesh(layer, np.zeros((0, 3)), [])
        sun = scene_sun(scene) if cloud_shadows.wanted(scene) else None  # EEVEE's alone
        grid_material(material, scene, s, sun)
        _modifier, tree = cloud_grid.ensure_modifier(layer)
        weather = weather_inputs(scene, s)
        sunlight = None if sun is None else {
            "sun": sun, "thickness": s["thickness"], "step": s["step"],
            "density": parameters(scene, s)["density"], "wet": grid_wet(s)}
        cloud_grid.build_tree(tree, material, density_inputs(scene, s, done["region"], done["fade"], True),
                              weather, image, done["box"], done["voxel"], sunlight)
        cloud_grid.drift_with_wind(layer, scene.sandscape_atmosphere.wind,
                                   frames_per_second(scene))
        # Ray marching steps a grid by its voxel x the step rate: Step long, as procedurally.
        material.cycles.volume_step_rate = float(min(max(s["step"] / done["voxel"], 1e-6), 1e6))
    else:
        cloud_grid.remove_modifier(layer)
        cloud_grid.stop_drift(layer)
        own.set_mesh(layer, *twin.box_mesh(done["region"], low, high))
        procedural_material(material, scene, s, image, done["region"], done["fade"])
        rate = step_rate(done["region"], low, high, s["step"])
        material.cycles.volume_step_rate = float(min(max(rate, 1e-6), 1e6))
        # A ray through the whole layer at 6 degrees is thickness / sin(6 deg) long: fewer steps
        # would cut the clouds off. Ray marching itself (volume_biased) is the artist's, or a preset's.
        longest = min(s["thickness"] / math.sin(math.radians(6.0)), 2 * s["reach"])
        needed = int(min(math.ceil(longest / s["step"]), 16384))
        if needed > scene.cycles.volume_max_steps:
            changes.append(f"volume max steps {scene.cycles.volume_max_steps} → {needed} (a ray through "
                           "the layer needs them)")
            scene.cycles.volume_max_steps = needed
    layer.matrix_world.translation.z = 0.0
    layer[far_haze.REGION_KEY] = [float(v) for v in done["region"]]
    layer[far_haze.BASE_KEY] = float(low)
    haze, no_haze = far_haze.refresh(scene)
    shadows = _apply_shadows(scene, s, image, done)
    sky_eevee_clouds.follow_scene(scene)  # EEVEE's lighting world takes the layer's light
    warnings = [text for text in (done["warning"], clip_warning(scene, s)) if text]
    return {**done, "layer": layer, "warning": "; ".join(warnings) or None, "changes": changes,
            "eevee_shadows": shadows, "far_haze": haze, "no_far_haze": no_haze}
