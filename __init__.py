# SPDX-License-Identifier: GPL-3.0-or-later
"""Sandscape: desert scenes for Blender (glinting sand, footprints, dusty light)."""

from .ui import registration


def register():
    registration.register()


def unregister():
    registration.unregister()
