"""Axisymmetric FEM (fem_reference.axisymmetric / indentation) against exact solutions."""

import numpy as np
import pytest

from bem import InputError, Material
from fem_reference import indentation
from fem_reference.axisymmetric import AxisymmetricStepper, fixed_dofs_axisymmetric
from fem_reference.indentation import SHIFT_PHASE, time_grid
from fem_reference.indentation_mesh import creep_axis
from fem_reference.kinematics import quadrature_operators
from fem_reference.mesh import half_space_mesh
from fem_reference.surface import top_surface
from validation.references import lee_radok
from validation.references.hertz import point_contact

R, P = 0.01, 1.0


def lame_error(n, nu, ri=1.0, ro=2.0, E=1e6, p_in=1e3):
    """Max nodal error of u_r for a thick cylinder under internal pressure, u_z = 0 on the ends."""
    from skfem import FacetBasis, LinearForm, MeshQuad, asm

    mesh = MeshQuad.init_tensor(np.linspace(ri, ro, n + 1), np.linspace(-0.5, 0.0, 3)).with_defaults()
    ops = quadrature_operators(mesh, "axi")
    b = ops.basis
    st = AxisymmetricStepper(ops, Material.elastic(E, nu=nu), b.get_dofs({"top", "bottom"}).all("u^2"))
    fb = FacetBasis(mesh, b.elem, facets=mesh.boundaries["left"], intorder=4)
    f = asm(LinearForm(lambda v, w: p_in * v[0] * 2 * np.pi * w.x[0]), fb)
    u = st.unit_response(f)
    dofs = b.nodal_dofs[0]
    r = b.doflocs[0, dofs]
    exact = (1 + nu) * p_in * ri**2 / (E * (ro**2 - ri**2)) * ((1 - 2 * nu) * r + ro**2 / r)
    return np.max(np.abs(u[dofs] - exact)) / np.max(np.abs(exact))


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_lame_thick_cylinder(nu):
    # Lame's exact u_r = A r + B / r. Biquadratic elements superconverge at the nodes
    # (measured rate 3.9, error 1.6e-6 at n = 8 for both nu); require a fitted rate >= 3.5
    # and 5e-6 at n = 8. nu = 0.5 exercises the mixed (incompressible) form.
    ns = np.array([2, 4, 8])
    errs = np.array([lame_error(int(n), nu) for n in ns])
    rate = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert rate >= 3.5
    assert errs[-1] <= 5e-6


def test_confined_creep_time_update():
    # A laterally confined column under a constant top pressure q creeps as
    # eps_zz(t) = q (1 + nu)(1 - 2 nu) / (1 - nu) J(t) (constant nu). The spatial solution
    # is exact (linear displacement), so only the time update's error remains: second
    # order in the step, measured 6e-4 at 20 steps per decade; tolerance 1e-3.
    nu = 0.3
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=nu)
    hs = half_space_mesh((0, 1), 0.5, x_range=(0, 2), depth=2, core_depth=1, ratio=1.3)
    ops = quadrature_operators(hs.mesh, "axi")
    st = AxisymmetricStepper(ops, m, fixed_dofs_axisymmetric(ops.basis))
    top = top_surface(ops.basis, axisymmetric=True)
    F = np.zeros(ops.basis.N)
    F[top.ydofs] = -1e3 * top.weights
    U = st.unit_response(F)
    out = [0.3, 1.0, 3.0, 10.0]
    t_prev, errs = 0.0, []
    for t in time_grid(np.array(out), m.creep_times, 20):
        e, u_hist = st.prepare(t - t_prev)
        u = U / e + u_hist
        st.commit(u)
        t_prev = t
        if t in out:
            exact = 1e3 * 2.0 * (1 + nu) * (1 - 2 * nu) / (1 - nu) * m.creep_compliance(t)
            errs.append(abs(-u[top.ydofs].mean() / exact - 1))
    assert max(errs) <= 1e-3


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_hertz_limits(nu):
    # t = 0+ is Hertz with E_inf and t -> inf Hertz with E0 (a step of 1e4 creep times
    # leaves alpha = eps to round-off, whatever the path). 8 elements per local contact radius:
    # contact radius within a quarter of the local element a/8 (read from the gaps of the first
    # free nodes; the glassy edge falls on a node, the relaxed one measured 0.12 element off), peak
    # pressure 1 % (measured 0.3 %), approach 0.5 % (block of 1000 a0: truncation ~ 0.1 %).
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=nu)
    r = indentation(m, radius=R, load=P, times=[0.0, 1e4], resolution=8, steps_per_decade=1)
    for i, E in enumerate((m.E_inf, m.E0)):
        hz = point_contact(E, nu, R, P)
        assert abs(r.contact_radius[i] - hz.a) <= hz.a / 8 / 4
        assert r.peak_pressure[i] == pytest.approx(hz.p0, rel=0.01)
        assert r.approach[i] == pytest.approx(hz.delta, rel=0.005)


