"""VTK export of a steady-rolling solution for ParaView: the block and its contact interface.

``write_fields(path, fields, result)`` writes, by the extension of ``path``:

- ``.vtm``: a multiblock with two datasets, ``volume`` (the block, .vtu) and ``interface``
  (the candidate contact band of the top surface, .vtp), in a folder beside the .vtm;
- ``.vtu``: the volume only.

Volume, point data: ``displacement`` (m, 3 components, z = 0). Cell data (element averages of
the Gauss-point values, weighted by the quadrature weights): ``stress`` and ``strain`` as full
3x3 tensors (components ``XX, XY, XZ, YX, YY, YZ, ZX, ZY, ZZ``; plane strain: ``strain ZZ = 0``,
``stress ZZ`` from the trace, :mod:`fem_reference.fields`), ``von_mises`` and
``hydrostatic_pressure`` (Pa, positive in compression), ``viscous_strain_tau=<tau>s`` per Prony
term (the strain of its dashpot, a full tensor) and ``dissipation`` (W/m^3). Point data beside
them: ``stress_nodal``, ``von_mises_nodal`` and ``hydrostatic_pressure_nodal`` (Pa, the L2
projection of the quadrature values onto the nodes, :mod:`fem_reference.nodal`).

Interface, point data at the top nodes ``x`` (m): ``pressure`` (Pa), ``gap`` (m, with the
cylinder's profile ``h = -x^2/2R`` and the approach), ``contact`` (1 in contact), ``depression``
(m, into the solid) and ``displacement`` (m, 3 components, from the field).

A periodic profile (:func:`fem_reference.sliding_profile`) is written the same way: the volume is one
period of the strip, the interface its surface with the profile's ``heights`` (m) and ``slopes`` beside
the gap, and its field data has ``period`` (m) where the rolling file has ``radius``,
``dimensionless_speed = V max(lambda_k) / L`` and ``contact_fraction``.

Field data on both (arrays of one value unless stated): ``speed`` (m/s), ``load`` (N/m),
``radius`` (m), ``E0``, ``E_inf`` (Pa), ``nu``, ``prony_moduli`` (Pa) and ``relaxation_times``
(s, one entry per term), ``creep_times`` (s) of the material the solver used (inactive Prony terms
folded), the same with the prefix ``input_`` for the material as given, ``dimensionless_speed``
(``V max(lambda_k) / a0``, retardation length over the relaxed Hertz half-width), the friction in
both forms, ``friction_dissipation`` (field dissipation over ``P V``, the form the validation harness
compares) and ``friction_moment`` (``x_bar / R``, the moment of the nodal forces), ``friction`` (the
dissipation form; the moment form at rest), ``approach`` (m), the provenance of :func:`provenance`:
``viscobem_version``, ``solver``, ``solver_settings`` (JSON: mesh, grading, element size, domain, linear
solver), and, as in the BEM's files, ``units`` (JSON: the unit of every point, cell and field array of
the dataset by name, ``"1"`` for a dimensionless one, ``"text"`` for a string) and ``conventions`` (the
sign conventions in words).

``write_indentation(path, ...)`` writes the creep indentation as a ``.pvd`` time series (time in s) of
``.vtm`` files with the same names, in the ``(r, z)`` plane (x = r, y = z; the tensors' ``ZZ`` is the
hoop component ``theta theta``): ``displacement``, ``stress``, ``strain``, ``von_mises``,
``hydrostatic_pressure``, ``viscous_strain_tau=<tau>s`` and ``dissipation`` (W/m^3) in the block (the
stress with the mixed solve's own pressure, :meth:`~fem_reference.axisymmetric.AxisymmetricStepper.pressure`);
``pressure``, ``gap``, ``contact``, ``depression`` on the interface; field data ``time``, ``load``
(N), ``radius``, the material, ``units`` and ``conventions``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import fields as derived
from .rolling_inputs import hertz_half_width

__all__ = [
    "write_fields",
    "write_indentation",
    "volume_grid",
    "interface_points",
    "metadata",
    "units",
    "UNITS",
    "CONVENTIONS",
    "COMPONENTS",
]

CONVENTIONS = (
    "SI units; strains are tensor components, not engineering shear; pressure and hydrostatic_pressure "
    "positive in compression; depression positive into the solid; the cylinder moves in +x"
)
PROFILE_CONVENTIONS = (
    "SI units; strains are tensor components, not engineering shear; pressure and hydrostatic_pressure "
    "positive in compression; depression positive into the solid; heights positive toward the solid; "
    "the profile moves in +x; one period of a periodic strip, load per period and unit length"
)
# The unit of every array the FEM writes, by name (a prefix ``input_`` keeps its unit); the load is
# a force per unit length in z for plane-strain rolling and a force for axisymmetric indentation.
UNITS = {
    **dict.fromkeys(("stress", "stress_nodal", "von_mises", "von_mises_nodal", "pressure"), "Pa"),
    **dict.fromkeys(("hydrostatic_pressure", "hydrostatic_pressure_nodal", "E0", "E_inf", "prony_moduli"), "Pa"),
    **dict.fromkeys(("displacement", "gap", "depression", "radius", "approach", "heights", "period"), "m"),
    **dict.fromkeys(("strain", "contact", "nu", "dimensionless_speed", "contact_fraction", "slopes"), "1"),
    **dict.fromkeys(("friction", "friction_dissipation", "friction_moment"), "1"),
    **dict.fromkeys(("relaxation_times", "creep_times", "time"), "s"),
    "dissipation": "W/m^3",
    "speed": "m/s",
    "load": "N/m",
}
_VISCOUS = "viscous_strain_tau="
COMPONENTS = ("XX", "XY", "XZ", "YX", "YY", "YZ", "ZX", "ZY", "ZZ")


def _cell_average(values, weights, nel):
    """Weighted element average of quadrature-point values (ngp[, ncomp])."""
    nqp = weights.size // nel
    w = weights.reshape(nel, nqp)
    v = values.reshape(nel, nqp, -1)
    return np.einsum("eq,eqc->ec", w, v) / w.sum(axis=1)[:, None]


def tau_name(tau):
    """Array name of the viscous strain of the Prony term with relaxation time ``tau`` (s)."""
    return f"viscous_strain_tau={tau:.3g}s"


def _name_components(dataset):
    for name in ("stress", "strain", *[k for k in dataset.cell_data if k.startswith("viscous_strain")]):
        arr = dataset.GetCellData().GetArray(name)
        if arr is not None:
            for i, c in enumerate(COMPONENTS):
                arr.SetComponentName(i, c)


def volume_grid(fields, material=None):
    """A pyvista UnstructuredGrid of the block (see module docstring)."""
    import pyvista as pv

    mesh, basis, u, weights = fields["mesh"], fields["basis"], fields["u"], fields["weights"]
    nel = mesh.t.shape[1]
    points = np.zeros((mesh.p.shape[1], 3))
    points[:, :2] = mesh.p.T
    cells = np.hstack([np.full((nel, 1), 4), mesh.t.T]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(nel, pv.CellType.QUAD, dtype=np.uint8), points)
    disp = np.zeros((mesh.p.shape[1], 3))
    disp[:, :2] = u[basis.nodal_dofs].T
    grid.point_data["displacement"] = disp
    stress = derived.stress_tensor(fields["stress"], fields["pressure"])
    grid.cell_data["stress"] = _cell_average(stress, weights, nel)
    grid.cell_data["strain"] = _cell_average(derived.strain_tensor(fields["strain"]), weights, nel)
    grid.cell_data["von_mises"] = _cell_average(derived.von_mises(stress), weights, nel)[:, 0]
    grid.cell_data["hydrostatic_pressure"] = _cell_average(derived.hydrostatic_pressure(stress), weights, nel)[:, 0]
    grid.cell_data["dissipation"] = _cell_average(fields["dissipation"], weights, nel)[:, 0]
    _add_nodal(grid, stress, basis)
    taus = material.relaxation_times if material is not None else range(len(fields["alpha"]))
    for tau, a in zip(taus, fields["alpha"]):
        grid.cell_data[tau_name(tau)] = _cell_average(derived.strain_tensor(np.asarray(a).reshape(-1, 3)), weights, nel)
    _name_components(grid)
    return grid


def _add_nodal(dataset, stress, basis):
    """Point data beside the cell averages: the stress, von Mises and hydrostatic pressure at the
    nodes (``*_nodal``, the L2 projection of the quadrature values, :mod:`fem_reference.nodal`)."""
    from .nodal import project_to_nodes

    nodal = project_to_nodes(stress, basis)
    dataset.point_data["stress_nodal"] = nodal
    dataset.point_data["von_mises_nodal"] = derived.von_mises(nodal)
    dataset.point_data["hydrostatic_pressure_nodal"] = derived.hydrostatic_pressure(nodal)
    arr = dataset.GetPointData().GetArray("stress_nodal")
    for i, c in enumerate(COMPONENTS):
        arr.SetComponentName(i, c)


def provenance(solver, settings):
    """Field data naming what made a file: ``viscobem_version``, ``solver`` and ``solver_settings``
    (JSON: mesh, grading, element size, domain, linear solver, ...)."""
    import json
    from importlib.metadata import PackageNotFoundError, version

    try:
        installed = version("viscobem")
    except PackageNotFoundError:
        installed = "unknown"
    return {
        "viscobem_version": [installed],
        "solver": [solver],
        "solver_settings": [json.dumps(settings, sort_keys=True, default=str)],
    }


def units(dataset, load="N/m"):
    """The ``units`` field data of ``dataset``: JSON giving the unit of each of its point, cell and
    field arrays by name, the same object the BEM's files carry, so one reader serves both.
    ``load`` is the unit of the load (N/m in plane strain, N for axisymmetric indentation)."""
    import json

    table = {}
    for name in (*dataset.point_data.keys(), *dataset.cell_data.keys(), *dataset.field_data.keys()):
        if name in ("units", "conventions"):
            continue
        base = name.removeprefix("input_")
        unit = "1" if base.startswith(_VISCOUS) else UNITS.get(base, "text")
        table[name] = load if base == "load" else unit
    return [json.dumps(table, sort_keys=True)]


def interface_points(result):
    """A pyvista PolyData of the candidate contact band's top nodes (see module docstring)."""
    import pyvista as pv

    from .surface import band, top_surface

    x = np.asarray(result.x, float)
    pts = np.zeros((x.size, 3))
    pts[:, 0] = x
    poly = pv.PolyData(pts)
    poly.lines = np.hstack([[x.size], np.arange(x.size)])
    w = np.asarray(result.displacement, float)
    poly.point_data["pressure"] = np.asarray(result.pressure, float)
    # heights positive toward the solid: the cylinder's -x^2 / 2R, or a periodic profile's own
    heights = result.heights if _is_profile(result) else -(x**2) / (2 * result.radius)
    poly.point_data["gap"] = w - heights - result.approach
    if _is_profile(result):
        poly.point_data["heights"] = np.asarray(heights, float)
        poly.point_data["slopes"] = np.asarray(result.slopes, float)
    poly.point_data["contact"] = (np.asarray(result.pressure) > 0).astype(np.uint8)
    poly.point_data["depression"] = w
    disp = np.zeros((x.size, 3))
    f = result.fields
    if f:
        top = top_surface(f["basis"])
        cand = band(top, x)
        u = np.asarray(f["u"])
        disp[:, 0] = u[top.ydofs[cand] - 1]  # the x DOF precedes the y DOF of each node
        disp[:, 1] = u[top.ydofs[cand]]
    poly.point_data["displacement"] = disp
    return poly


