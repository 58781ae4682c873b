"""Every result states what it is worth: error estimates and warnings (bem.accuracy).

Reference for an estimate: the same surface content solved on the grid with twice the points per
axis (``error_estimate="refined"``). The cheap estimate is an expected magnitude; its targets
(docs/theory.md §13): within a factor 3 of the measured error, never below 1 % where the
measured error exceeds 5 %, and a warning whenever it exceeds 5 %.
"""

import json
import math

import numpy as np
import pytest

import bem
from bem.accuracy import Finding, gather
from bem.accuracy import indicators as ind
from bem.accuracy.findings import findings_of
from bem.accuracy.refined import refine_surface

SLS = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)


def rubber(ratio, terms, tmin, tmax, E0=1e6):
    """Equal moduli summing to ``(ratio - 1) E0``, relaxation times log-spaced in [tmin, tmax] (s)."""
    return bem.Material.from_prony(
        E0=E0, moduli=np.full(terms, E0 * (ratio - 1) / terms), times=np.geomspace(tmin, tmax, terms)
    )


# ---------------------------------------------------------------- the estimate's type and keyword


def test_estimate_is_a_mapping_of_three_quantities_with_reasons():
    s = bem.surfaces.sinusoid(64, 1e-3, amplitude=1e-6)
    r = bem.solve(s, bem.Material.elastic(1e7), speed=0.0, load=1.0)
    est = r.error_estimate
    assert list(est) == ["friction", "contact_fraction", "peak_pressure"] and len(est) == 3
    # elastic: friction is zero on every grid, so it has no relative error, and says why
    assert est["friction"] is None and "nothing dissipates" in est.reasons["friction"]
    assert est["contact_fraction"] > 0 and est["peak_pressure"] >= 0
    plain = json.loads(json.dumps(est.as_dict()))
    assert plain["method"] == "indicators" and plain["friction"] is None
    assert r.peak_pressure == pytest.approx(r.pressure.max())


def test_error_estimate_keyword_is_checked_and_none_skips_it():
    s = bem.surfaces.sinusoid(32, 1e-3, amplitude=1e-6)
    with pytest.raises(bem.InputError, match="error_estimate must be 'indicators'"):
        bem.solve(s, SLS, speed=1e-3, load=1.0, error_estimate="cheap")
    r = bem.solve(s, SLS, speed=1e-3, load=1.0, error_estimate=None)
    assert r.warnings == () and all(r.error_estimate[q] is None for q in r.error_estimate)
    assert r.error_estimate.reasons["friction"].startswith("not requested")


def test_unconverged_solve_says_so_and_has_no_estimate():
    s = bem.surfaces.self_affine(64, 0.01, hurst=0.8, scales=16, rms_height=2e-5, seed=2)
    r = bem.solve(s, SLS, speed=1e-3, load=0.3, maxiter=1, raise_on_failure=False)
    assert not r.success
    assert [w.kind for w in r.warnings] == ["not_converged"] and "did not converge" in r.warnings[0]
    assert r.error_estimate["friction"] is None and r.error_estimate.reasons["friction"] == "the solve did not converge"
    with pytest.raises(bem.ConvergenceError) as err:
        bem.solve(s, SLS, speed=1e-3, load=0.3, maxiter=1)
    assert err.value.result.warnings[0].kind == "not_converged"


# ---------------------------------------------------------------- indicators, exactly


def test_contact_perimeter_counts_faces_per_contact_cell():
    chi = np.zeros((8, 8), dtype=bool)
    chi[2:5, 3:5] = True  # 3 x 2 block: 10 faces, 6 cells
    assert ind.contact_perimeter(chi, periodic=True) == pytest.approx(10 / 6)
    strip = np.zeros(16, dtype=bool)
    strip[:4] = True  # touches the isolated domain's end: its boundary is no face
    assert ind.contact_perimeter(strip, periodic=False) == pytest.approx(1 / 4)
    assert ind.contact_perimeter(strip, periodic=True) == pytest.approx(2 / 4)


