"""The seeded white-noise image glints read through the mesh UVs (Source: Image): one texel per
grain, made and packed by Sandscape, one image per resolution and seed."""

import bpy
import numpy as np

from ..core import glints as glint_twin
from . import ownership as own


def ensure_noise_image(resolution, seed):
    """The seeded white-noise image for this resolution and seed (8-bit, Non-Color, packed).

    One image per (resolution, seed): two materials with other seeds never share, and so never
    rewrite, each other's image.
    """
    image = own.image(own.GLINT_NOISE, seed=seed, resolution=resolution)
    if image is not None and image.packed_file:
        return image
    if image is None:
        image = bpy.data.images.new("Sandscape Glint Noise", resolution, resolution, alpha=False)
        own.mark(image, own.IMAGE_KEY, own.GLINT_NOISE, seed=seed, resolution=resolution)
        # Before the pixels: changing the colour space of a generated image regenerates it.
        image.colorspace_settings.name = "Non-Color"
    values = glint_twin.byte_to_unit(glint_twin.noise_image(resolution, seed))
    rgba = np.repeat(values[..., None], 4, axis=-1)
    rgba[..., 3] = 1.0
    image.pixels.foreach_set(rgba.ravel())
    image.pack()
    return image
