"""A ground whose colour comes from an image: EEVEE's light from below takes the image's mean in
linear light (core/image_mean.py, addon/sky_eevee_ground.py), checked against the sRGB standard's
own numbers and against Cycles' decoding of the same file (an emission bake)."""

import importlib
import math

import bpy
import numpy as np
import pytest

from core import image_mean
from core import sand as core_sand
from devtools import readback, scenes, session

ground = importlib.import_module(f"{session.MODULE}.addon.sky_eevee_ground")
SIZE = 32
SMALL_CLOUDS = {"reach": 3000.0, "voxel": 150.0, "map_scale": 2000.0, "shape_scale": 600.0, "coverage": 0.6}


def test_the_srgb_decoding_gives_the_standards_values():
    """IEC 61966-2-1: code 0.5 is 0.2140 linear, the knee 0.04045 is 0.0031308, 1 is 1; the mean is
    taken after decoding (black and white halves: 0.5, not the 0.214 of the mean code)."""
    assert image_mean.srgb_to_linear([0.0, 0.04045, 0.5, 1.0]) == pytest.approx(
        [0.0, 0.0031308, 0.2140411, 1.0], abs=2e-7)
    halves = np.array([[0.0, 0.0, 0.0, 1.0], [1.0, 1.0, 1.0, 1.0]], np.float32).ravel()
    assert image_mean.mean_colour(halves, 4, srgb=True) == pytest.approx((0.5, 0.5, 0.5))
    grey = np.array([0.5, np.nan, 0.5], np.float32)
    assert image_mean.mean_colour(grey, 1, srgb=True) == pytest.approx((0.2140411,) * 3, abs=2e-7)
    assert image_mean.mean_colour(np.array([np.inf, 0.0, 0.0]), 3, srgb=False) is None


def _codes(seed=7):
    """A contrasty green-brown texture's codes: (SIZE * SIZE * 4,) float32, alpha 1."""
    rng = np.random.default_rng(seed)
    codes = np.empty((SIZE, SIZE, 4), np.float32)
    codes[..., 0], codes[..., 1] = rng.uniform(0.05, 0.6, (SIZE, SIZE)), rng.uniform(0.2, 0.9, (SIZE, SIZE))
    codes[..., 2], codes[..., 3] = rng.uniform(0.0, 0.3, (SIZE, SIZE)), 1.0
    return codes.ravel()


def _image_file(tmp_path, name, float_buffer=False, extension="png", codes=None):
    """The codes written to a file and loaded back from it, as an artist's texture is."""
    image = bpy.data.images.new(name, SIZE, SIZE, float_buffer=float_buffer)
    image.pixels.foreach_set(_codes() if codes is None else codes)
    path = tmp_path / f"{name}.{extension}"
    image.filepath_raw, image.file_format = str(path), "OPEN_EXR" if extension == "exr" else "PNG"
    image.save()
    bpy.data.images.remove(image)
    return bpy.data.images.load(str(path), check_existing=False)


def _textured_ground(image):
    """A rotated, scaled plane whose Principled Base Color is the image through a reroute, and a
    camera over it."""
    bpy.ops.mesh.primitive_plane_add(size=20.0, rotation=(0.0, 0.0, math.radians(30.0)))
    obj = bpy.context.active_object
    obj.scale = (3.0, 2.0, 1.0)
    material = bpy.data.materials.new("Their Meadow")
    tree = material.node_tree
    texture, reroute = tree.nodes.new("ShaderNodeTexImage"), tree.nodes.new("NodeReroute")
    texture.image = image
    tree.links.new(texture.outputs["Color"], reroute.inputs[0])
    tree.links.new(reroute.outputs[0], tree.nodes["Principled BSDF"].inputs["Base Color"])
    obj.data.materials.append(material)
    scenes.camera("PERSP", location=(1.0, 2.0, 1.6), rotation=(math.radians(85.0), 0.0, 0.0))
    return obj, material


def _world_colour(scene):
    scene.frame_set(scene.frame_current)
    return tuple(socket.default_value for socket in scene.world.node_tree.nodes[ground.NODE].inputs[:3])


