"""VTK output of BEM surface fields for ParaView (pyvista), with a .pvd per sweep."""
from pathlib import Path
from xml.sax.saxutils import quoteattr


def surface_grid(surface, result, origin=(0.0, 0.0)):
    """A pyvista ImageData of the cell with point data pressure, displacement, gap, contact.

    ``origin`` (m): coordinates of the first grid point (x, y), e.g. to put an indenter's
    axis at 0 so that the grid overlays an FEM mesh in ParaView."""
    import numpy as np
    import pyvista as pv

    n, d = surface.n, surface.spacing
    dims = (n, n, 1) if surface.ndim == 2 else (n, 1, 1)
    grid = pv.ImageData(dimensions=dims, spacing=(d, d, d), origin=(float(origin[0]), float(origin[1]), 0.0))

    def flat(a):  # VTK orders points x fastest; our arrays are [ix, iy]
        return np.asarray(a).ravel(order="F")

    grid.point_data["heights"] = flat(surface.heights)
    grid.point_data["pressure"] = flat(result.pressure)
    grid.point_data["displacement"] = flat(result.displacement)
    grid.point_data["gap"] = flat(result.gap)
    grid.point_data["contact"] = flat(result.pressure > 0).astype(np.uint8)
    return grid


def write_pvd(path, datasets):
    """Write a ParaView collection ``path`` (.pvd) of ``datasets = [(file, time_value), ...]``
    (file names relative to the .pvd's folder); ParaView opens them as one time series."""
    entries = [f'  <DataSet timestep={quoteattr(repr(float(t)))} file={quoteattr(str(name))}/>'
               for name, t in datasets]
    Path(path).write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                          + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")


def write_sweep(folder, surface, results, xi):
    """Write ``point_XXX.vti`` per result and ``sweep.pvd`` (xi as the time value); return names."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names, entries = [], []
    for k, (res, x) in enumerate(zip(results, xi)):
        name = f"point_{k:03d}.vti"
        surface_grid(surface, res).save(folder / name)
        names.append(f"{folder.name}/{name}")
        entries.append((name, x))
    write_pvd(folder / "sweep.pvd", entries)
    names.append(f"{folder.name}/sweep.pvd")
    return names
