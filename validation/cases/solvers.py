"""Solver adapters of the validation cases: one call, one dict of comparable outputs.

Every adapter returns ``x`` (m, sample abscissae along the sliding direction through the
indenter's axis), ``pressure`` (Pa) there, ``spacing`` (m, the element or cell size used for
edge errors), ``trailing_edge``/``leading_edge`` (m), ``friction``, ``peak_pressure``, and
the native result under ``result``, and ``success``. A BEM solve that misses its tolerance
comes back with ``success=False``, its ``residual`` and ``message`` and nothing else: the
cases then report a failed convergence check instead of comparing an invalid answer. Conventions of docs/theory.md §3: the indenter moves in ``+x``,
the leading edge is at ``+x``, the indenter's axis at ``x = 0``.
"""

from __future__ import annotations

import numpy as np
from scipy.fft import next_fast_len

from validation.metrics import sampled_edges

__all__ = [
    "hertz_line_half_width",
    "bem_periodic_cylinder",
    "fem_cylinder",
    "bem_periodic_sphere",
    "cylinder_cell",
    "bem_isolated_cylinder",
    "bem_isolated_sphere",
]


def hertz_line_half_width(E, nu, radius, load):
    return float(np.sqrt(4.0 * load * radius * (1.0 - nu**2) / (np.pi * E)))


def cylinder_cell(material, radius, load, speed, cells):
    """Periodic cell standing for the isolated line contact: ``(n, spacing)``.

    Spacing ``a_inf / cells`` (glassy Hertz half-width). Length ``40 a_0 + 20 V max(lambda_k)``:
    the images of the neighbouring cylinders change the contact by ``O((a/L)^2)`` (6e-4 at
    ``L = 40 a``), and the material re-enters the contact after ``L / (V lambda) >= 20``
    retardation lengths, its memory decayed to ``exp(-20)``.
    """
    a0 = hertz_line_half_width(material.E0, material.nu, radius, load)
    a_inf = hertz_line_half_width(material.E_inf, material.nu, radius, load)
    dx = a_inf / cells
    lmax = speed * float(np.max(material.creep_times)) if material.creep_times.size else 0.0
    n = next_fast_len(int(np.ceil((40 * a0 + 20 * lmax) / dx)))
    return n + n % 2, dx


def thinnest_layer(material, speed):
    """``V min(tau_k)`` (m): the thinnest leading-edge layer of the pressure (``inf`` elastic or at rest)."""
    taus = np.asarray(material.relaxation_times)
    return float(speed * taus.min()) if taus.size and speed > 0 else float("inf")


def _layer(material, speed, size):
    """``layer``, ``layer_cell`` and ``peak_resolved`` of an adapter output: the peak pressure is judged
    pointwise only where the thinnest layer spans at least one cell or element ``size``."""
    layer = thinnest_layer(material, speed)
    return dict(layer=layer, layer_cell=float(size), peak_resolved=bool(layer >= size))


def _failed(res, detail):
    """Adapter output of a solve that did not reach its tolerance: no fields to compare."""
    return dict(
        success=False,
        residual=float(res.residual),
        message=res.message,
        detail=detail,
        friction=float("nan"),
        result=None,
    )


FLAT = 8.0  # the cylinder profile is flattened beyond FLAT relaxed half-widths from its axis
RTOL = 1e-10  # complementarity tolerance of the BEM solves of the cylinder cases


PERIODIC_LINE_MAXITER = 1000  # active-set iterations of the periodic 1-D cylinder (see below)


