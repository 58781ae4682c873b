"""VTK output of BEM surface fields for ParaView (pyvista), with a .pvd per sweep."""
from pathlib import Path
from xml.sax.saxutils import quoteattr


def surface_grid(surface, result):
    """A pyvista ImageData of the cell with point data pressure, displacement, gap, contact."""
    import numpy as np
    import pyvista as pv

    n, d = surface.n, surface.spacing
    dims = (n, n, 1) if surface.ndim == 2 else (n, 1, 1)
    grid = pv.ImageData(dimensions=dims, spacing=(d, d, d), origin=(0.0, 0.0, 0.0))

    def flat(a):  # VTK orders points x fastest; our arrays are [ix, iy]
        return np.asarray(a).ravel(order="F")

    grid.point_data["heights"] = flat(surface.heights)
    grid.point_data["pressure"] = flat(result.pressure)
    grid.point_data["displacement"] = flat(result.displacement)
    grid.point_data["gap"] = flat(result.gap)
    grid.point_data["contact"] = flat(result.pressure > 0).astype(np.uint8)
    return grid


def write_sweep(folder, surface, results, xi):
    """Write ``point_XXX.vti`` per result and ``sweep.pvd`` (xi as the time value); return names."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names, entries = [], []
    for k, (res, x) in enumerate(zip(results, xi)):
        name = f"point_{k:03d}.vti"
        surface_grid(surface, res).save(folder / name)
        names.append(f"{folder.name}/{name}")
        entries.append(f'  <DataSet timestep={quoteattr(repr(float(x)))} file={quoteattr(name)}/>')
    pvd = ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
           + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    (folder / "sweep.pvd").write_text(pvd)
    names.append(f"{folder.name}/sweep.pvd")
    return names
