"""VTK export of the rolling fields: write a .vtm (block + interface), read it back with pyvista,
and compare names, units and values with the result object."""

import numpy as np
import pytest
from conftest import vtk_units

from bem import Material
from fem_reference import rolling_cylinder
from fem_reference.fields import contact_residual
from fem_reference.vtk import COMPONENTS, CONVENTIONS, tau_name


@pytest.fixture(scope="module")
def rolled(tmp_path_factory):
    m = Material.from_prony(E0=1e6, moduli=[1e6, 1e6], times=[3e-3, 3e-2], nu=0.5)
    path = tmp_path_factory.mktemp("vtk") / "rolling.vtm"
    r = rolling_cylinder(
        m, radius=0.01, load=100.0, speed=0.05, resolution=2, grading=1.5, vtk=path, keep_fields=True, fold=0
    )
    return r, path


def test_vtm_holds_the_block_and_the_interface_with_metadata(rolled):
    pv = pytest.importorskip("pyvista")
    r, path = rolled
    blocks = pv.read(path)
    assert list(blocks.keys()) == ["volume", "interface"]
    vol, iface = blocks["volume"], blocks["interface"]
    m = r.material
    for ds in (vol, iface):
        fd = ds.field_data
        assert fd["speed"][0] == r.speed and fd["load"][0] == r.load and fd["radius"][0] == r.radius
        assert fd["E0"][0] == m.E0 and fd["E_inf"][0] == m.E_inf and fd["nu"][0] == m.nu
        np.testing.assert_array_equal(fd["relaxation_times"], m.relaxation_times)
        np.testing.assert_array_equal(fd["prony_moduli"], m.moduli)
        a0 = np.sqrt(4 * r.load * r.radius * (1 - m.nu**2) / (np.pi * m.E0))
        assert fd["dimensionless_speed"][0] == pytest.approx(r.speed * m.creep_times.max() / a0, rel=1e-12)
        units = vtk_units(ds)
        assert units["speed"] == "m/s" and units["load"] == "N/m" and units["E0"] == "Pa"
        assert str(fd["conventions"][0]) == CONVENTIONS
    assert vtk_units(vol)[tau_name(m.relaxation_times[0])] == "1" and vtk_units(vol)["stress"] == "Pa"
    # the interface: the result's own pressure, contact set and gap, at its own nodes
    np.testing.assert_array_equal(iface.points[:, 0], r.x)
    np.testing.assert_array_equal(iface.point_data["pressure"], r.pressure)
    np.testing.assert_array_equal(iface.point_data["contact"].astype(bool), r.pressure > 0)
    gap = iface.point_data["gap"]
    assert np.all(np.abs(gap[r.pressure > 0]) <= 1e-9 * abs(r.approach))
    assert np.all(gap[r.pressure == 0] >= -1e-9 * abs(r.approach))
    np.testing.assert_allclose(-iface.point_data["displacement"][:, 1], r.displacement, atol=1e-8 * abs(r.approach))


def test_tensors_are_full_and_named_and_internal_variables_carry_tau(rolled):
    pv = pytest.importorskip("pyvista")
    r, path = rolled
    vol = pv.read(path)["volume"]
    f = r.fields
    nel = f["mesh"].t.shape[1]
    for name in ("stress", "strain"):
        assert vol.cell_data[name].shape == (nel, 9)
        arr = vol.GetCellData().GetArray(name)
        assert [arr.GetComponentName(i) for i in range(9)] == list(COMPONENTS)
    s = vol.cell_data["stress"]
    # plane strain: sigma_zz is not zero, the trace is -3 p, von Mises and hydrostatic pressure agree
    assert np.max(np.abs(s[:, 8])) > 0.1 * np.max(np.abs(s[:, 4]))
    np.testing.assert_allclose(vol.cell_data["strain"][:, 8], 0.0)
    w = f["weights"].reshape(nel, -1)
    p_avg = (w * f["pressure"].reshape(nel, -1)).sum(1) / w.sum(1)
    np.testing.assert_allclose(vol.cell_data["hydrostatic_pressure"], p_avg, rtol=1e-9, atol=1e-9 * np.abs(p_avg).max())
    assert np.all(vol.cell_data["von_mises"] >= 0)
    names = [tau_name(t) for t in r.material.relaxation_times]
    assert sorted(names) == ["viscous_strain_tau=0.003s", "viscous_strain_tau=0.03s"]
    for name in names:
        assert vol.cell_data[name].shape == (nel, 9)
    # the contact compresses the block under the cylinder
    centre = f["mesh"].p[:, f["mesh"].t].mean(axis=1)
    cell = np.argmin(np.abs(centre[0]) + np.abs(centre[1]))
    assert s[cell, 4] < 0 and vol.cell_data["hydrostatic_pressure"][cell] > 0


