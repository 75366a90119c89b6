"""Procedural asset library (MjSpec primitives, code-built meshes, PIL textures).

Importing this package registers every asset module's categories in ``ASSETS``.
"""

from . import distractors, primitives, task_objects, task_props  # noqa: F401  (register categories)
from .base import ObjectInfo
from .registry import ASSETS, AssetEntry, build_asset, categories, register_asset

__all__ = ["ASSETS", "AssetEntry", "ObjectInfo", "build_asset", "categories", "register_asset"]
