"""Half-space meshes of squares graded in both directions (fem_reference.quadtree)."""

import numpy as np
import pytest

from fem_reference.kinematics import quadrature_operators
from fem_reference.quadtree import quadtree_half_space

# a contact 0.2 mm wide with a fine zone at its leading edge, in a block 10^10 times its elements
SEGMENTS = [(-1e-4, 1e-4, 2e-5), (0.9e-4, 1e-4, 1e-7)]


def squares(q):
    pv = q.mesh.p[:, q.mesh.t]
    return pv.min(axis=1), pv.max(axis=1)


def shared_faces(lo, hi):
    """Pairs of elements (e, f) whose faces overlap along a vertical line (f's left on e's right)."""
    pairs = []
    for x in np.intersect1d(hi[0], lo[0]):
        es, fs = np.flatnonzero(hi[0] == x), np.flatnonzero(lo[0] == x)
        over = (lo[1, es][:, None] < hi[1, fs][None, :]) & (hi[1, es][:, None] > lo[1, fs][None, :])
        i, j = np.nonzero(over)
        pairs.append(np.stack([es[i], fs[j]]))
    return np.concatenate(pairs, axis=1)


def test_squares_balanced_and_no_larger_than_requested():
    q = quadtree_half_space(SEGMENTS, length=1e3, ratio=1.25)
    lo, hi = squares(q)
    side = hi - lo
    np.testing.assert_allclose(side[0], side[1], rtol=1e-12)  # squares: aspect ratio 1
    assert lo[0].min() == -1e3 and hi[0].max() == 1e3 and lo[1].min() == -1e3 and hi[1].max() == 0.0
    area = np.sum(side[0] * side[1])
    assert area == pytest.approx(2e6, rel=1e-12)  # they tile the block
    for e, f in shared_faces(lo, hi).T:  # 2:1 across every vertical face (and so every hanging node)
        assert 0.5 <= side[0, e] / side[0, f] <= 2.0
    # every square is within the size requested at its point nearest to the segments, and the
    # smallest within a factor of two of the smallest requested
    requested = np.full(side[0].shape, np.inf)
    for s_lo, s_hi, size in SEGMENTS:
        dx = np.maximum(0.0, np.maximum(s_lo - hi[0], lo[0] - s_hi))
        requested = np.minimum(requested, size + 0.25 * np.hypot(dx, -hi[1]))
    assert np.all(side[0] <= requested * (1 + 1e-9))
    assert 0.5e-7 < q.element_size <= 1e-7 and q.element_size == side[0].min()


def test_elements_grow_with_the_log_of_the_block():
    # each doubling of the block adds a ring of squares: the count grows with log(L), not L
    # (measured 3134, 4106, 5108: about a hundred squares a doubling)
    counts = [quadtree_half_space(SEGMENTS, length=L, ratio=1.25).n_elements for L in (1e0, 1e3, 1e6)]
    growth = np.diff(counts)
    assert growth[0] > 0 and abs(growth[1] - growth[0]) < 0.1 * growth[0], counts
    assert counts[-1] < 6000


def test_vertices_near_the_contact_keep_their_precision():
    # in a block of 48 km the squares at the contact are 6e-9 m: their vertices are exact multiples
    q = quadtree_half_space([(-3e-3, 3e-3, 5e-4), (3e-3, 3e-3, 5e-9)], length=4.8e4, ratio=1.25)
    lo, hi = squares(q)
    small = (hi[0] - lo[0]) == q.element_size
    np.testing.assert_allclose((hi - lo)[:, small], q.element_size, rtol=1e-12, atol=0)


def test_hanging_nodes_carry_the_large_elements_quadratic():
    from skfem import Basis, ElementQuad2, ElementVector

    q = quadtree_half_space(SEGMENTS, length=1e-2, ratio=1.25)
    assert len(q.hanging) > 0
    ops = quadrature_operators(q.mesh, "plane", hanging=q.hanging)
    basis = Basis(q.mesh, ElementVector(ElementQuad2()), intorder=4)
    x, y = basis.doflocs
    quadratic = 1.0 + 3.0 * x - 2.0 * y + 50.0 * (x**2 - x * y + 2.0 * y**2)
    np.testing.assert_allclose(ops.complete(quadratic), quadratic, rtol=0, atol=1e-14)
    cubic = x**3 / 1e-6  # not in the space: the constraint misses it (by 7e-4), so the check can fail
    assert np.max(np.abs(ops.complete(cubic) - cubic)) > 1e-5 * np.max(np.abs(cubic))
    # a uniform strain is the same at every quadrature point, hanging nodes or not
    dofs_x = np.concatenate([basis.nodal_dofs[0], basis.facet_dofs[0], basis.interior_dofs[0]])
    dofs_y = np.concatenate([basis.nodal_dofs[1], basis.facet_dofs[1], basis.interior_dofs[1]])
    u = np.zeros(basis.N)
    u[dofs_x] = 1e-3 * x[dofs_x] + 2e-3 * y[dofs_x]
    u[dofs_y] = -4e-3 * y[dofs_y]
    eps = (ops.B @ u).reshape(-1, 3)
    # round-off only (measured 1.1e-15 on strains of 1e-3 over squares of 1e-7 m at x ~ 1e-4 m)
    np.testing.assert_allclose(eps, np.broadcast_to([1e-3, -4e-3, 2e-3], eps.shape), rtol=0, atol=1e-13)


