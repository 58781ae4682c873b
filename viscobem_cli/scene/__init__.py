"""Scenes: one study described in a TOML file, read into a validated :class:`Scene`.

Workflow:

1. the text is read and every key checked against the one table of the format
   (:mod:`.schema`), single values by :mod:`.values`;
2. the material (series, or DMA data with units and shift laws, :mod:`.temperatures`), the
   surface (generated, analytic, from a file, or measured, :mod:`.measured`), the loads,
   speeds and sliding directions (:mod:`.directions`) become objects (:mod:`.parse`);
3. the scene is handed to :func:`viscobem_cli.run.run_scene`.
"""

from .parse import (
    DEFAULT_SCENE,
    INDENTER_KINDS,
    MIN_POINTS_PER_WAVELENGTH,
    SCENE_DIR,
    SCHEMA,
    SURFACE_KINDS,
    Scene,
    builtin_scenes,
    describe_xi,
    load,
    parse,
)

__all__ = [
    "DEFAULT_SCENE",
    "INDENTER_KINDS",
    "MIN_POINTS_PER_WAVELENGTH",
    "SCENE_DIR",
    "SCHEMA",
    "SURFACE_KINDS",
    "Scene",
    "builtin_scenes",
    "describe_xi",
    "load",
    "parse",
]
