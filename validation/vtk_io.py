"""VTK output of BEM surface fields for ParaView (pyvista), with a .pvd per sweep.

Every .vti holds point data ``heights`` (m), ``pressure`` (Pa), ``displacement`` (m, into the
solid), ``gap`` (m) and ``contact`` (1 in contact), and field data (arrays of one value unless
stated):

- the point: ``speed`` (m/s), ``load`` (N per cell, or N/m for a profile), ``friction``,
  ``friction_eq6``, ``approach`` (m), ``contact_fraction``, ``residual``, ``iterations``,
  ``converged`` (1 or 0), ``cell_length`` (m), ``grid_points`` (one entry per axis) and
  ``grid_spacing`` (m);
- with the material: ``E0``, ``E_inf`` (Pa), ``nu``, ``prony_moduli`` (Pa) and
  ``relaxation_times`` (s, one entry per term), ``creep_times`` (s) and
  ``dimensionless_speed`` (``V max(lambda_k) / L``, ``L`` the cell side);
- provenance (strings): ``viscobem_version``, ``solver`` (which solver and how it was called),
  ``solver_settings`` (JSON: ``rtol``, ``maxiter``, ``periodic``, ``method``, the grid, ...),
  ``material_given`` (JSON: the material as the user gave it, e.g. a scene's ``[material]``
  table, before any folding of inactive terms), and ``rtol`` as a number;
- in a series: ``series_parameter`` (its name and unit) and ``series_value``;
- ``units``: a JSON object giving the unit of every point and field array by name (``"1"`` for
  a dimensionless one; ``json.loads(grid.field_data["units"][0])``), and ``conventions``, the
  sign conventions in words.

A ``.pvd`` collection lists one file per point with the series parameter as ParaView's *time*
value (ParaView calls it time whatever it is); the file says in a comment which parameter and
unit that is, and each dataset's field data repeats it.
"""

import json
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

CONVENTIONS = (
    "SI units; heights positive toward the solid, displacement positive into it; the indenter "
    "moves in +x; friction is the dissipation form, friction_eq6 the direct form (-1/F_N) int p dh/dx dA"
)
POINT_UNITS = {"heights": "m", "pressure": "Pa", "displacement": "m", "gap": "m", "contact": "1"}
FIELD_UNITS = {
    "speed": "m/s",
    "load": "N (N/m on a 1-D profile)",
    "friction": "1",
    "friction_eq6": "1",
    "approach": "m",
    "contact_fraction": "1",
    "residual": "1",
    "iterations": "1",
    "converged": "1",
    "cell_length": "m",
    "grid_points": "1",
    "grid_spacing": "m",
    "rtol": "1",
    "E0": "Pa",
    "E_inf": "Pa",
    "nu": "1",
    "prony_moduli": "Pa",
    "relaxation_times": "s",
    "creep_times": "s",
    "dimensionless_speed": "1",
    "xi": "1",
    "series_value": "the unit named in series_parameter",
}


def version():
    """The installed viscobem version (``unknown`` in a source tree that is not installed)."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("viscobem")
    except PackageNotFoundError:
        return "unknown"


def provenance(*, solver, settings, material_given=None):
    """Field data naming what made a file: the version, the solver and its settings (``rtol``,
    ``maxiter``, grid, ...: any JSON-ready dict) and the material as the user gave it."""
    meta = {
        "viscobem_version": [version()],
        "solver": [str(solver)],
        "solver_settings": [json.dumps(settings, sort_keys=True, default=str)],
    }
    if "rtol" in settings and settings["rtol"] is not None:
        meta["rtol"] = [float(settings["rtol"])]
    if material_given is not None:
        meta["material_given"] = [json.dumps(material_given, sort_keys=True, default=str)]
    return meta


def metadata(surface, result, material=None):
    """Field data of one BEM solution: the point, the grid and the material (module docstring)."""
    import numpy as np

    shape = np.shape(result.pressure)
    meta = dict(
        speed=[float(result.speed)],
        load=[float(result.load)],
        friction=[float(result.friction)],
        friction_eq6=[float(result.friction_eq6)],
        approach=[float(result.approach)],
        contact_fraction=[float(result.contact_fraction)],
        residual=[float(result.residual)],
        iterations=[int(result.iterations)],
        converged=[int(bool(result.success))],
        cell_length=[float(surface.length)],
        grid_points=[int(n) for n in shape],
        grid_spacing=[float(surface.spacing)],
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
    return meta


def units(field_data, point_data=POINT_UNITS):
    """The ``units`` JSON object for the arrays present (point arrays, then field arrays)."""
    table = dict(point_data)
    table.update({k: FIELD_UNITS.get(k, "text") for k in field_data if k not in ("units", "conventions")})
    return [json.dumps(table)]


def surface_grid(surface, result, origin=(0.0, 0.0), material=None, *, extra=None):
    """A pyvista ImageData of the cell with point data pressure, displacement, gap, contact and
    the field data of :func:`metadata`, plus ``extra`` field data (e.g. :func:`provenance`).

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
    meta = metadata(surface, result, material)
    meta.update(extra or {})
    meta["units"] = units(meta)
    meta["conventions"] = [CONVENTIONS]
    for k, v in meta.items():
        grid.field_data[k] = v
    return grid


def write_pvd(path, datasets, parameter="time value"):
    """Write a ParaView collection ``path`` (.pvd) of ``datasets = [(file, value), ...]`` (file
    names relative to the .pvd's folder); ParaView opens them as one series whose *time* is
    ``value``, and a comment in the file names that ``parameter`` (with its unit)."""
    entries = [f"  <DataSet timestep={quoteattr(repr(float(t)))} file={quoteattr(str(name))}/>" for name, t in datasets]
    note = escape(f"timestep = {parameter} (ParaView shows it as Time)").replace("--", "- -")
    Path(path).write_text(
        f'<?xml version="1.0"?>\n<!-- {note} -->\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
        + "\n".join(entries)
        + "\n</Collection>\n</VTKFile>\n"
    )


def pvd_parameter(path):
    """The series parameter a .pvd written by :func:`write_pvd` names (None if it names none)."""
    import re

    match = re.search(r"<!-- timestep = (.*?) \(ParaView shows it as Time\) -->", Path(path).read_text())
    return match.group(1) if match else None


def write_sweep(folder, surface, results, xi, material=None, *, extra=None):
    """Write ``point_XXX.vti`` per result and ``sweep.pvd``; return the names written.

    The series runs over the sliding speed: it is the .pvd's time value (m/s), so ParaView's
    time shows the speed; each file's field data also holds ``xi``, the study's dimensionless
    speed, and ``extra`` (e.g. :func:`provenance`)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names, entries = [], []
    parameter = "sliding speed V (m/s)"
    for k, (res, x) in enumerate(zip(results, xi)):
        name = f"point_{k:03d}.vti"
        point = dict(extra or {}, xi=[float(x)], series_parameter=[parameter], series_value=[float(res.speed)])
        surface_grid(surface, res, material=material, extra=point).save(folder / name)
        names.append(f"{folder.name}/{name}")
        entries.append((name, float(res.speed)))
    write_pvd(folder / "sweep.pvd", entries, parameter)
    names.append(f"{folder.name}/sweep.pvd")
    return names
