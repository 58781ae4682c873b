"""The built-in scenes and the optional extras, known without importing numpy or bem.

``viscobem --help`` and ``viscobem run NAME`` read this module only, so they stay fast.
"""

import difflib
import importlib
from pathlib import Path

from bem.errors import InputError

SCENE_DIR = Path(__file__).with_name("builtin_scenes")
DEFAULT_NAME = "seed"

# optional dependency (top-level module) -> (pip extra, what needs it)
EXTRAS = {
    "dask": ("dask", "a dask.distributed scheduler ([solver] scheduler)"),
    "distributed": ("dask", "a dask.distributed scheduler ([solver] scheduler)"),
    "pyvista": ("vtk", "VTK output ([outputs] vtk = true; the VTK files of viscobem validate)"),
    "vtk": ("vtk", "VTK output ([outputs] vtk = true; the VTK files of viscobem validate)"),
    "pypardiso": ("fem", "the FEM reference's PARDISO solver (without it: SuperLU, slower)"),
    "SurfaceTopography": ("topography", "reading measured topography files (scene kind measured)"),
    "psutil": ("bench", "the benchmarks' memory measurements"),
    "tamaas": ("tamaas", "the elastic reference of viscobem bench periodic"),
    "pyvisco": ("pyvisco", "viscobem bench materials (the comparison with pyvisco)"),
    "selenium": ("browser", "the browser test of report.html"),
}

# pip extra -> what it adds (the getting-started page lists them from here; a test keeps this in
# step with pyproject.toml)
EXTRA_PURPOSE = {
    "vtk": "VTK files for ParaView (pyvista): `[outputs] vtk = true` and the VTK of `viscobem validate`",
    "topography": 'measured topography files (SurfaceTopography): `kind = "measured"`, `bem.surfaces.measured`',
    "dask": "sweeps on a dask.distributed cluster: `[solver] scheduler`, `--scheduler`",
    "fem": "PARDISO (pypardiso), a faster sparse solver for the FEM reference (SuperLU without it)",
    "bench": "psutil, for the benchmarks",
    "tamaas": "tamaas, the elastic reference of `viscobem bench periodic`",
    "pyvisco": "pyvisco, the comparison of `viscobem bench materials`",
    "test": "the test tools, and every optional package the test suite exercises",
    "browser": "selenium, for the browser test of `report.html` (`pytest -m browser`, with Chromium)",
    "docs": "MkDocs and its plugins, to build this documentation",
}


def builtin_scenes():
    """Names of the built-in scenes (``viscobem run NAME``, ``viscobem scene NAME``)."""
    return sorted(p.stem for p in SCENE_DIR.glob("*.toml"))


def scene_path(name=None):
    """Path of the scene ``name``: a built-in name, a file, or None for the default study.

    A name that is neither raises :class:`~bem.errors.InputError` listing the built-in
    scenes (and the closest one).
    """
    if name is None:
        return SCENE_DIR / f"{DEFAULT_NAME}.toml"
    if str(name) in builtin_scenes():
        return SCENE_DIR / f"{name}.toml"
    path = Path(name)
    if path.suffix or path.exists():
        return path
    names = builtin_scenes()
    close = difflib.get_close_matches(str(name), names, n=1)
    hint = f" Did you mean {close[0]!r}?" if close else ""
    raise InputError(
        f"no built-in scene named {str(name)!r} (and no such file).{hint} Built-in scenes: "
        f"{', '.join(names)}; or give a scene file SCENE.toml (template: viscobem scene)"
    )


def install_hint(module):
    """One line naming the pip extra that provides ``module``, or None if it is not optional."""
    top = (module or "").split(".")[0]
    if top not in EXTRAS:
        return None
    extra, what = EXTRAS[top]
    return f'{top} is not installed; {what} needs it: pip install "viscobem[{extra}]"'


def hint_for(err):
    """The install hint for an ImportError: by the module it names, else by an optional
    package named in its message (a library may raise its own ImportError with advice)."""
    hint = install_hint(getattr(err, "name", None))
    if hint is None:
        text = str(err)
        hint = next((install_hint(m) for m in EXTRAS if m in text), None)
    return hint


def missing(module):
    """The install hint if the optional ``module`` cannot be imported, else None."""
    try:
        importlib.import_module(module)
    except ImportError as err:
        return hint_for(err) or install_hint(module) or str(err)
    return None


def require(module):
    """Raise InputError with the install hint if the optional ``module`` cannot be imported."""
    hint = missing(module)
    if hint is not None:
        raise InputError(hint)
