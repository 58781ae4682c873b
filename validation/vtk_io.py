"""VTK output of BEM surface fields for ParaView (pyvista), with a .pvd per sweep.

Every .vti holds point data ``heights``, ``pressure`` (Pa), ``displacement`` (m, into the solid),
``gap`` (m) and ``contact`` (1 in contact), and field data (arrays of one value unless stated):
``speed`` (m/s), ``load`` (N per cell, or N/m for a profile), ``friction``, ``approach`` (m),
``cell_length`` (m), and with the material ``E0``, ``E_inf`` (Pa), ``nu``, ``prony_moduli`` (Pa)
and ``relaxation_times`` (s, one entry per term), ``creep_times`` (s) and
``dimensionless_speed`` (``xi = V max(lambda_k) / L``, ``L`` the cell side), plus ``units``.
"""

from pathlib import Path
from xml.sax.saxutils import quoteattr

UNITS = (
    "SI units: lengths, heights, displacements and gaps m, pressure Pa, speed m/s, load N on a 2-D cell "
    "or N/m on a 1-D profile, times s; heights positive toward the solid, displacement positive into it; "
    "the indenter moves in +x"
)


def metadata(surface, result, material=None):
    """Field data of one BEM solution (see module docstring)."""
    import numpy as np

    meta = dict(
        speed=[float(result.speed)],
        load=[float(result.load)],
        friction=[float(result.friction)],
        approach=[float(result.approach)],
        cell_length=[float(surface.length)],
    )
    if material is not None:
        lam = float(np.max(material.creep_times)) if material.creep_times.size else 0.0
        meta.update(
            E0=[float(material.E0)],
            E_inf=[float(material.E_inf)],
            nu=[float(material.nu)],
            prony_moduli=np.asarray(material.moduli, float),
            relaxation_times=np.asarray(material.relaxation_times, float),
            creep_times=np.asarray(material.creep_times, float),
            dimensionless_speed=[float(result.speed) * lam / float(surface.length)],
        )
    meta["units"] = [UNITS]
    return meta


def surface_grid(surface, result, origin=(0.0, 0.0), material=None):
    """A pyvista ImageData of the cell with point data pressure, displacement, gap, contact and
    the field data of :func:`metadata`.

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
    for k, v in metadata(surface, result, material).items():
        grid.field_data[k] = v
    return grid


def write_pvd(path, datasets):
    """Write a ParaView collection ``path`` (.pvd) of ``datasets = [(file, time_value), ...]``
    (file names relative to the .pvd's folder); ParaView opens them as one time series."""
    entries = [f"  <DataSet timestep={quoteattr(repr(float(t)))} file={quoteattr(str(name))}/>" for name, t in datasets]
    Path(path).write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
        + "\n".join(entries)
        + "\n</Collection>\n</VTKFile>\n"
    )


def write_sweep(folder, surface, results, xi, material=None):
    """Write ``point_XXX.vti`` per result and ``sweep.pvd`` (xi as the time value); return names."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names, entries = [], []
    for k, (res, x) in enumerate(zip(results, xi)):
        name = f"point_{k:03d}.vti"
        surface_grid(surface, res, material=material).save(folder / name)
        names.append(f"{folder.name}/{name}")
        entries.append((name, x))
    write_pvd(folder / "sweep.pvd", entries)
    names.append(f"{folder.name}/sweep.pvd")
    return names