def bem_periodic_cylinder(material, *, radius, load, speed, cells):
    """The periodic 1-D BEM (plane strain) on a long cell holding one cylinder.

    The profile ``-x^2 / 2R`` is flattened at ``|x| >= 8 a_0`` (``FLAT``), 64 relaxed Hertz depths
    below the apex, where the solid never touches it (checked). Why: the solver's complementarity
    residual is scaled by the peak-to-valley height, which for the full parabola on a cell of
    ``40 a_0 + 20 V lambda`` grows like ``(L/a_0)^2`` (1e6 at s = 100): the gap tolerance then
    exceeds the contact's own heights (edges off by more than a cell, L2 errors of 1.5-3 %), and
    the three-term Prony case did not converge at s >= 1 (residual 45-4500 after 400 iterations).
    """
    import bem

    n, dx = cylinder_cell(material, radius, load, speed, cells)
    a0 = hertz_line_half_width(material.E0, material.nu, radius, load)
    x = (np.arange(n) - n // 2) * dx
    surface = bem.surfaces.from_heights(np.maximum(-(x**2), -((FLAT * a0) ** 2)) / (2 * radius), n * dx)
    # strongly non-symmetric operators on these long cells: the active set moves the contact edges
    # a few cells per iteration from the symmetric part's contact, so a rubber at its friction
    # peak needs several hundred iterations (the line-preconditioned attempt gets half of them)
    res = bem.solve(
        surface, material, speed=speed, load=load, rtol=RTOL, maxiter=PERIODIC_LINE_MAXITER, raise_on_failure=False
    )
    if not res.success:
        return _failed(res, f"n = {n}: {res.message}")
    if np.any(res.pressure[np.abs(x) >= FLAT * a0] > 0):
        raise RuntimeError("the cylinder touches the solid where its profile is flattened; raise FLAT")
    trail, lead = sampled_edges(x, res.pressure)
    return dict(
        success=True,
        x=x,
        pressure=res.pressure,
        spacing=dx,
        trailing_edge=trail,
        leading_edge=lead,
        friction=res.friction,
        peak_pressure=float(res.pressure.max()),
        result=res,
        material=material,
        surface=surface,
        origin=(float(x[0]), 0.0),
        detail=f"n = {n}, dx = {dx:.3e} m",
        **_layer(material, speed, dx),
    )


def fem_cylinder(material, *, radius, load, speed, resolution, vtk=None, **options):
    """scikit-fem steady rolling (:func:`fem_reference.rolling_cylinder`).

    ``friction`` is the field-dissipation form (the BEM's ``friction`` is the dissipation
    form too); the moment form is kept as ``friction_moment``. Edges are the FEM's own
    (extrapolated) ones; ``spacing`` is the 9-node element size. ``success`` is the solver's
    own; ``contact_residual`` is recomputed from the displacement field
    (:func:`fem_reference.fields.contact_residual`), ``linear_residual`` is the solver's
    ``||K u - f|| / ||f||`` when it reports one, ``linear_residual_limit`` its limit. ``options`` go to ``rolling_cylinder``."""
    import fem_reference
    from fem_reference.fields import contact_residual

    res = fem_reference.rolling_cylinder(
        material, radius=radius, load=load, speed=speed, resolution=resolution, vtk=vtk, keep_fields=True, **options
    )
    friction = res.friction_dissipation if speed > 0 else res.friction
    t = res.timings
    detail = (
        f"{res.n_unknowns} unknowns, {res.n_nonzeros} entries, factor {res.factor_nonzeros}, "
        f"h = {res.element_size:.3e} m; "
    ) + ", ".join(f"{k} {v:.2g} s" for k, v in t.items())
    out = dict(
        success=bool(res.success),
        residual=float(res.residual),
        message=res.message,
        x=res.x,
        pressure=res.pressure,
        spacing=res.element_size,
        trailing_edge=res.trailing_edge,
        leading_edge=res.leading_edge,
        friction=friction,
        friction_moment=res.friction,
        peak_pressure=res.peak_pressure,
        contact_residual=contact_residual(res),
        linear_residual=_linear_residual(res),
        linear_residual_limit=getattr(res, "linear_residual_limit", None),
        force_sum=float(np.sum(res.forces)),
        layer=res.thinnest_layer,
        layer_cell=res.smallest_element,
        peak_resolved=bool(res.peak_resolved),
        power_fields=res.friction_dissipation * load * speed,
        power_moment=res.friction * load * speed,
        timings=dict(t),
        n_unknowns=int(res.n_unknowns),
        detail=detail,
    )
    out["result"] = _without_fields(res)
    return out


def _linear_residual(res):
    """The solver's ``||K u - f|| / ||f||``, or None when this FEM does not report it."""
    value = getattr(res, "linear_residual", None)
    return None if value is None or not np.isfinite(value) else float(value)


def _without_fields(res):
    from dataclasses import replace

    return replace(res, fields={})


def bem_periodic_sphere(material, *, radius, load, speed, cells, cell_radii=8.0):
    """The periodic 2-D BEM on a square cell holding one sphere cap.

    Spacing ``a_inf / cells``; side ``cell_radii`` relaxed Hertz radii. The images of the
    neighbouring spheres bend the surface under the contact by a curvature of relative size
    ``O((a/L)^3)`` (about 2e-3 at ``L = 8 a``), which bounds what this stand-in for an
    isolated contact can show. Returns the profile along ``x`` through the axis.
    """
    import bem

    es = 1.0 - material.nu**2
    a0 = (3 * load * radius * es / (4 * material.E0)) ** (1 / 3)
    a_inf = (3 * load * radius * es / (4 * material.E_inf)) ** (1 / 3)
    dx = a_inf / cells
    n = int(np.ceil(cell_radii * a0 / dx / 2)) * 2
    x = (np.arange(n) - n // 2) * dx
    X, Y = np.meshgrid(x, x, indexing="ij")
    surface = bem.surfaces.from_heights(-(X**2 + Y**2) / (2 * radius), n * dx)
    res = bem.solve(surface, material, speed=speed, load=load, raise_on_failure=False)
    if not res.success:
        return _failed(res, f"{n}^2 cells: {res.message}")
    line = res.pressure[:, n // 2]
    trail, lead = sampled_edges(x, line)
    return dict(
        success=True,
        x=x,
        pressure=line,
        spacing=dx,
        trailing_edge=trail,
        leading_edge=lead,
        friction=res.friction,
        peak_pressure=float(res.pressure.max()),
        result=res,
        material=material,
        surface=surface,
        field=res.pressure,
        X=X,
        Y=Y,
        origin=(float(x[0]), float(x[0])),
        detail=f"{n}^2 cells, dx = {dx:.3e} m",
    )


def _isolated(surface, material, load, speed, method, dx, line, origin):
    import bem

    res = bem.solve(
        surface, material, speed=speed, load=load, periodic=False, method=method, rtol=RTOL, raise_on_failure=False
    )
    n = surface.n
    if not res.success:
        return _failed(res, f"{method}, n = {n}: {res.message}")
    x = surface.x
    p = res.pressure if res.pressure.ndim == 1 else line(res.pressure)
    trail, lead = sampled_edges(x, p)
    return dict(
        success=True,
        x=x,
        pressure=p,
        spacing=dx,
        trailing_edge=trail,
        leading_edge=lead,
        friction=res.friction,
        peak_pressure=float(res.pressure.max()),
        result=res,
        material=material,
        surface=surface,
        field=res.pressure,
        origin=origin(x),
        detail=f"{method}, n = {n}, dx = {dx:.3e} m",
        **_layer(material, speed, dx),
    )


def bem_isolated_cylinder(material, *, radius, load, speed, cells, method):
    """The isolated 1-D BEM (``periodic=False``, ``method`` "uniform" or "adaptive") on a domain of
    four relaxed half-widths centred on the axis (the contact stays within ``[-a_0, a_0]``), cells
    of ``a_inf / cells``, a multiple of 8 of them (three adaptive levels)."""
    import bem

    a0 = hertz_line_half_width(material.E0, material.nu, radius, load)
    dx = hertz_line_half_width(material.E_inf, material.nu, radius, load) / cells
    n = int(np.ceil(4 * a0 / dx / 8)) * 8
    surface = bem.surfaces.cylinder(radius=radius, n=n, length=n * dx)
    return _isolated(surface, material, load, speed, method, dx, None, lambda x: (float(x[0]), 0.0))


def bem_isolated_sphere(material, *, radius, load, speed, cells, method):
    """The isolated 2-D BEM on a square of side three relaxed Hertz radii centred on the axis,
    cells of ``a_inf / cells`` (a multiple of 8 per side). ``pressure`` is the row of cells next to
    the line ``y = 0`` (cell centres at ``y = dx/2``: the comparison uses the exact pressure there)."""
    import bem

    es = 1.0 - material.nu**2
    a0 = (3 * load * radius * es / (4 * material.E0)) ** (1 / 3)
    dx = (3 * load * radius * es / (4 * material.E_inf)) ** (1 / 3) / cells
    n = int(np.ceil(3 * a0 / dx / 8)) * 8
    surface = bem.surfaces.sphere(radius=radius, n=n, length=n * dx)
    out = _isolated(
        surface, material, load, speed, method, dx, lambda f: f[:, n // 2], lambda x: (float(x[0]), float(x[0]))
    )
    if out["success"]:
        X, Y = np.meshgrid(surface.x, surface.x, indexing="ij")
        out.update(X=X, Y=Y, line_y=float(surface.x[n // 2]))
    return out
