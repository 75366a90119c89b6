"""Procedural asset library (MjSpec primitives, code-built meshes, PIL textures).

Importing this package registers every asset module's categories in ``ASSETS``.
"""

from . import devices, distractors, handheld, primitives, surfaces  # noqa: F401  (register categories)
from .base import ObjectInfo
from .registry import ASSETS, AssetEntry, build_asset, categories, register_asset

__all__ = ["ASSETS", "AssetEntry", "ObjectInfo", "build_asset", "categories", "register_asset"]