def _cycles_mean(image, alpha_used=False):
    """Cycles' own decoding of the image: its texels baked through an Emission at their centres;
    alpha_used: with the node's Alpha output used too (by a Greater Than giving the Strength 1)."""
    plane = readback.uv_plane(name="Decode Plane")
    material = bpy.data.materials.new("Decode")
    tree = material.node_tree
    tree.nodes.clear()
    texture, emission = tree.nodes.new("ShaderNodeTexImage"), tree.nodes.new("ShaderNodeEmission")
    texture.image, texture.interpolation = image, "Closest"
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(texture.outputs["Color"], emission.inputs["Color"])
    if alpha_used:
        one = tree.nodes.new("ShaderNodeMath")
        one.operation, one.inputs[1].default_value = "GREATER_THAN", -1.0
        tree.links.new(texture.outputs["Alpha"], one.inputs[0])
        tree.links.new(one.outputs[0], emission.inputs["Strength"])
    tree.links.new(emission.outputs[0], output.inputs["Surface"])
    plane.data.materials.append(material)
    baked = readback.bake_emit(plane, material, SIZE)
    bpy.data.objects.remove(plane)
    return tuple(baked[..., :3].reshape(-1, 3).astype(np.float64).mean(axis=0))


@pytest.mark.parametrize("kind", ["8-bit sRGB", "8-bit Non-Color", "float EXR"])
def test_the_ground_takes_the_images_mean_as_cycles_decodes_it(sandscape, tmp_path, kind):
    """The world's ground colour is the mean of the image as Cycles reads the same file (its
    texels baked): an 8-bit sRGB PNG decoded first, Non-Color taken as it is, a float EXR
    linear. Within 1e-3 (Cycles' float decoding); the sRGB mean's decoded mean code is off by
    far more (asserted, so the test tells the two apart)."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    image = _image_file(tmp_path, "Meadow", float_buffer=kind == "float EXR",
                        extension="exr" if kind == "float EXR" else "png")
    if kind == "8-bit Non-Color":
        image.colorspace_settings.name = "Non-Color"
    reference = _cycles_mean(image)
    _obj, material = _textured_ground(image)
    images = len(bpy.data.images)
    done = sandscape.addon.atmosphere.apply(scene, scene.sandscape_atmosphere)
    assert done["ground"] == material and done["ground_read"] and done["ground_image"] == image
    assert len(bpy.data.images) == images
    assert _world_colour(scene) == pytest.approx(reference, abs=1e-3)
    if kind == "8-bit sRGB":
        decoded_mean_code = image_mean.srgb_to_linear(_codes().reshape(-1, 4)[:, :3].mean(axis=0))
        assert np.max(np.abs(np.array(reference) - decoded_mean_code)) > 0.01
    line = sandscape.operators.atmosphere.report_line(scene, scene.sandscape_atmosphere, done)
    assert f"image '{image.name}'" in line and "Their Meadow" in line
    panel = sandscape.ui.panels.ground_light_text(scene)
    assert panel.endswith(f"the mean of image '{image.name}' on 'Their Meadow'")


def test_a_large_image_is_read_from_a_scaled_copy_that_is_removed(sandscape, tmp_path, monkeypatch):
    """Past MEAN_PIXELS a file's mean comes from a scaled copy (here a 32x32 image past 256
    pixels), and bpy.data holds the images it held. A smooth image keeps its mean within 1 %; white
    noise loses a fifth, as scaling averages codes before they are decoded (the README's caveat).
    An image edited since it was loaded is read whole: a copy would lose the edit."""
    bpy.ops.wm.read_homefile(use_empty=True)
    ramp = np.linspace(0.1, 0.9, SIZE, dtype=np.float32)
    half, one = np.float32(0.5), np.float32(1.0)
    codes = np.stack(np.broadcast_arrays(ramp[None, :], ramp[:, None], half, one), axis=-1)
    smooth = _image_file(tmp_path, "Smooth Meadow", codes=codes.ravel())
    noise = _image_file(tmp_path, "Noise Meadow")
    painted = bpy.data.images.new("Painted Meadow", SIZE, SIZE)
    painted.pixels.foreach_set(_codes())
    images = (smooth, noise, painted)
    whole = [ground.mean_colour(image) for image in images]
    monkeypatch.setattr(ground, "MEAN_PIXELS", 256)
    names = sorted(bpy.data.images.keys())
    scaled = [ground.mean_colour(image) for image in images]
    assert sorted(bpy.data.images.keys()) == names
    assert all(tuple(image.size) == (SIZE, SIZE) for image in images)
    assert scaled[0] == pytest.approx(whole[0], rel=0.01)
    assert 0.7 < np.mean(np.array(scaled[1]) / whole[1]) < 0.9
    assert scaled[2] == whole[2] == pytest.approx(whole[1], rel=1e-6)


def test_the_clouds_take_the_images_mean_and_a_missing_file_gives_the_sands(sandscape, tmp_path):
    """Clouds added afterwards take the world's fixed colour; another image put in the node is
    named as a change until the operator runs again (a helper's finding: the sidebar said "the
    colour of" the material); an image whose file is gone gives the sand's colour, and the report
    says its image has no pixels."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    image = _image_file(tmp_path, "Meadow")
    _textured_ground(image)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    meadow = _world_colour(scene)
    assert bpy.ops.sandscape.add_clouds(**SMALL_CLOUDS) == {"FINISHED"}
    layer = next(o for o in scene.objects if o.get("sandscape_object") == "clouds")
    clouds = tuple(s.default_value for s in layer.active_material.node_tree.nodes[ground.NODE].inputs[:3])
    assert clouds == pytest.approx(meadow, abs=1e-6)
    assert ground.followed(layer.active_material.node_tree) == bpy.data.materials["Their Meadow"]
    # Another image in the node: the sidebar says the ground changed until the operator runs again.
    nodes = bpy.data.materials["Their Meadow"].node_tree.nodes
    texture = next(node for node in nodes if node.bl_idname == "ShaderNodeTexImage")
    basalt = np.tile(np.float32([0.1, 0.1, 0.1, 1.0]), SIZE * SIZE)
    texture.image = _image_file(tmp_path, "Basalt", codes=basalt)
    assert sandscape.ui.panels.ground_light_text(scene).endswith("changed, Add Atmosphere again")
    sandscape.addon.atmosphere.apply(scene, scene.sandscape_atmosphere)
    assert "the mean of image 'Basalt.png'" in sandscape.ui.panels.ground_light_text(scene)
    assert _world_colour(scene) == pytest.approx((float(image_mean.srgb_to_linear(0.1)),) * 3, abs=1e-3)
    texture.image.filepath = str(tmp_path / "gone.png")
    texture.image.reload()
    done = sandscape.addon.atmosphere.apply(scene, scene.sandscape_atmosphere)
    assert not done["ground_read"]
    assert _world_colour(scene) == pytest.approx(core_sand.SAND_COLOR[:3], abs=1e-6)
    line = sandscape.operators.atmosphere.report_line(scene, scene.sandscape_atmosphere, done)
    assert "sand's colour: image 'Basalt.png'" in line and "no pixels" in line
    assert sandscape.ui.panels.ground_light_text(scene).endswith("Sandscape's sand colour stands in")


def _codes_with_alpha():
    codes = _codes().reshape(SIZE, SIZE, 4)
    codes[..., 3] = np.random.default_rng(3).uniform(0.05, 1.0, (SIZE, SIZE))
    return codes.ravel()


@pytest.mark.parametrize("alpha_used", [False, True])
def test_an_image_with_alpha_gives_its_colour_times_its_alpha(sandscape, tmp_path, alpha_used):
    """An 8-bit PNG with straight alpha (0.05-1, mean 0.52) on the ground's Base Color: Cycles
    shades its colour times its alpha with the node's Alpha output unused (the codes premultiplied,
    then decoded), and the ground takes that mean (within 1e-3 of the bake). With the Alpha used
    (a cut-out's Principled Alpha) Cycles gives the colour alone, but lets the light through where
    the alpha is low, so the ground reflects the same share: the same mean (a helper found the
    colour alone made EEVEE's shaded sides half as bright again as Cycles'). The colour alone
    differs from it by far more, so the test tells them apart."""
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    source = bpy.data.images.new("Cut-out Source", SIZE, SIZE, alpha=True)
    source.pixels.foreach_set(_codes_with_alpha())
    source.filepath_raw, source.file_format = str(tmp_path / "cutout.png"), "PNG"
    source.save()
    bpy.data.images.remove(source)
    image = bpy.data.images.load(str(tmp_path / "cutout.png"), check_existing=False)
    assert image.alpha_mode == "STRAIGHT" and image.channels == 4
    reference, colour_alone = _cycles_mean(image), _cycles_mean(image, alpha_used=True)
    _obj, material = _textured_ground(image)
    if alpha_used:
        nodes = material.node_tree.nodes
        texture = next(node for node in nodes if node.bl_idname == "ShaderNodeTexImage")
        material.node_tree.links.new(texture.outputs["Alpha"], nodes["Principled BSDF"].inputs["Alpha"])
    sandscape.addon.atmosphere.apply(scene, scene.sandscape_atmosphere)
    colour = _world_colour(scene)
    print(f"alpha used {alpha_used}: ground {np.round(colour, 4)}, Cycles {np.round(reference, 4)}")
    assert colour == pytest.approx(reference, abs=1e-3)
    assert np.max(np.abs(np.array(colour_alone) - reference)) > 0.05