def _is_profile(result):
    return hasattr(result, "heights") and hasattr(result, "spots")


def _profile_metadata(result):
    """Field data of a :class:`~fem_reference.ProfileResult`: as the rolling result's, with the period
    (m) for the radius, ``dimensionless_speed = V max(lambda_k) / L`` and the contact fraction."""
    m = result.material
    given = getattr(result, "input_material", None) or m
    lam = float(np.max(m.creep_times)) if m.creep_times.size else 0.0
    diss = result.friction_dissipation if result.speed > 0 else result.friction
    settings = ("elements", "passes", "n_elements", "n_unknowns", "solver", "iterations", "residual", "linear_residual")
    return dict(
        speed=[result.speed],
        load=[result.load],
        period=[result.length],
        **_material_data(m),
        **_material_data(given, "input_"),
        dimensionless_speed=[result.speed * lam / result.length],
        friction=[diss],
        friction_dissipation=[diss],
        friction_moment=[result.friction],
        contact_fraction=[result.contact_fraction],
        approach=[result.approach],
        conventions=[PROFILE_CONVENTIONS],
        **provenance(
            "fem_reference.sliding_profile (scikit-fem: plane strain, one period of a periodic strip, steady "
            "Eulerian Prony terms on closed streamlines, Q2 displacement / discontinuous P1 pressure)",
            {k: getattr(result, k) for k in settings},
        ),
    )