def test_points_per_wavelength_of_a_sinusoid_and_a_band_limited_surface():
    assert ind.points_per_wavelength(bem.surfaces.sinusoid(128, 1.0, amplitude=1.0, wavelength=0.125).heights) == 16
    s = bem.surfaces.self_affine(128, 0.01, hurst=0.8, scales=32, rms_height=1e-6, seed=4)
    # the 95 % curvature quantile sits within a few per cent of the cut-off q_1 (4 points)
    assert 4.0 <= ind.points_per_wavelength(s.heights) < 4.3


def test_peak_sharpness_and_its_distance_to_the_edge():
    p = np.zeros(16)
    p[4:12] = np.sin(np.linspace(0.2, np.pi - 0.2, 8))
    sharp, edge = ind.peak_sharpness(p, periodic=False)
    assert 0 < sharp < 0.1 and edge is None  # a smooth peak four cells inside
    p[11] = 3.0  # a one-cell spike on the edge
    sharp, edge = ind.peak_sharpness(p, periodic=False)
    assert sharp == pytest.approx((3.0 - 0.5 * p[10]) / 3.0) and edge == 1


def test_leading_edge_layers_spike_and_growth():
    p = np.zeros(32)
    p[8:24] = np.sqrt(np.sin(np.linspace(0.1, np.pi - 0.1, 16)))
    p[23] = 0.8  # the leading edge cell (the indenter moves to +x), near the peak as at a slow speed
    # no layers: nothing spikes, and the edge cell's pressure falls by 2**-0.5 on a finer grid
    assert ind.leading_edge_layers(p, bem.Material.elastic(1e7), 1e-3, 1e-4, periodic=False) == (0.0, 0.0)
    glassy = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, relaxation_time=10.0)
    spike, growth = ind.leading_edge_layers(p, glassy, 1e-3, 1e-4, periodic=False)  # V tau = 1 cm >> dx
    assert spike == 0.0 and growth == pytest.approx(2**-0.5, rel=5e-3)
    # a broad rubber slowly: layers far below the cell stiffen the edge, which grows on refinement
    broad = rubber(500, 14, 1e-8, 10.0)
    spike, growth = ind.leading_edge_layers(p, broad, 1e-7, 1e-5, periodic=False)
    assert spike > 1.0 and growth > 1.0
    assert ind.leading_edge_layers(p, broad, 1e-6, 1e-5, periodic=False)[1] < 1.0  # layers near the cell
    # the leading edge is the side the indenter moves to (+x): a lone spike on the trailing side is
    # not read as an edge layer
    trailing = p.copy()
    trailing[8] = 2.0
    lead_only, _ = ind.leading_edge_layers(trailing, broad, 1e-7, 1e-5, periodic=False)
    assert lead_only == pytest.approx(spike * p.max() / 2.0) and lead_only < 1.0


def test_subcell_layers_pick_the_terms_thinner_than_a_cell():
    m = rubber(1000, 12, 1e-7, 1.0)
    layers = ind.subcell_layers(m, speed=1e-5, spacing=1e-6)
    expected = sorted(t for t in m.relaxation_times if 1e-5 * t < 1e-6)  # V tau < dx: tau < 0.1 s
    assert [t for t, _, _ in layers] == pytest.approx(expected) and len(expected) == 10
    assert [thick for _, thick, _ in layers] == pytest.approx([1e-5 * t / 1e-6 for t in expected])
    # a term carrying less than 1 % of the modulus at the cell's frequency is no layer that matters
    small = bem.Material.from_prony(E0=1e6, moduli=[1e3, 1e8], times=[1e-6, 1.0])
    assert [t for t, _, _ in ind.subcell_layers(small, speed=1e-5, spacing=1e-6)] == []
    assert ind.subcell_layers(SLS, speed=1.0, spacing=1e-6) == []  # V tau = 3.3 mm >> dx