R, P = 0.01, 100.0


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_rolling_hertz_on_squares(nu):
    # an elastic cylinder on the quadtree (resolution 6): measured p0 +0.20 / +0.22 % and both edges
    # -0.08 / -0.06 % for nu = 0.3 / 0.5; the mesh is symmetric about the contact, so the moment is
    # round-off (1e-15). Tolerances: 0.5 % (p0) and 0.3 % (edges), margins of two to four
    from bem import Material
    from fem_reference import rolling_cylinder
    from validation.references.hertz import line_contact

    r = rolling_cylinder(Material.elastic(1e7, nu=nu), radius=R, load=P, speed=1.0, mesh="quadtree")
    hz = line_contact(1e7, nu, R, P)
    assert r.success and r.warnings == ()
    assert r.peak_pressure == pytest.approx(hz.p0, rel=5e-3)
    assert r.leading_edge == pytest.approx(hz.a, rel=3e-3)
    assert r.trailing_edge == pytest.approx(-hz.a, rel=3e-3)
    assert abs(r.friction) < 1e-12
    assert r.grading == 1.25 and r.n_elements < 1500


def hunter_case(ratio, ell):
    from bem import Material
    from fem_reference import rolling_cylinder
    from validation.references import hunter
    from validation.references.hertz import line_contact

    m = Material.standard_linear_solid(E0=1e6, E_inf=ratio * 1e6, relaxation_time=0.01, nu=0.5)
    V = ell * line_contact(m.E0, m.nu, R, P).a / m.creep_times[0]
    return rolling_cylinder(m, radius=R, load=P, speed=V, mesh="quadtree"), hunter.rolling_cylinder(
        m, radius=R, load=P, speed=V
    )


@pytest.mark.parametrize("ell", [0.3, 3.0])
def test_rolling_hunter_on_squares(ell):
    # Hunter's standard solid at E_inf/E0 = 3, V lambda = 0.3 and 3 relaxed half-widths: measured
    # moment -0.03 / -0.14 %, dissipation +0.03 / -0.09 %, peak +0.04 / -0.08 %, each within its
    # estimate (0.14-0.49 %); tolerance 0.5 % (the bar is 1 %)
    r, h = hunter_case(3.0, ell)
    assert r.success and r.peak_resolved and r.warnings == ()
    for value in (r.friction, r.friction_dissipation):
        assert value == pytest.approx(h.friction, rel=5e-3)
        assert abs(value / h.friction - 1) <= max(
            r.error_estimate["friction"], r.error_estimate["friction_dissipation"]
        )
    assert r.peak_pressure == pytest.approx(h.peak_pressure, rel=5e-3)
    assert r.solver_path[0]["solver"] in ("pardiso", "splu")


def test_coarsest_grading_has_its_twin():
    # grading 2, the largest a user may ask for: the error estimate's twin grows its squares twice as
    # fast (3), a mesh of its own, not an input; the estimate is there and the result meets Hunter
    # within the estimate (measured -0.91 % moment, +0.90 % dissipation, both estimates 1.8 %)
    from bem import Material
    from fem_reference import rolling_cylinder
    from validation.references import hunter

    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)
    r = rolling_cylinder(m, radius=R, load=P, speed=0.05, resolution=2, grading=2.0, mesh="quadtree")
    h = hunter.rolling_cylinder(m, radius=R, load=P, speed=0.05)
    assert r.success and set(r.error_estimate) >= {"friction", "friction_dissipation"}
    assert abs(r.friction / h.friction - 1) <= r.error_estimate["friction"]


@pytest.mark.heavy
def test_rolling_hunter_on_squares_at_ratio_1000():
    # E_inf/E0 = 1000, V lambda = 3 relaxed half-widths: the leading-edge layer V tau is 0.3 % of the
    # relaxed half-width and resolved. Measured moment -0.09 %, dissipation +0.84 % (its estimate
    # 3.6 %, which warns), peak -0.06 %; 1,650 squares. Tolerances 1 % (friction) and 0.5 % (peak)
    r, h = hunter_case(1000.0, 3.0)
    assert r.success and r.peak_resolved
    assert r.friction == pytest.approx(h.friction, rel=0.01)
    assert r.friction_dissipation == pytest.approx(h.friction, rel=0.01)
    assert abs(r.friction_dissipation / h.friction - 1) <= r.error_estimate["friction_dissipation"]
    assert r.peak_pressure == pytest.approx(h.peak_pressure, rel=5e-3)
    assert r.n_elements < 2500