def metadata(result):
    """Field data of a :class:`~fem_reference.RollingResult` or :class:`~fem_reference.ProfileResult`
    (see module docstring)."""
    if _is_profile(result):
        return _profile_metadata(result)
    m = result.material
    given = getattr(result, "input_material", None) or m
    a0 = hertz_half_width(m.E0, m.nu, result.radius, result.load)
    lam = float(np.max(m.creep_times)) if m.creep_times.size else 0.0
    diss = result.friction_dissipation if result.speed > 0 else result.friction
    return dict(
        speed=[result.speed],
        load=[result.load],
        radius=[result.radius],
        **_material_data(m),
        **_material_data(given, "input_"),
        dimensionless_speed=[result.speed * lam / a0],
        friction=[diss],
        friction_dissipation=[diss],
        friction_moment=[result.friction],
        approach=[result.approach],
        conventions=[CONVENTIONS],
        **provenance(
            "fem_reference.rolling_cylinder (scikit-fem: plane strain, steady Eulerian Prony terms, Q2 displacement / discontinuous P1 pressure)",
            {
                k: getattr(result, k)
                for k in (
                    "mesh",
                    "element_size",
                    "grading",
                    "domain_width",
                    "domain_depth",
                    "n_elements",
                    "n_unknowns",
                    "solver",
                    "passes",
                    "iterations",
                    "residual",
                    "linear_residual",
                )
            },
        ),
    )