def test_dissipation_moment_is_none_without_dissipation_and_grows_as_the_grid_coarsens():
    s = bem.surfaces.sinusoid(64, 1e-3, amplitude=1e-6)
    r = bem.solve(s, bem.Material.elastic(1e7), speed=0.0, load=1.0)
    assert ind.dissipation_moment(r.pressure, bem.Material.elastic(1e7), 0.0, 1e-3, periodic=True) is None
    moments = []
    for n in (32, 64, 128):
        c = bem.surfaces.cylinder(radius=0.01, n=n, length=0.006)
        r = bem.solve(c, SLS, speed=0.05, load=1000.0, periodic=False)
        moments.append(r.error_estimate.indicators["dissipation_moment"])
    assert moments[0] > moments[1] > moments[2] > 0


# ---------------------------------------------------------------- the refined estimate


def test_refined_surface_keeps_the_content():
    s = bem.surfaces.self_affine(32, 0.01, hurst=0.8, scales=16, rms_height=1e-6, seed=5)
    f = refine_surface(s, periodic=True)
    assert f.shape == (64, 64) and np.allclose(f.heights[::2, ::2], s.heights, rtol=0, atol=1e-18)
    spectrum = np.abs(np.fft.fft2(f.heights))
    k = np.abs(np.fft.fftfreq(64, 1 / 64))
    assert spectrum[k > 16, :].max() < 1e-12 * spectrum.max()  # no new roughness above the coarse Nyquist
    sphere = bem.surfaces.sphere(radius=0.01, n=16, length=0.004)
    fine = refine_surface(sphere, periodic=False)
    assert np.allclose(fine.heights, bem.surfaces.sphere(radius=0.01, n=32, length=0.004).heights, atol=1e-15)


def _within(est, ref, factor=3.0, floor=1e-3):
    """Quantities whose measured error exceeds ``floor``: the estimate is within ``factor`` of it."""
    return {q: ref[q] / factor <= est[q] <= ref[q] * factor for q in est if ref[q] is not None and ref[q] > floor}


def test_estimate_against_the_twice_finer_solve_periodic_rough():
    """A 2-D rough cell (96², 12 scales: 8 points per wavelength, H = 0.7) on a 4-term rubber at
    10 % contact (a surface, seed and material none of the fitted cases had). Measured: friction
    1.1e-2 against an estimate of 1.1e-2, contact 4.8e-2 / 5.0e-2. The peak pressure sits two cells
    from a spot's leading edge, where layers V tau_k of 3e-8..3e-5 m (cells of 1e-4 m) put the edge
    cell's model spike at 1.09 times the peak: it is reported unresolved, though it moved only 0.9 %
    (and 0.2 % on the next doubling), an early alarm of the rule (docs/theory.md §13.4)."""
    m = rubber(30, 4, 1e-4, 1e-1)
    s = bem.surfaces.self_affine(96, 0.01, hurst=0.7, scales=12, rms_slope=0.2, seed=21)
    r = bem.solve(s, m, speed=3e-4, load=2.0)
    ref = bem.solve(s, m, speed=3e-4, load=2.0, error_estimate="refined").error_estimate
    assert ref.method == "refined" and ref.indicators["refined_points"] == 192
    est = r.error_estimate
    assert _within({q: est[q] for q in ("friction", "contact_fraction")}, ref) == {
        "friction": True,
        "contact_fraction": True,
    }
    assert est["peak_pressure"] is None and est.reasons["peak_pressure"].startswith("unresolved")


