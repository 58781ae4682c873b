"""VTK files of the cases: BEM fields as structured grids (.vti), FEM fields as .vtu, one
.pvd collection per speed sweep (the sweep parameter as ParaView's time value)."""

from __future__ import annotations

from pathlib import Path

from validation.vtk_io import surface_grid, write_pvd

__all__ = ["write_bem_sweep", "write_pvd_for"]


def _rel(path, root):
    return str(Path(path).relative_to(root)) if root is not None else str(path)


def write_bem_sweep(folder, root, solutions, values, name="sweep.pvd"):
    """``solutions``: adapter dicts with ``surface``, ``result`` and ``origin``; one .vti each
    (pressure, displacement, gap, contact, heights) plus ``name`` (.pvd). Returns the paths
    relative to ``root``."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    files, entries = [], []
    for k, (sol, value) in enumerate(zip(solutions, values)):
        fname = f"point_{k:03d}.vti"
        surface_grid(
            sol["surface"], sol["result"], origin=sol.get("origin", (0.0, 0.0)), material=sol.get("material")
        ).save(folder / fname)
        files.append(_rel(folder / fname, root))
        entries.append((fname, value))
    write_pvd(folder / name, entries)
    return files + [_rel(folder / name, root)]


def write_pvd_for(folder, root, entries, name="sweep.pvd"):
    """A .pvd over files already written in ``folder``: ``entries = [(file, value), ...]``."""
    folder = Path(folder)
    write_pvd(folder / name, entries)
    return [_rel(folder / f, root) for f, _ in entries] + [_rel(folder / name, root)]
