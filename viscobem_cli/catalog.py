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
    "pyvista": ("vtk", "VTK output ([outputs] vtk = true; viscobem validate without --no-vtk)"),
    "vtk": ("vtk", "VTK output ([outputs] vtk = true; viscobem validate without --no-vtk)"),
    "pypardiso": ("fem", "the FEM reference's PARDISO solver"),
    "SurfaceTopography": ("topography", "reading measured topography files (scene kind measured)"),
    "psutil": ("bench", "the benchmarks' memory measurements"),
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


def require(module):
    """Raise InputError with the install hint if the optional ``module`` cannot be imported."""
    try:
        importlib.import_module(module)
    except ModuleNotFoundError as err:
        raise InputError(install_hint(err.name) or str(err)) from None