def test_estimate_against_the_twice_finer_solve_cylinder_on_a_rubber():
    """Rolling cylinder on a 12-term rubber (E_inf/E0 = 1000, tau 1e-7..1 s) near its friction peak.
    Measured at 512 cells: friction 2.2e-4 against an estimate of 1.1e-4, contact 0 (the width is
    the same number of cells) against 8e-4, peak 2.4e-3 against 2.3e-3."""
    m = rubber(1000, 12, 1e-7, 1.0)
    c = bem.surfaces.cylinder(radius=0.02, n=512, length=0.04 * 0.55)
    r = bem.solve(c, m, speed=1e-4, load=1500.0, periodic=False)
    ref = bem.solve(c, m, speed=1e-4, load=1500.0, periodic=False, error_estimate="refined").error_estimate
    assert r.error_estimate["friction"] < 1e-3 and ref["friction"] < 1e-3
    assert all(_within(r.error_estimate, ref, floor=1e-4).values()), (r.error_estimate, ref)
    assert r.warnings == ()


def test_estimate_against_the_twice_finer_solve_sphere():
    s = bem.surfaces.sphere(radius=0.01, n=40, length=0.004)
    r = bem.solve(s, SLS, speed=2e-3, load=1.0, periodic=False)
    ref = bem.solve(s, SLS, speed=2e-3, load=1.0, periodic=False, error_estimate="refined").error_estimate
    assert all(_within(r.error_estimate, ref, floor=1e-3).values()), (r.error_estimate, ref)


# ---------------------------------------------------------------- findings and their gathering


def test_a_warning_whenever_an_estimate_exceeds_five_per_cent():
    s = bem.surfaces.self_affine(32, 0.01, hurst=0.8, scales=8, rms_height=2e-5, seed=3)
    for speed in (1e-4, 1e-2, 1.0):
        r = bem.solve(s, SLS, speed=speed, load=0.3)
        kinds = {w.kind for w in r.warnings}
        for q, e in r.error_estimate.items():
            assert (e is not None and e > 0.05) == (q in kinds), (q, e, kinds)


def test_friction_form_finding_threshold():
    from types import SimpleNamespace

    def result(mu, mu6):
        return SimpleNamespace(success=True, friction=mu, friction_eq6=mu6, contact_fraction=0.1, pressure=np.ones(4))

    est = {"friction": 0.01, "contact_fraction": 0.01, "peak_pressure": 0.01}

    def kinds(mu, mu6):
        gap = ind.form_gap(mu, mu6)
        return [f.kind for f in findings_of(result(mu, mu6), est, {"form_gap": gap}, 64)]

    assert kinds(0.1, 0.0955) == []  # 4.5 %
    assert kinds(0.1, 0.107) == ["friction_forms"]  # 6.5 %
    assert kinds(1e-5, 2e-5) == []  # both below 1e-4: negligible friction is not compared
    assert kinds(1.5e-5, -1.4e-3) == ["friction_forms"]  # eq. 6 of the wrong sign


def test_gather_one_sentence_per_kind_with_where_it_comes_from():
    a = Finding("friction off by 10 %", "friction", 0.1)
    b = Finding("friction off by 30 %", "friction", 0.3)
    c = Finding("contact off by 6 %", "contact_fraction", 0.06)
    out = gather([("v = 1", [a, c]), ("v = 2", [b]), ("v = 3", []), ("v = 4", ["a material warning"])], noun="speeds")
    assert out == [
        "at 2 of 4 speeds (v = 1, v = 2; worst at v = 2): friction off by 30 %",
        "at v = 1: contact off by 6 %",
        "at v = 4: a material warning",
    ]
    assert [f.kind for f in out] == ["friction", "contact_fraction", "other"]
    assert Finding.from_dict(json.loads(json.dumps(out[0].as_dict()))).value == 0.3


# ---------------------------------------------------------------- the reproducers