def _add_field_data(dataset, meta, load="N/m"):
    for k, v in meta.items():
        dataset.field_data[k] = v
    dataset.field_data["units"] = units(dataset, load)


def write_fields(path, fields, result=None):
    """Write ``fields`` (``RollingResult.fields``) and, with ``result``, the interface and the
    metadata, to ``path`` (.vtm or .vtu; see module docstring). Returns the path."""
    import pyvista as pv

    path = Path(path)
    vol = volume_grid(fields, None if result is None else result.material)
    meta = metadata(result) if result is not None else {"conventions": [CONVENTIONS]}
    _add_field_data(vol, meta)
    if path.suffix == ".vtm":
        if result is None:
            raise ValueError("a .vtm holds the interface too: pass the RollingResult")
        iface = interface_points(result)
        _add_field_data(iface, meta)
        pv.MultiBlock({"volume": vol, "interface": iface}).save(path)
    else:
        vol.save(path)
    return path


def _axisymmetric_strain(v):
    """Full tensors from axisymmetric Voigt ``(rr, zz, tt, rz)`` with engineering shear (x = r,
    y = z, z = theta)."""
    v = np.asarray(v, float).reshape(-1, 4)
    return derived.full_tensor(v[:, 0], v[:, 1], v[:, 2], 0.5 * v[:, 3])


def _axisymmetric_stress(v):
    """Full tensors (Pa) from axisymmetric Voigt stresses ``(rr, zz, tt, rz)`` (x = r, y = z, z = theta)."""
    v = np.asarray(v, float).reshape(-1, 4)
    return derived.full_tensor(v[:, 0], v[:, 1], v[:, 2], v[:, 3])


