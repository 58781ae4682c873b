"""Settings and tolerances of the rubber case (:mod:`.rubber`), each tolerance with the error it was
measured at and its margin. Every solver runs at the case's load, 1500 N/m. Speeds: the friction maximum
of the isolated BEM over a sweep of 4 points per decade (quick rubber: 1e-2 m/s; full rubber: 1.78e-3
m/s), and a decade below. The reference is the isolated BEM on twice the cells; sampled edges on the
two nested grids differ by whole half-cells (0, 0.5 or 1 coarse cell), so the edge tolerance is 0.75 cell."""

# Quick (4 terms, E_inf/E0 = 30; BEM 10 cells per a_inf, reference 20), measured at V = 1e-3 / 1e-2 m/s for
# the three BEM solvers: binned L2 0.35-1.28 %, friction <= 1.09e-3 (periodic at the peak; isolated <= 6.3e-4),
# edges 0 or 0.5 cell, peak 1.4e-4 - 1.0e-3 at the friction peak (0.7-14 % at 1e-3 m/s, not judged).
_WHY_BEM_Q = dict(
    l2="measured 0.35-1.28 % (10 against 20 cells); margin 1.6x",
    friction="measured <= 1.09e-3 (periodic at the peak), <= 6.3e-4 (isolated); margin 1.4x",
    edge="sampled edges on nested grids: measured 0 or 0.5 cell; 0.75 cell",
    peak="at the friction peak: measured 1.4e-4 (isolated) to 1.0e-3 (periodic); margin 7x",
    peak_unjudged="not judged: a decade below the peak the solvers' peaks differ by 0.7-14 % (leading-edge layers "
    "V tau_k of 1e-7..1e-4 m, at or below the cell: a pointwise value at an unresolved jump)",
)
# FEM on the quick rubber (graded mesh, resolution 2) at 1e-3 m/s against the 20-cell reference: binned L2 3.45 %,
# friction 9.5e-3 in the dissipation form (the element memory's upwind jumps between elements dissipate at this
# resolution) and 6.7e-5 in the moment form, edges 0.23 / 0.02 reference cell, energy balance 0.96 %, peak 0.84 %
# (not judged: the reference's cells do not resolve the layers V tau_k from 1e-7 m, and the BEM solvers' peaks
# differ by 0.7-14 %).
_WHY_FEM_Q = dict(
    l2="measured 4.38 % (graded, resolution 2, against 20 cells per a_inf); margin 2.3x",
    friction="dissipation form, measured 9.5e-3 (element memory, resolution 2); margin 2.1x",
    friction_moment="moment form, measured 6.7e-5 (resolution 2); bound 3e-3, twice the 10-cell BEMs' friction "
    "difference from this 20-cell reference (1.5e-3): the reference's own error is of that size",
    edge="measured 0.21 / 0.39 reference cell; margin 3.8x",
    peak="",
    peak_unjudged="not judged: the reference's cells (4.9e-5 m) do not resolve the leading-edge layers V tau_k "
    "(from 1e-7 m); the BEM solvers' own peaks differ by 2.7-14 % here",
    balance="field dissipation against mu P V: measured 2.2 %; margin 1.8x",
)
QUICK = dict(
    material=dict(ratio=30, terms=4, tmin=1e-4),
    speeds=[1e-3, 1e-2],
    cells=10,
    ref_cells=20,
    fem=dict(material=None, speeds=[1e-3], resolution=2, note=""),
    tol=dict(
        bem=dict(l2=0.02, friction=1.5e-3, edge=0.75, peak=7e-3, peak_speeds=[1e-2]),
        fem=dict(l2=0.1, friction=0.02, friction_moment=3e-3, edge=1.5, peak=None, peak_speeds=[], balance=0.04),
    ),
    why=dict(bem=_WHY_BEM_Q, fem=_WHY_FEM_Q),
)
# FEM on the case's rubber (graded mesh, resolution 6: elements per contact half-width at the edges and the
# leading-edge layers), measured against the reference (isolated BEM, 40 cells per a_inf) at 1.78e-4 / 1.78e-3 m/s:
# friction 4.0e-3 / 5.9e-3, edges 1.5-4.6 reference cells (< 0.5 % of the contact width), energy balance 0.97 % /
# 0.79 %, binned L2 16.6 % / 19.9 % (all of it in the leading-edge layer, where the reference's cells do not resolve
# the layer's shape; the interior agrees within 1 %), peak 0.06 % at the friction peak (and -1.04 % against the
# isolated BEM on 2^14 points); a decade below, the reference's own peak is 19 % off the converged BEM's.
_WHY_FEM_F = dict(
    l2={
        1.78e-4: "measured 16.6 % (res 6), all in the leading-edge layer the reference does not resolve; margin 1.8x",
        1.78e-3: "measured 19.9 % (res 6), all in the leading-edge layer the reference does not resolve; margin 1.8x",
    },
    friction={
        1.78e-4: "dissipation form, measured 6.4e-3 (res 6); margin 1.25x",
        1.78e-3: "dissipation form, measured 2.7e-3 (res 6); margin 4.5x",
    },
    friction_moment={
        1.78e-4: "moment form, measured 4.5e-4 (res 6); margin 4.4x",
        1.78e-3: "moment form, measured 1.07e-3 (res 6); margin 2.8x",
    },
    edge={
        1.78e-4: "measured 4.2 / 1.5 reference cells (< 0.4 % of the contact width); margin 1.9x",
        1.78e-3: "measured 4.6 / 4.0 reference cells (< 1 % of the contact width); margin 2x",
    },
    peak="measured 0.06 % against the reference, -1.04 % against the isolated BEM on 2^14 points; 2x the larger",
    peak_unjudged="not judged: a decade below the peak the reference's peak is 19 % off the converged BEM's (layers "
    "V tau_k down to 1.8e-9 m against its cells of 7.7e-6 m)",
    balance={
        1.78e-4: "field dissipation against mu P V: measured 0.97 % (res 6); margin 2x",
        1.78e-3: "field dissipation against mu P V: measured 0.79 % (res 6); margin 2x",
    },
)
# BEM (8 terms, E_inf/E0 = 300; 20 cells per a_inf, reference 40), measured at 1500 N/m at 1.78e-4 / 1.78e-3 m/s:
# binned L2 0.39-0.99 % (isolated), 2.0-2.6 % (periodic), friction <= 3.3e-4 (isolated), 5.8e-4 (periodic), edges 0
# or 0.5 cell, peak 1.5e-4 (isolated) / 1.75 % (periodic) at the friction peak. FEM at 1500 N/m: friction 2.25e-3 /
# 6.6e-3, edges 2.45-5.1 reference cells, L2 14.2 % / 22.3 %, balance 1.14 % / 0.82 %, peak 1.03 % at the friction
# peak: within the tolerances below, set at 1000 N/m. Measured at 1000 N/m: binned L2
# 1.55 % / 1.80 % (isolated), 2.4 % (periodic, 1.78e-3), friction <= 1.5e-4 (isolated), 8.3e-4 (periodic), edges
# 0 or 0.5 cell, peak 8.8e-5 (isolated) / 9.4e-4 (periodic) at the friction peak, 8.3 % a decade below.
_WHY_BEM_F = dict(
    l2="measured 1.55-1.80 % (isolated), 2.4 % (periodic) at 20 against 40 cells; margin 1.5x",
    friction="measured <= 1.5e-4 (isolated), 8.3e-4 (periodic); margin 2.4x",
    edge="sampled edges on nested grids: measured 0 or 0.5 cell; 0.75 cell",
    peak={
        "bem-periodic": "at the friction peak, 1500 N/m: measured 1.75 % (its leading-edge layer V tau_min = 1.8e-8 m is "
        "far below its cell; 9.4e-4 at 1000 N/m); margin 2x",
        "bem-isolated-uniform": "at the friction peak, 1500 N/m: measured 1.5e-4; margin 13x",
        "bem-isolated-adaptive": "at the friction peak, 1500 N/m: measured 1.5e-4; margin 13x",
    },
    peak_unjudged="not judged: a decade below the peak the peaks differ by 8.3 % (leading-edge layers V tau_k of "
    "2e-9..2e-5 m, at or below the cell of 1.5e-5 m)",
)
FULL = dict(
    material=dict(ratio=300, terms=8, tmin=1e-5),
    speeds=[1.78e-4, 1.78e-3],
    cells=20,
    ref_cells=40,
    fem=dict(material=None, speeds=[1.78e-4, 1.78e-3], resolution=6, note=""),
    tol=dict(
        bem=dict(
            l2=0.035,
            friction=2e-3,
            edge=0.75,
            peak={"bem-periodic": 0.035, "bem-isolated-uniform": 2e-3, "bem-isolated-adaptive": 2e-3},
            peak_speeds=[1.78e-3],
        ),
        fem=dict(
            l2={1.78e-4: 0.3, 1.78e-3: 0.35},
            friction={1.78e-4: 8e-3, 1.78e-3: 0.012},
            friction_moment={1.78e-4: 2e-3, 1.78e-3: 3e-3},
            edge={1.78e-4: 8.0, 1.78e-3: 9.0},
            peak=0.02,
            peak_speeds=[1.78e-3],
            balance={1.78e-4: 0.02, 1.78e-3: 0.016},
        ),
    ),
    why=dict(bem=_WHY_BEM_F, fem=_WHY_FEM_F),
)
