"""VTK files of the cases: BEM fields as structured grids (.vti), FEM fields as .vtu, one
.pvd collection per speed sweep (the sweep parameter as ParaView's time value, named in the
.pvd and in each file's field data).

Each BEM file carries its provenance (:func:`validation.vtk_io.provenance`): the solver (the
folder's name and the adapter's detail), its settings (``rtol``, grid, spacing), the material
as the case defines it, and the viscobem version.
"""

from __future__ import annotations

import re
from pathlib import Path

from validation.vtk_io import provenance, surface_grid, write_pvd

__all__ = ["write_bem_sweep", "write_pvd_for", "PARAMETERS"]

# short names of the cases' sweep parameters -> what they are (with units)
PARAMETERS = {
    "s": "s = V max(lambda_k) / a0, the dimensionless speed (a0: the relaxed Hertz contact half-width or radius)",
    "V": "V, the sliding speed (m/s)",
    "fem V": "V, the sliding speed (m/s) of the FEM's points (a sweep of its own, on the FEM's material)",
    "xi": "xi = V max(lambda_k) / L, the dimensionless speed (L: the cell side)",
    "fraction": "the mean pressure as a fraction of the full-contact pressure",
    "index": "the index of the solve (no physical parameter)",
}


def _rel(path, root):
    return str(Path(path).relative_to(root)) if root is not None else str(path)


def _stated_rtol(message):
    """The tolerance a BEM result's message states (``... rtol 1.0e-08 ...``), or None."""
    match = re.search(r"rtol ([0-9.]+e[-+]?[0-9]+)", str(message))
    return float(match.group(1)) if match else None


def _material(m):
    if m is None:
        return None
    return {
        "E0": float(m.E0),
        "prony_moduli": [float(x) for x in m.moduli],
        "relaxation_times": [float(x) for x in m.relaxation_times],
        "nu": float(m.nu),
    }


def write_bem_sweep(folder, root, solutions, values, name="sweep.pvd", *, parameter, rtol=None):
    """``solutions``: adapter dicts with ``surface``, ``result`` and ``origin``; one .vti each
    (pressure, displacement, gap, contact, heights) plus ``name`` (.pvd), the series running over
    ``values`` of ``parameter`` (a key of :data:`PARAMETERS`). ``rtol``: the solves' tolerance
    (default: the one each result's message states).
    Returns the paths relative to ``root``."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    described = PARAMETERS[parameter]
    files, entries = [], []
    for k, (sol, value) in enumerate(zip(solutions, values)):
        fname = f"point_{k:03d}.vti"
        surface = sol["surface"]
        settings = {
            "rtol": rtol if rtol is not None else _stated_rtol(sol["result"].message),
            "grid": list(surface.shape),
            "spacing_m": surface.spacing,
            "cell_length_m": surface.length,
            "detail": sol.get("detail", ""),
        }
        extra = provenance(
            solver=f"{folder.name} ({sol.get('detail', 'bem.solve')})",
            settings=settings,
            material_given=_material(sol.get("material")),
        )
        extra.update(series_parameter=[described], series_value=[float(value)])
        surface_grid(
            surface, sol["result"], origin=sol.get("origin", (0.0, 0.0)), material=sol.get("material"), extra=extra
        ).save(folder / fname)
        files.append(_rel(folder / fname, root))
        entries.append((fname, value))
    write_pvd(folder / name, entries, described)
    return files + [_rel(folder / name, root)]


def write_pvd_for(folder, root, entries, name="sweep.pvd", *, parameter):
    """A .pvd over files already written in ``folder``: ``entries = [(file, value), ...]`` of
    ``parameter`` (a key of :data:`PARAMETERS`)."""
    folder = Path(folder)
    write_pvd(folder / name, entries, PARAMETERS[parameter])
    return [_rel(folder / f, root) for f, _ in entries] + [_rel(folder / name, root)]
