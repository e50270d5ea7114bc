"""Images Sandscape makes: the seeded glint-noise image, packed into the .blend."""

import bpy
import numpy as np

from ..core import glints

IMAGE_KEY = "sandscape_image"
GLINT_NOISE = "glint_noise"


def find_noise_image():
    for image in bpy.data.images:
        if image.get(IMAGE_KEY) == GLINT_NOISE:
            return image
    return None


def ensure_noise_image(resolution, seed):
    """Our seeded white-noise image (8-bit, Non-Color, packed as PNG), updated in place."""
    image = find_noise_image()
    if image is None:
        image = bpy.data.images.new("Sandscape Glint Noise", resolution, resolution, alpha=False)
        image[IMAGE_KEY] = GLINT_NOISE
        # Before the pixels: changing the colour space of a generated image regenerates it.
        image.colorspace_settings.name = "Non-Color"
    elif tuple(image.size) == (resolution, resolution) and image.get("seed") == seed and image.packed_file:
        return image
    elif tuple(image.size) != (resolution, resolution):
        image.scale(resolution, resolution)
    values = glints.byte_to_unit(glints.noise_image(resolution, seed))
    rgba = np.repeat(values[..., None], 4, axis=-1)
    rgba[..., 3] = 1.0
    image.pixels.foreach_set(rgba.ravel())
    image.pack()
    image["seed"] = seed
    return image