def test_friction_curve_on_an_under_resolved_grid_warns():
    """64² with 32 scales (2 points per shortest wavelength): eq. 6 turns negative at high speed and is
    up to ~100x off the dissipation form. Before: FrictionCurve had no warnings and no estimate."""
    s = bem.surfaces.self_affine(64, 0.01, hurst=0.8, scales=32, rms_height=2e-5, seed=1)
    curve = bem.friction_curve(s, SLS, speeds=np.logspace(-4, 2, 7), load=0.3)
    assert np.min(curve.friction_eq6) < 0
    kinds = [w.kind for w in curve.warnings]
    assert {"friction_forms", "contact_fraction", "friction"} <= set(kinds)
    assert len(kinds) == len(set(kinds))  # one sentence per kind, with the speeds it comes from
    forms = curve.warnings[kinds.index("friction_forms")]
    assert forms.startswith("at ") and " of 7 speeds (" in forms
    assert np.all(curve.error_estimate["contact_fraction"] > 0.05)
    assert all(r.warnings for r in curve.results)


def test_unresolved_leading_edge_layers_flag_the_peak_not_the_friction():
    """12-term rubber (E_inf/E0 = 1000, tau 1e-7..1 s), cylinder a decade below its friction peak:
    the peak pressure sits within two cells of the leading edge, in layers V tau_k of 1e-12..1e-5 m
    against cells of 1e-5 m, and moves erratically with the grid (measured per doubling from 1024
    cells: 44 %, 0.6 %, 3.7 %, 12 %) while friction moves 1.8e-4 and less. Estimated at 4096 cells
    (the peak on the edge cell; the model edge spike, 1.09 times the peak, falls on the finer grid, so
    the peak counts as resolved but uncertain): peak 6.9 %, friction 3.4e-5."""
    m = rubber(1000, 12, 1e-7, 1.0)
    a0 = math.sqrt(4 * 1500.0 * 0.02 / (math.pi * m.E0 / 0.75))
    c = bem.surfaces.cylinder(radius=0.02, n=4096, length=4 * a0)
    r = bem.solve(c, m, speed=1e-5, load=1500.0, periodic=False)
    assert r.error_estimate["peak_pressure"] > 0.05
    assert r.error_estimate["friction"] < 1e-3
    (peak,) = [w for w in r.warnings if w.kind == "peak_pressure"]
    assert "leading-edge layers thinner than a cell" in peak and "Friction does not depend on them" in peak


BROAD = rubber(500, 14, 1e-8, 10.0)  # the broad rubber: 14 terms, E_inf/E0 = 500


def _indenter(kind, n, speed, a=1e-3, radius=0.01):
    """A cylinder or sphere of contact half-width ``a`` (m) on :data:`BROAD`, on a domain 4 a wide."""
    e_star = abs(complex(BROAD.complex_modulus(speed / a))) / (1 - BROAD.nu**2)
    if kind == "cylinder":
        s, load = bem.surfaces.cylinder(radius=radius, n=n, length=4 * a), math.pi * a**2 * e_star / (4 * radius)
    else:
        s, load = bem.surfaces.sphere(radius=radius, n=n, length=4 * a), 4 * e_star * a**3 / (3 * radius)
    return s, dict(speed=speed, load=load, periodic=False)


@pytest.mark.parametrize("kind, n, speed", [("cylinder", 512, 1e-7), ("sphere", 48, 2e-7)])
def test_slow_indenter_on_a_broad_rubber_has_an_unresolved_peak(kind, n, speed):
    """The trap of issue 37: every layer V tau_k is thinner than a cell (1e-15..1e-6 m against cells of
    7.8e-6 m for the cylinder), the grid puts the peak at the centre, and the finer grid finds a
    leading-edge spike: the peak moved 9.8 % (cylinder) and 12 % (sphere) where the estimate said
    4.6e-6 and 1.1e-3. Now the peak has no estimate, says why, and warns; friction, which integrates
    over the layers, keeps its estimate (measured 1.3e-3 and 5.4e-3)."""
    s, kw = _indenter(kind, n, speed)
    r = bem.solve(s, BROAD, **kw)
    est = r.error_estimate
    assert est["peak_pressure"] is None and est.reasons["peak_pressure"].startswith("unresolved")
    (found,) = [w for w in r.warnings if w.kind == "peak_unresolved"]
    assert "thinner than a cell" in found and "14 Prony term(s)" in found
    assert not [w for w in r.warnings if w.kind == "friction"]
    ref = bem.solve(s, BROAD, error_estimate="refined", **kw).error_estimate
    assert ref["peak_pressure"] > 0.05
    assert ref["friction"] / 3 <= est["friction"] <= 3 * ref["friction"]