def test_lee_radok_creep():
    # Step load on a standard linear solid: a(t)^3 = (3R/4) P (1 - nu^2) J(t) and
    # delta(t) = a(t)^2 / R (Lee & Radok 1960). The approach is a global measure: measured
    # within 0.11 % at 40 steps/decade, 0.2 % at the default 20; tolerance 0.5 %. The
    # contact radius read from the gaps carries the node quantisation of a moving edge (measured
    # up to 0.14 of the local element a/6); tolerance a quarter of it.
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=0.5)
    times = np.array([0.0, 0.3, 1.0, 3.0, 10.0, 100.0])
    r = indentation(m, radius=R, load=P, times=times, resolution=6)
    a_lr = (0.75 * R * P * (1 - m.nu**2) * m.creep_compliance(times)) ** (1 / 3)
    np.testing.assert_allclose(r.approach, a_lr**2 / R, rtol=0.005)
    assert np.all(np.abs(r.contact_radius - a_lr) <= a_lr / 6 / 4)
    assert np.all(np.diff(r.contact_radius) >= -r.element_size / 8)  # creep: contact grows


def test_requested_times_within_round_off_of_the_log_grid():
    # requested times computed as multiples of the creep time land within an ulp of the log-spaced
    # step times (0.1 * 0.01 != 1e-3): each must still be one step and one output, in order
    m = Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01, nu=0.5)
    times = np.array([0.0, 0.1, 0.3, 1.0, 3.0, 10.0]) * float(np.max(m.creep_times))
    g = time_grid(times, m.creep_times, 10)
    assert np.all(np.isin(times, g)) and np.min(np.diff(g) / g[1:]) > 1e-6
    r = indentation(m, radius=R, load=P, times=times, resolution=2, steps_per_decade=10)
    a_lr = (0.75 * R * P * (1 - m.nu**2) * m.creep_compliance(times)) ** (1 / 3)
    # measured within 0.9 % of Lee-Radok at resolution 2 (E_inf/E0 = 10); outputs shifted by one
    # time are 20-50 % off
    np.testing.assert_allclose(r.approach, a_lr**2 / R, rtol=0.02)


@pytest.mark.parametrize(
    "kw, name",
    [
        (dict(radius=0.0), "radius"),
        (dict(load=-1.0), "load"),
        (dict(times=[1.0, 0.5]), "times"),
        (dict(times=[-1.0]), "times"),
        (dict(resolution=0), "resolution"),
        (dict(grading=3.0), "grading"),
        (dict(steps_per_decade=0), "steps_per_decade"),
    ],
)
def test_bad_input(kw, name):
    args = dict(radius=R, load=P, times=[0.0]) | kw
    with pytest.raises(InputError, match=name):
        indentation(Material.elastic(1e6, nu=0.3), **args)


@pytest.mark.parametrize("ratio", [10.0, 3000.0])
def test_creep_mesh_is_as_fine_relative_to_every_contact_radius_it_sweeps(ratio):
    # h(r) = max(r, a_inf) / n from the axis to band * a0, then growing by the grading: the element
    # under any edge between a_inf and a0 is 1/n of the radius (within one growth step), and the
    # count grows with log(ratio), not with its cube root as a uniform core of a_inf / n would
    n, band, a_inf = 16, 1.5, 1.0
    a0 = a_inf * ratio ** (1 / 3)
    x = creep_axis(a_inf, band * a0, n, 1000 * a0, 1.3)
    h, mid = np.diff(x), 0.5 * (x[1:] + x[:-1])
    sweep = mid <= band * a0
    np.testing.assert_allclose(h[sweep] * n / np.maximum(mid[sweep], a_inf), 1.0, atol=1.0 / n)
    # the outer steps are scaled by one factor to land on the block's side: within sqrt(grading)
    assert np.max(h[1:] / h[:-1]) <= 1.3**1.5 and x[-1] == pytest.approx(1000 * a0)
    assert np.count_nonzero(sweep) <= n * (1 + np.log(band * a0 / a_inf)) + 2


@pytest.mark.parametrize("n", [2, 12])
def test_the_shifted_mesh_has_its_nodes_between_the_first_ones(n):
    # the contact radius is read from the surface nodes, vertices and the 9-node elements' middle
    # nodes alike: the estimate's twin must read the edge at other nodes, so over the sweep each of
    # its nodes lies near the middle between two of the first mesh's (within the growth of one node
    # spacing), never on one of them
    a_inf, a0 = 1.0, 10.0 ** (1 / 3)

    def nodes(phase):
        x = creep_axis(a_inf, 1.5 * a0, n, 1000 * a0, 1.3, phase)
        return np.sort(np.concatenate([x, 0.5 * (x[1:] + x[:-1])]))

    first, twin = nodes(0.0), nodes(SHIFT_PHASE)
    inner = twin[(twin > 1.05 * a_inf) & (twin < a0)]
    k = np.searchsorted(first, inner)
    share = (inner - first[k - 1]) / (first[k] - first[k - 1])  # where between its two neighbours
    assert np.all(np.abs(share - 0.5) <= 0.5 / n + 0.05), share