def test_dissipated_power_is_the_field_integral_not_the_moment(rolled):
    """The dissipation written to the file, integrated over the block, is ``dissipated_power``; it
    agrees with ``mu P V`` from the moment only to the discretisation error (so it is computed,
    not copied)."""
    pv = pytest.importorskip("pyvista")
    r, path = rolled
    vol = pv.read(path)["volume"]
    w = r.fields["weights"].reshape(vol.n_cells, -1).sum(axis=1)
    assert np.sum(vol.cell_data["dissipation"] * w) == pytest.approx(r.dissipated_power, rel=1e-10)
    moment = r.friction * r.load * r.speed
    assert r.dissipated_power != moment and r.dissipated_power == pytest.approx(moment, rel=0.05)


def test_contact_residual_from_the_field_can_fail(rolled):
    """A real residual: ~1e-9 for the solution, 1e-4 once the approach is 1e-4 of itself off."""
    from dataclasses import replace

    r, _ = rolled
    assert contact_residual(r) < 1e-8
    assert contact_residual(replace(r, approach=r.approach * (1 + 1e-4))) > 0.9e-4


def test_interface_of_a_graded_mesh_whose_band_is_not_symmetric(tmp_path):
    """On the graded mesh the candidate band runs from its own trailing to its own leading end;
    the interface written is that band, node by node, with its displacement from the field."""
    pv = pytest.importorskip("pyvista")
    from fem_reference.surface import top_surface

    m = Material.from_prony(E0=1e6, moduli=np.full(3, 29e6 / 3), times=[1e-5, 1e-3, 1e-1], nu=0.5)
    r = rolling_cylinder(
        m, radius=0.01, load=100.0, speed=1e-3, resolution=1, solver="splu", keep_fields=True, vtk=tmp_path / "g.vtm"
    )
    top = top_surface(r.fields["basis"])
    # the case has teeth: a band symmetric about x = 0 would hold more nodes than the result
    assert np.count_nonzero(np.abs(top.x) <= np.max(np.abs(r.x))) > r.x.size
    iface = pv.read(tmp_path / "g.vtm")["interface"]
    np.testing.assert_array_equal(iface.points[:, 0], r.x)
    np.testing.assert_allclose(-iface.point_data["displacement"][:, 1], r.displacement, atol=1e-8 * abs(r.approach))
    assert contact_residual(r) < 1e-8


def test_friction_in_both_forms_and_the_material_as_given(tmp_path):
    """The metadata carry the friction in both forms (``friction`` is the dissipation form the harness
    compares) and the material as given beside the folded one the solver used."""
    pv = pytest.importorskip("pyvista")
    given = Material.from_prony(E0=1e6, moduli=[1e6, 1e6, 1e6], times=[1e-12, 3e-3, 3e-2], nu=0.5)
    r = rolling_cylinder(given, radius=0.01, load=100.0, speed=0.05, resolution=2, grading=2.0, vtk=tmp_path / "f.vtm")
    assert r.material.moduli.size == 2 and r.input_material is given  # the 1e-12 s term folded
    fd = pv.read(tmp_path / "f.vtm")["volume"].field_data
    assert fd["friction_dissipation"][0] == r.friction_dissipation and fd["friction_moment"][0] == r.friction
    assert fd["friction"][0] == r.friction_dissipation != r.friction
    np.testing.assert_array_equal(fd["input_relaxation_times"], given.relaxation_times)
    np.testing.assert_array_equal(fd["relaxation_times"], r.material.relaxation_times)
    assert fd["input_E0"][0] == given.E0 and fd["E0"][0] == r.material.E0


