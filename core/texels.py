"""Bilinear image sampling from four nearest-texel lookups: the twin of node groups Sandscape
Texel Corners and Sandscape Texel Blend, and of an image node's Linear interpolation with Clip
extension (texels outside the image are transparent black)."""

import numpy as np


def corners(uv, width, height):
    """The four texel centres round each point (..., 2) of 0..1 coordinates: (..., 4, 2) in the
    order left-bottom, right-bottom, left-top, right-top, and the weights (..., 2)."""
    size = np.array([width, height], np.float64)
    texels = np.asarray(uv, np.float64)[..., :2] * size - 0.5
    first = np.floor(texels)
    weight = texels - first
    near, far = (first + 0.5) / size, (first + 1.5) / size
    points = np.stack([near, np.stack([far[..., 0], near[..., 1]], -1),
                       np.stack([near[..., 0], far[..., 1]], -1), far], axis=-2)
    return points, weight


def nearest(image, points):
    """Closest lookup with Clip extension: image (H, W, C), rows bottom-up; points (..., 2)."""
    height, width = image.shape[:2]
    column = np.floor(points[..., 0] * width).astype(np.int64)
    row = np.floor(points[..., 1] * height).astype(np.int64)
    inside = (column >= 0) & (column < width) & (row >= 0) & (row < height)
    values = image[np.clip(row, 0, height - 1), np.clip(column, 0, width - 1)]
    return np.where(inside[..., None], values, 0.0)


def blend(colours, weight):
    """colours (..., 4, C) at the corners, weight (..., 2): the bilinear value (..., C)."""
    wx, wy = weight[..., 0:1], weight[..., 1:2]
    bottom = colours[..., 0, :] * (1 - wx) + colours[..., 1, :] * wx
    top = colours[..., 2, :] * (1 - wx) + colours[..., 3, :] * wx
    return bottom * (1 - wy) + top * wy


def bilinear(image, uv):
    """Linear interpolation with Clip extension at points uv (..., 2)."""
    points, weight = corners(uv, image.shape[1], image.shape[0])
    return blend(nearest(image, points), weight)