def test_a_coarse_mesh_warns_and_its_estimate_covers_its_error():
    # Two elements per contact radius and 4 steps per decade on a standard solid, E_inf/E0 = 10:
    # contact radius up to 3.0 % and approach up to 2.4 % off Lee & Radok. The estimate (twice the
    # change on the mesh shifted by half a node spacing at half the steps per decade, or the elastic
    # limits' error) says 12.7 % and 6.2 % at worst, at least the error at every time, and warns; a
    # result whose estimate said less than its worst error would let a wrong reference pass.
    m = Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=1.0, nu=0.5)
    times = np.array([0.0, 0.3, 1.0, 3.0, 10.0, 100.0])
    r = indentation(m, radius=R, load=P, times=times, resolution=2, steps_per_decade=4)
    err_a = np.abs(r.contact_radius / lee_radok.contact_radius(m, R, P, times) - 1)
    err_d = np.abs(r.approach / lee_radok.approach(m, R, P, times) - 1)
    assert np.max(err_a) > 0.02 and np.max(err_d) > 0.02  # the mesh is coarse indeed
    assert np.max(r.error_estimate["contact_radius"]) >= np.max(err_a)
    assert np.max(r.error_estimate["approach"]) >= np.max(err_d)
    assert any("contact radius" in w for w in r.warnings) and any("approach" in w for w in r.warnings)
    # the elastic limits are exact checks the estimate never falls below
    assert np.all(r.error_estimate["approach"] >= abs(r.elastic_limits["fine_glassy"]["approach"]))


@pytest.mark.slow
def test_the_estimate_covers_the_contact_radius_at_every_time():
    # A standard solid at E_inf/E0 = 1000 (tau = 0.1 s, R = 5 mm, P = 1 N) at the default mesh, 12
    # times from 1e-8 s to 1e3 s: mid-creep the edge sits at a node of the first mesh and reads
    # 0.89 % and 0.82 % off Lee & Radok. The shifted twin reads it between two nodes: estimates
    # 1.37 % and 1.90 %, at least 1.5 times the error at every time. A twin whose nodes sat on the
    # first mesh's middle nodes read the edge alike and said 0.54 % for the 0.89 % (69 s).
    m = Material.standard_linear_solid(E0=1e6, E_inf=1e9, relaxation_time=0.1, nu=0.5)
    times = np.logspace(-8, 3, 12)
    r = indentation(m, radius=0.005, load=1.0, times=times)
    err_a = np.abs(r.contact_radius / lee_radok.contact_radius(m, 0.005, 1.0, times) - 1)
    assert np.max(err_a) > 0.008  # the case has teeth: an edge read at a node, near 1 % off
    assert np.all(r.error_estimate["contact_radius"] >= err_a), r.error_estimate["contact_radius"] / err_a


@pytest.mark.slow
def test_lee_radok_on_a_held_out_rubber_at_the_default_mesh():
    # A 5-term rubber no other test uses (E_inf/E0 = 50, tau = 1e-4..1e-1 s, E0 = 2 MPa), called
    # with no mesh argument (88 s, 0.6 GiB). Measured against Lee & Radok at 10 times from 0 to
    # 1000 creep times: contact radius within 1.45 % (mid-creep, where the moving edge's layer is
    # thinner than an element; <= 0.34 % elsewhere), approach within 0.30 %. Tolerances 2 % and
    # 0.5 % (margins 1.4x and 1.7x). Where the contact radius is off by more than 1 % the estimate
    # must say so (measured 2.64 % against the 1.45 % error).
    m = Material.from_prony(E0=2e6, moduli=np.full(5, 2e6 * 49 / 5), times=np.geomspace(1e-4, 1e-1, 5))
    times = np.concatenate([[0.0], np.geomspace(1e-5, 1e3 * float(np.max(m.creep_times)), 9)])
    r = indentation(m, radius=R, load=P, times=times)
    assert r.success
    err_a = np.abs(r.contact_radius / lee_radok.contact_radius(m, R, P, times) - 1)
    err_d = np.abs(r.approach / lee_radok.approach(m, R, P, times) - 1)
    assert np.max(err_a) <= 0.02 and np.max(err_d) <= 0.005
    assert np.all(r.error_estimate["contact_radius"][err_a > 0.01] >= err_a[err_a > 0.01])
    assert np.max(r.error_estimate["approach"]) >= np.max(err_d)
