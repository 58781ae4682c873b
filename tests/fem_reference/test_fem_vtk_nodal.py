"""FEM VTK files: nodal stress beside the cell averages, and the files' provenance."""

import json

import numpy as np
import pytest

from fem_reference.nodal import project_to_nodes

pv = pytest.importorskip("pyvista", reason="the vtk extra")


def test_projection_is_exact_for_linear_fields():
    from skfem import Basis, ElementQuad2, MeshQuad

    mesh = MeshQuad.init_tensor(np.linspace(0, 1, 6), -(np.linspace(1, 0, 5) ** 3))  # graded in depth
    basis = Basis(mesh, ElementQuad2())
    x, y = basis.mapping.F(basis.X)
    field = np.stack([1 + 2 * x - 3 * y, np.full_like(x, 5.0)], axis=-1).reshape(-1, 2)
    nodal = project_to_nodes(field, basis)
    exact = np.stack([1 + 2 * mesh.p[0] - 3 * mesh.p[1], np.full(mesh.p.shape[1], 5.0)], axis=-1)
    assert np.max(np.abs(nodal - exact)) < 1e-12
    scalar = project_to_nodes(field[:, 0], basis)
    assert scalar.shape == (mesh.p.shape[1],) and np.allclose(scalar, exact[:, 0])
    bent = project_to_nodes((x**2).reshape(-1), basis)  # a curved field is not reproduced: the check can fail
    assert np.max(np.abs(bent - mesh.p[0] ** 2)) > 1e-4


def test_rolling_vtm_has_nodal_stress_and_provenance(tmp_path):
    import bem
    import fem_reference

    material = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
    path = tmp_path / "roll.vtm"
    result = fem_reference.rolling_cylinder(material, radius=0.01, load=1000.0, speed=0.05, resolution=4, vtk=path)
    volume = pv.read(path)["volume"]
    assert volume.point_data["stress_nodal"].shape == (volume.n_points, 9)
    assert "stress" in volume.cell_data and "von_mises_nodal" in volume.point_data
    # the nodal field averages back to the cell field: mean over each cell's corners vs the cell mean
    corners = volume.cells.reshape(-1, 5)[:, 1:]
    yy_nodal = volume.point_data["stress_nodal"][:, 4][corners].mean(axis=1)
    yy_cell = volume.cell_data["stress"][:, 4]
    scale = np.abs(yy_cell).max()
    assert np.median(np.abs(yy_nodal - yy_cell)) < 0.05 * scale
    # at the contact, the nodal -sigma_yy of the top surface follows the interface pressure
    top = np.isclose(volume.points[:, 1], 0.0)
    x_top, p_top = volume.points[top, 0], -volume.point_data["stress_nodal"][top, 4]
    order = np.argsort(x_top)
    p_interp = np.interp(result.x, x_top[order], p_top[order])
    assert np.max(np.abs(p_interp - result.pressure)) < 0.15 * result.peak_pressure
    fd = volume.field_data
    from importlib.metadata import version

    assert fd["viscobem_version"][0] == version("viscobem") and "rolling_cylinder" in fd["solver"][0]
    settings = json.loads(fd["solver_settings"][0])
    assert settings["n_elements"] == result.n_elements and settings["grading"] == result.grading
    units = json.loads(fd["units"][0])
    assert units["stress_nodal"] == "Pa" and units["displacement"] == "m"