def test_a_measured_change_does_not_clear_an_unresolved_peak():
    """The same cylinder on 256 cells: the grid twice as fine moves its peak by 9e-6, and the next one
    by 9.8 % (above). The refined estimate reports the 9e-6 it measured, and the warning that it does
    not bound the error."""
    s, kw = _indenter("cylinder", 256, 1e-7)
    r = bem.solve(s, BROAD, error_estimate="refined", **kw)
    assert r.error_estimate["peak_pressure"] < 1e-4
    (found,) = [w for w in r.warnings if w.kind == "peak_unresolved"]
    assert "does not bound its error" in found


def test_slower_still_the_layers_raise_no_spike_and_the_peak_keeps_its_estimate():
    """Ten times slower (layers 1e-16..1e-7 m): the layers still lie below the cell, but the edge stays
    below the centre's pressure, the peak is resolved and moves 2e-6 on the finer grid."""
    s, kw = _indenter("cylinder", 512, 1e-8)
    r = bem.solve(s, BROAD, **kw)
    assert r.error_estimate["peak_pressure"] is not None and r.error_estimate["peak_pressure"] < 1e-3
    assert r.warnings == ()


def test_refined_estimate_falls_back_when_the_finer_grid_is_refused():
    """An adaptive mesh whose finer level exceeds max_elements: the default estimate, saying why."""
    c = bem.surfaces.cylinder(radius=0.01, n=64, length=0.006)
    r = bem.solve(c, SLS, speed=0.05, load=1000.0, periodic=False, method="adaptive", max_elements=64)
    ref = bem.solve(
        c, SLS, speed=0.05, load=1000.0, periodic=False, method="adaptive", max_elements=64, error_estimate="refined"
    ).error_estimate
    assert ref.method == "indicators" and "max_elements" in ref.indicators["refined"]
    assert ref["friction"] == pytest.approx(r.error_estimate["friction"])


# ---------------------------------------------------------------- the material's data


def _dma_fitted(w_lo, w_hi):
    """A rubber fitted to noise-free DMA data over [w_lo, w_hi] rad/s."""
    truth = rubber(100, 8, 1e-6, 1e1)
    w = np.logspace(math.log10(w_lo), math.log10(w_hi), 41)
    e = truth.complex_modulus(w)
    return bem.Material.fit_prony(w, e.real, e.imag)


def test_a_solve_beyond_the_dma_data_says_so():
    """A 1 mm cell sliding at 1 m/s loads the material at 2 pi/L v = 6.3e3 .. pi/dx v = 2e5 rad/s
    (64 points): data that stop at 1e3 rad/s leave that band unmeasured, and the result says
    so; data over 1e-2..1e7 rad/s cover it, and the result has no such warning."""
    s = bem.surfaces.self_affine(64, 1e-3, hurst=0.8, scales=8, rms_slope=0.2, seed=3)
    short = bem.solve(s, _dma_fitted(1e-4, 1e3), speed=1.0, load=0.05 * 1e6 * 1e-6)
    found = [w for w in short.warnings if w.kind == "material_data"]
    assert len(found) == 1 and "rad/s" in found[0]
    covered = bem.solve(s, _dma_fitted(1e-2, 1e7), speed=1.0, load=0.05 * 1e6 * 1e-6)
    assert not [w for w in covered.warnings if w.kind == "material_data"]
    # a material given by its constants has no data to be beyond
    assert not [
        w for w in bem.solve(s, rubber(100, 8, 1e-6, 1e1), speed=1.0, load=0.05).warnings if w.kind == "material_data"
    ]
