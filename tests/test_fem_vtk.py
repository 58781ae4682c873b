"""VTK export of the rolling fields: write, read back with meshio, compare."""
import numpy as np
import pytest

from bem import Material
from fem_reference import rolling_cylinder


def test_vtu_round_trip(tmp_path):
    meshio = pytest.importorskip("meshio")
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)
    path = tmp_path / "rolling.vtu"
    r = rolling_cylinder(m, radius=0.01, load=100.0, speed=0.1, resolution=2, grading=1.5, vtk=path,
                         keep_fields=True)
    back = meshio.read(path)
    f = r.fields
    nel = f["mesh"].t.shape[1]
    assert back.points.shape == (f["mesh"].p.shape[1], 3)
    np.testing.assert_allclose(back.points[:, :2], f["mesh"].p.T)
    np.testing.assert_allclose(back.point_data["displacement"][:, :2], f["u"][f["basis"].nodal_dofs].T)
    for name in ("strain", "stress", "alpha_0"):
        assert back.cell_data[name][0].shape == (nel, 3)
    diss = back.cell_data["dissipation"][0]
    assert diss.shape == (nel,) and np.all(diss >= 0)
    # cell averages integrate to the total dissipation (weights sum per cell)
    w = f["weights"].reshape(nel, -1).sum(axis=1)
    assert np.sum(diss * w) == pytest.approx(np.sum(f["weights"] * f["dissipation"]), rel=1e-10)
    # the contact pushes the surface down under the cylinder
    top = np.abs(back.points[:, 1]) < 1e-15
    x = back.points[top, 0]
    uy = back.point_data["displacement"][top, 1]
    assert uy[np.argmin(np.abs(x))] < 0
    # and compresses it there: sigma_yy < 0 in the cell below the contact centre
    centre = f["mesh"].p[:, f["mesh"].t].mean(axis=1)
    cell = np.argmin(np.abs(centre[0]) + np.abs(centre[1]))
    assert back.cell_data["stress"][0][cell, 1] < 0


def test_no_fields_unless_asked():
    m = Material.elastic(1e7, nu=0.3)
    r = rolling_cylinder(m, radius=0.01, load=100.0, speed=0.0, resolution=2)
    assert r.fields == {}