def _indentation_snapshot(snap, ops, material, radius, r, top, meta):
    import pyvista as pv

    mesh, basis, weights = ops.basis.mesh, ops.basis, ops.weights
    nel = mesh.t.shape[1]
    points = np.zeros((mesh.p.shape[1], 3))
    points[:, :2] = mesh.p.T
    cells = np.hstack([np.full((nel, 1), 4), mesh.t.T]).ravel()
    vol = pv.UnstructuredGrid(cells, np.full(nel, pv.CellType.QUAD, dtype=np.uint8), points)
    u = np.asarray(snap["u"])
    disp = np.zeros((mesh.p.shape[1], 3))
    disp[:, :2] = u[basis.nodal_dofs].T
    vol.point_data["displacement"] = disp
    vol.cell_data["strain"] = _cell_average(_axisymmetric_strain(snap["eps"]), weights, nel)
    stress = _axisymmetric_stress(snap["stress"])
    vol.cell_data["stress"] = _cell_average(stress, weights, nel)
    vol.cell_data["von_mises"] = _cell_average(derived.von_mises(stress), weights, nel)[:, 0]
    vol.cell_data["hydrostatic_pressure"] = _cell_average(derived.hydrostatic_pressure(stress), weights, nel)[:, 0]
    _add_nodal(vol, stress, basis)
    for tau, a in zip(material.relaxation_times, snap["alpha"], strict=True):
        vol.cell_data[tau_name(tau)] = _cell_average(_axisymmetric_strain(a), weights, nel)
    vol.cell_data["dissipation"] = _cell_average(np.asarray(snap["dissipation"], float), weights, nel)[:, 0]
    _name_components(vol)
    pts = np.zeros((r.size, 3))
    pts[:, 0] = r
    iface = pv.PolyData(pts)
    iface.lines = np.hstack([[r.size], np.arange(r.size)])
    w = -u[top.ydofs[: r.size]]
    iface.point_data["pressure"] = np.asarray(snap["pressure"], float)
    iface.point_data["gap"] = w + r**2 / (2 * radius) - snap["approach"]
    iface.point_data["contact"] = (np.asarray(snap["pressure"]) > 0).astype(np.uint8)
    iface.point_data["depression"] = w
    for ds in (vol, iface):
        _add_field_data(ds, dict(meta, time=[snap["t"]], approach=[snap["approach"]]), load="N")
    return pv.MultiBlock({"volume": vol, "interface": iface})


def write_indentation(path, snapshots, ops, material, radius, load, r):
    """Write the indentation ``snapshots`` (dicts with ``t``, ``u``, ``eps``, ``alpha``, ``stress``
    (axisymmetric Voigt, Pa), ``dissipation`` (W/m^3), ``pressure`` at the candidate radii ``r``, ``approach``) as ``point_XXX.vtm`` files beside the
    ``.pvd`` ``path``; returns the path."""
    from xml.sax.saxutils import quoteattr

    from .surface import top_surface

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    top = top_surface(ops.basis, axisymmetric=True)
    meta = _material_data(material)
    meta.update(load=[load], radius=[radius], conventions=[CONVENTIONS])
    meta.update(
        provenance(
            "fem_reference.indentation (scikit-fem: axisymmetric, exponential time steps)",
            {"n_elements": ops.basis.mesh.t.shape[1], "times": [s["t"] for s in snapshots]},
        )
    )
    entries = []
    for k, snap in enumerate(snapshots):
        name = f"{path.stem}_{k:03d}.vtm"
        _indentation_snapshot(snap, ops, material, radius, np.asarray(r, float), top, meta).save(path.parent / name)
        entries.append(f"  <DataSet timestep={quoteattr(repr(snap['t']))} file={quoteattr(name)}/>")
    path.write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
        + "\n".join(entries)
        + "\n</Collection>\n</VTKFile>\n"
    )
    return path


def _material_data(m, prefix=""):
    data = dict(
        E0=[m.E0],
        E_inf=[m.E_inf],
        nu=[m.nu],
        prony_moduli=np.asarray(m.moduli, float),
        relaxation_times=np.asarray(m.relaxation_times, float),
        creep_times=np.asarray(m.creep_times, float),
    )
    return {prefix + k: v for k, v in data.items()}