def test_vtu_of_the_block_alone(tmp_path):
    pv = pytest.importorskip("pyvista")
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)
    r = rolling_cylinder(m, radius=0.01, load=100.0, speed=0.1, resolution=2, vtk=tmp_path / "b.vtu")
    vol = pv.read(tmp_path / "b.vtu")
    assert vol.field_data["speed"][0] == r.speed and "stress" in vol.cell_data
    assert r.fields == {}


def test_no_fields_unless_asked():
    m = Material.elastic(1e7, nu=0.3)
    r = rolling_cylinder(m, radius=0.01, load=100.0, speed=0.0, resolution=2)
    assert r.fields == {}


def test_indentation_pvd_time_series(tmp_path):
    """Creep indentation as a .pvd: one block + interface per output time, the time values, the
    names and the last pressure profile of the result."""
    pv = pytest.importorskip("pyvista")
    from fem_reference import indentation

    m = Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01, nu=0.5)
    times = np.array([0.0, 0.01, 0.05])
    r = indentation(m, radius=0.01, load=1.0, times=times, resolution=2, steps_per_decade=4, vtk=tmp_path / "creep.pvd")
    reader = pv.get_reader(tmp_path / "creep.pvd")
    np.testing.assert_allclose(reader.time_values, times)
    reader.set_active_time_point(len(times) - 1)
    blocks = reader.read()[0]  # the .pvd's one dataset at this time: the .vtm multiblock
    vol, iface = blocks["volume"], blocks["interface"]
    assert vol.cell_data["strain"].shape[1] == 9
    assert vol.GetCellData().GetArray("strain").GetComponentName(8) == "ZZ"
    assert tau_name(m.relaxation_times[0]) in vol.cell_data.keys()
    np.testing.assert_allclose(iface.points[:, 0], r.r)
    np.testing.assert_allclose(iface.point_data["pressure"], r.pressure)
    contact = iface.point_data["contact"].astype(bool)
    assert np.all(np.abs(iface.point_data["gap"][contact]) <= 1e-6 * r.approach[-1])
    fd = iface.field_data
    assert fd["time"][0] == pytest.approx(0.05) and fd["approach"][0] == pytest.approx(r.approach[-1])
    assert fd["load"][0] == 1.0 and fd["E_inf"][0] == m.E_inf and vtk_units(iface)["load"] == "N"
    assert vtk_units(vol)["dissipation"] == "W/m^3" and vtk_units(vol)["time"] == "s"
    for name in ("stress", "von_mises", "hydrostatic_pressure", "dissipation"):
        assert name in vol.cell_data.keys()
    # creeping at t = 5 creep times: the dashpots still dissipate, never negatively
    diss = vol.cell_data["dissipation"]
    assert np.all(diss >= -1e-12 * diss.max()) and diss.max() > 0
    assert vol.GetCellData().GetArray("stress").GetComponentName(4) == "YY"
    assert np.allclose(vol.cell_data["hydrostatic_pressure"], -vol.cell_data["stress"][:, [0, 4, 8]].sum(axis=1) / 3)
    for k in range(len(times)):
        reader.set_active_time_point(k)
        assert vertical_force_through_rows(reader.read()[0]["volume"], 1.0) == pytest.approx(-1.0, rel=1e-9)


def vertical_force_through_rows(vol, load, rows=3):
    """The axial stress (``YY``) integrated over the ring areas of the top ``rows`` rows of cells
    (N), the worst row. Axial equilibrium with roller sides makes it minus the load at every depth;
    the cell averages are weighted by the axisymmetric volume, so it holds for the discrete solution
    (measured within 1.2e-12 of the load; tolerance 1e-9 for round-off)."""
    c = vol.cell_centers().points
    area = vol.compute_cell_sizes(length=False, volume=False)["Area"]
    forces = []
    for z in np.unique(np.round(c[:, 1], 12))[::-1][:rows]:
        row = np.isclose(c[:, 1], z)
        bounds = vol.get_cell(int(np.flatnonzero(row)[0])).bounds
        ring = 2 * np.pi * c[row, 0] * area[row] / (bounds[3] - bounds[2])
        forces.append(np.sum(vol.cell_data["stress"][row, 4] * ring))
    return max(forces, key=lambda f: abs(f + load))
