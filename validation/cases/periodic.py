"""Periodic-cell cases: rough surface in full contact, Westergaard's sinusoid, and elastic
rough contact against a dense direct solve.

Solver: ``bem-periodic`` (:func:`bem.solve`). References: ``exact`` (Fourier full-contact
solution and Westergaard, :mod:`validation.references.periodic_exact`, :mod:`validation.references.westergaard`)
and ``dense`` (explicit influence matrix and Murty's principal pivoting).
"""

from __future__ import annotations

import numpy as np

import bem
from bem import surfaces
from validation import metrics
from validation.references.periodic_exact import dense_contact, full_contact
from validation.references.westergaard import westergaard

from .base import Case, CaseOutput, Profile, Sweep
from .cylinder import sls
from .vtk_out import write_bem_sweep

L = 1e-3  # cell side (m)


def _rough(n, dim, seed):
    return surfaces.self_affine(n, L, hurst=0.8, scales=n // 4, rms_height=1e-6, seed=seed, dim=dim)


def _line(field):
    return field if field.ndim == 1 else field[:, 0]


def run_full_contact(*, quick, vtk_dir, root, tamper):
    material = sls(3)
    cfg = QUICK_FULL if quick else FULL_FULL
    out = CaseOutput()
    lam = float(material.creep_times[0])
    for dim, n in cfg["grids"]:
        s = _rough(n, dim, seed=5)
        # mean pressure 1.5x the one that just closes every gap at the slowest speed (checked below)
        p0, _ = full_contact(s.heights, L, material, 0.0, 0.0)
        p_mean = 1.5 * float(-p0.min()) * material.E_inf / material.E0
        sols, mu_b, mu_e = [], [], []
        for xi in cfg["xi"]:
            V = xi * L / lam
            label = f"{dim}-D n={n} xi={xi:g}"
            p_ex, mu_ex = full_contact(s.heights, L, material, V, p_mean)
            if p_ex.min() <= 0:
                raise RuntimeError(f"{label}: the chosen load does not close every gap")
            m, v, load = tamper.inputs("bem-periodic", material, V, p_mean * L**dim)
            res, cost = metrics.measure(bem.solve, s, m, speed=v, load=load, rtol=1e-10)
            out.cost("bem-periodic", label, cost, f"{n}^{dim} points")
            out.check("pressure_rel_max", "bem-periodic", label, metrics.rel_max(res.pressure, p_ex), cfg["tol"], WHY)
            out.check(
                "friction_rel_error", "bem-periodic", label, metrics.rel_diff(res.friction, mu_ex), cfg["tol"], WHY
            )
            out.check(
                "friction_eq6_rel_error",
                "bem-periodic",
                label,
                metrics.rel_diff(res.friction_eq6, mu_ex),
                cfg["tol"],
                WHY,
            )
            sols.append(dict(surface=s, result=res, material=m))
            mu_b.append(res.friction)
            mu_e.append(mu_ex)
            if xi == cfg["xi"][len(cfg["xi"]) // 2]:
                x = np.arange(n) * L / n
                out.profiles.append(
                    Profile(
                        f"{label} (line y = 0)",
                        {"exact": (x, _line(p_ex)), "bem-periodic": (x, _line(res.pressure))},
                        reference="exact",
                        errors={"bem-periodic": (x, _line(res.pressure - p_ex))},
                    )
                )
        out.sweeps.append(
            Sweep(
                f"friction against speed, {dim}-D n = {n}",
                "xi = V lambda / L",
                "friction",
                {"exact": (np.array(cfg["xi"]), np.array(mu_e)), "bem-periodic": (np.array(cfg["xi"]), np.array(mu_b))},
            )
        )
        if vtk_dir is not None:
            out.files += write_bem_sweep(vtk_dir / f"bem_{dim}d", root, sols, cfg["xi"], parameter="xi", rtol=1e-10)
    return out


def run_westergaard(*, quick, vtk_dir, root, tamper):
    E, nu, g0, lam = 1e7 / 3, 0.5, 1e-6, L
    material = bem.Material.elastic(E, nu)
    cfg = QUICK_WEST if quick else FULL_WEST
    n = cfg["n"]
    x = np.arange(n) * L / n
    out = CaseOutput()
    sols = []
    p_star = np.pi * E / (1 - nu**2) * g0 / lam
    for frac in cfg["fractions"]:
        ex = westergaard(g0, lam, frac * p_star, E, nu)
        surface = surfaces.sinusoid(n, L, amplitude=g0)
        m, v, load = tamper.inputs("bem-periodic", material, 0.0, ex.load)
        res, cost = metrics.measure(bem.solve, surface, m, speed=v, load=load, rtol=1e-10)
        label = f"p/p*={frac:g}"
        out.cost("bem-periodic", label, cost, f"n = {n}")
        p_ex = ex.pressure(x)
        dx = L / n
        t = cfg["tol"]
        out.check(
            "pressure_rel_l2",
            "bem-periodic",
            label,
            metrics.rel_l2(None, res.pressure, p_ex),
            t["l2"] / n,
            WHY_WEST["l2"],
        )
        out.check(
            "pressure_rel_max",
            "bem-periodic",
            label,
            metrics.rel_max(res.pressure, p_ex),
            t["max"] / np.sqrt(n),
            WHY_WEST["max"],
        )
        out.check(
            "peak_pressure_rel_error",
            "bem-periodic",
            label,
            metrics.rel_diff(res.pressure.max(), p_ex.max()),
            t["peak"] / n,
            WHY_WEST["peak"],
        )
        if not ex.full_contact:
            # centred view: the crest at x = 0, contact [-a, a]
            xc = np.where(x > L / 2, x - L, x)
            order = np.argsort(xc)
            trail, lead = metrics.sampled_edges(xc[order], res.pressure[order])
            out.check(
                "half_width_error_cells",
                "bem-periodic",
                label,
                metrics.edge_error(0.5 * (lead - trail), ex.half_width, dx),
                t["edge"],
                WHY_WEST["edge"],
            )
        xs = np.roll(np.where(x >= L / 2, x - L, x), n // 2)
        out.profiles.append(
            Profile(
                label,
                {"exact": (xs, np.roll(p_ex, n // 2)), "bem-periodic": (xs, np.roll(res.pressure, n // 2))},
                reference="exact",
                errors={"bem-periodic": (xs, np.roll(res.pressure - p_ex, n // 2))},
            )
        )
        sols.append(dict(surface=surface, result=res, material=m))
    if vtk_dir is not None:
        out.files += write_bem_sweep(vtk_dir / "bem", root, sols, cfg["fractions"], parameter="fraction", rtol=1e-10)
    return out


def run_dense(*, quick, vtk_dir, root, tamper):
    material = bem.Material.elastic(1e7 / 3)
    cfg = QUICK_DENSE if quick else FULL_DENSE
    out = CaseOutput()
    sols = []
    for dim, n, overlap in cfg["grids"]:
        s = _rough(n, dim, seed=3)
        label = f"{dim}-D n={n}"
        (p, delta, pivots), cost = tamper.reference(
            ("dense", dim, n), metrics.measure, dense_contact, s.heights, L, material, overlap * np.ptp(s.heights)
        )
        out.cost("dense", label, cost, f"{n}^{dim} unknowns, {pivots} pivots")
        load = float(p.mean() * L**dim)
        m, v, load = tamper.inputs("bem-periodic", material, 0.0, load)
        res, cost = metrics.measure(bem.solve, s, m, speed=v, load=load, rtol=1e-12)
        out.cost("bem-periodic", label, cost, f"{res.iterations} iterations")
        out.check("pressure_rel_max", "bem-periodic", label, metrics.rel_max(res.pressure, p), cfg["tol"], WHY_DENSE)
        out.check(
            "approach_rel_error", "bem-periodic", label, metrics.rel_diff(res.approach, delta), cfg["tol"], WHY_DENSE
        )
        out.check(
            "contact_set_mismatch_points",
            "bem-periodic",
            label,
            float(np.count_nonzero((res.pressure > 0) != (p > 0))),
            0.0,
            "the LCP solution is unique (P-matrix): the same contact set, exactly",
        )
        out.numbers[label] = dict(contact_fraction=float(np.mean(p > 0)), pivots=int(pivots))
        x = np.arange(n) * L / n
        out.profiles.append(
            Profile(
                f"{label} (line y = 0)",
                {"dense": (x, _line(p)), "bem-periodic": (x, _line(res.pressure))},
                reference="dense",
                errors={"bem-periodic": (x, _line(res.pressure - p))},
            )
        )
        sols.append(dict(surface=s, result=res, material=m))
    if vtk_dir is not None:
        out.files += write_bem_sweep(vtk_dir / "bem", root, sols, list(range(len(sols))), parameter="index", rtol=1e-12)
    return out


# --------------------------------------------------------------------------- settings and tolerances
WHY = (
    "the same Fourier solution: the BEM's full contact set is exact, so only round-off and its "
    "residual (rtol 1e-10) remain; measured <= 1e-12"
)
QUICK_FULL = dict(grids=[(1, 256), (2, 64)], xi=[1e-2, 1e-1, 1.0], tol=1e-8)
FULL_FULL = dict(grids=[(1, 4096), (2, 256)], xi=[1e-3, 1e-2, 1e-1, 1.0, 10.0], tol=1e-8)
# Westergaard (docs/theory.md §3 elastic): the sampled square-root edge gives an L2 error ~ 0.86/n (tests:
# slope -1.00) and a pointwise one ~ C / sqrt(n) next to the edge; bounds 3/n and 2/sqrt(n).
WHY_WEST = {
    "l2": "first order in dx (measured err * n = 0.86 at a = lam/4); bound 3/n",
    "max": "next to the square-root edge ~ sqrt(dx/a); bound 2/sqrt(n)",
    "peak": "interior point, O(dx) through the load carried by the edge cells; bound 2/n",
    "edge": "edge between two samples: half a cell plus the solver's; one cell",
}
QUICK_WEST = dict(n=256, fractions=[0.1, 0.5, 0.9, 1.5], tol=dict(l2=3.0, max=2.0, peak=2.0, edge=1.0))
FULL_WEST = dict(n=4096, fractions=[0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 1.5], tol=dict(l2=3.0, max=2.0, peak=2.0, edge=1.0))
WHY_DENSE = (
    "same discrete LCP (unique solution), BEM at rtol 1e-12: differences are the iterative "
    "solve's tolerance times the conditioning; measured <= 1e-11 (tests: <= 6e-12)"
)
QUICK_DENSE = dict(grids=[(1, 64, 0.5), (2, 24, 0.3)], tol=1e-7)
FULL_DENSE = dict(grids=[(1, 256, 0.5), (2, 24, 0.3), (2, 32, 0.45)], tol=1e-7)

CASES = [
    Case(
        "full_contact_rough",
        "Rough surface in full contact (viscoelastic, exact Fourier solution)",
        "Self-affine surface (H = 0.8) pressed into full contact on the seed SLS; the pressure and friction "
        "are exact in Fourier space at every speed.",
        ("exact", "bem-periodic"),
        "exact",
        run_full_contact,
    ),
    Case(
        "westergaard",
        "Westergaard's sinusoid (elastic)",
        "Rigid sinusoid (1 um amplitude, 1 mm wavelength) on an elastic half-space, partial and full contact.",
        ("exact", "bem-periodic"),
        "exact",
        run_westergaard,
    ),
    Case(
        "elastic_rough_dense",
        "Elastic rough contact against a dense direct solve",
        "Self-affine surface on an elastic half-space, small grids: the BEM against an explicit influence "
        "matrix solved by Murty's principal pivoting.",
        ("dense", "bem-periodic"),
        "dense",
        run_dense,
    ),
]
