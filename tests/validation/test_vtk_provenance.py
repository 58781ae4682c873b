"""VTK files say what made them: version, solver and settings, the material as given, a unit
for every array (machine-readable), and the parameter their .pvd series runs over."""

import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from conftest import make_tiny_scene, vtk_units

import bem
from validation import vtk_io
from viscobem_cli.main import main

pv = pytest.importorskip("pyvista", reason="the vtk extra")

SCENE = make_tiny_scene("vtk = true\nplots = false", speeds="[0.001, 0.01, 0.1]", seed=2, solver="rtol = 1e-9")


def every_array_has_a_unit(grid):
    units = vtk_units(grid)
    for name in ("pressure", "E0", "E_inf", "prony_moduli"):
        assert units[name] == "Pa"
    assert units["speed"] == "m/s" and units["gap"] == "m" and units["creep_times"] == "s"
    return units


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("vtkrun")
    (folder / "s.toml").write_text(SCENE)
    assert main(["run", str(folder / "s.toml"), "--out", str(folder / "out"), "--no-progress"]) == 0
    return folder / "out", json.loads((folder / "out" / "results.json").read_text())


def test_cli_files_carry_their_provenance(run):
    out, record = run
    from importlib.metadata import version

    for k in range(3):
        grid = pv.read(out / "vtk" / f"point_{k:03d}.vti")
        fd = grid.field_data
        assert fd["viscobem_version"][0] == version("viscobem")
        assert "periodic BEM" in fd["solver"][0]
        settings = json.loads(fd["solver_settings"][0])
        assert settings["rtol"] == 1e-9 and fd["rtol"][0] == 1e-9
        assert settings["grid"] == [16, 16] and settings["maxiter"] == record["solver"]["maxiter"]
        assert json.loads(fd["material_given"][0]) == {"E0": 3.3e6, "E_inf": 1.0e7, "creep_time": 0.01, "nu": 0.5}
        assert list(fd["grid_points"]) == [16, 16] and fd["grid_spacing"][0] == pytest.approx(0.01 / 16)
        assert fd["friction_eq6"][0] == pytest.approx(record["friction_curve"]["friction_eq6"][k], rel=1e-12)
        assert fd["xi"][0] == pytest.approx(record["friction_curve"]["xi"][k], rel=1e-12)
        every_array_has_a_unit(grid)


def test_cli_series_runs_over_the_speed_and_says_so(run):
    out, record = run
    pvd = out / "vtk" / "sweep.pvd"
    times = [float(d.get("timestep")) for d in ET.parse(pvd).getroot().iter("DataSet")]
    assert times == pytest.approx(record["friction_curve"]["speed"], rel=1e-15)
    assert vtk_io.pvd_parameter(pvd) == "sliding speed V (m/s)"
    reader = pv.get_reader(pvd)  # what ParaView's time widget shows
    assert list(reader.time_values) == pytest.approx(record["friction_curve"]["speed"])
    reader.set_active_time_point(1)
    grid = reader.read()[0]
    assert grid.field_data["series_parameter"][0] == "sliding speed V (m/s)"
    assert grid.field_data["series_value"][0] == pytest.approx(0.01)


def test_units_table_covers_new_arrays(tmp_path):
    """The check can fail: an array the units table does not know is reported as text, and a
    point array missing from POINT_UNITS fails the coverage check."""
    material = bem.Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=0.01)
    surface = bem.surfaces.sinusoid(32, 1e-3, amplitude=1e-6)
    res = bem.solve(surface, material, speed=0.01, load=1.0)
    grid = vtk_io.surface_grid(surface, res, material=material, extra={"note": ["x"]})
    assert json.loads(grid.field_data["units"][0])["note"] == "text"
    grid.point_data["unlisted"] = np.zeros(grid.n_points)
    with pytest.raises(AssertionError, match="unlisted"):
        every_array_has_a_unit(grid)
