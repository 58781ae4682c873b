"""Layering (STYLE.md practice 1): ``import bem`` pulls in numpy and scipy only.

Each check runs in a fresh interpreter, so modules imported by other tests do not count.
"""

import json
import subprocess
import sys
from pathlib import Path

import pytest

FORBIDDEN = [
    "matplotlib",
    "skfem",
    "meshio",
    "pyvista",
    "vtk",
    "tqdm",
    "rich",
    "fem_reference",
    "validation",
    "viscobem_cli",
    "pandas",
    "numba",
]


def _modules_after(statement):
    code = f"import sys, json; {statement}; print(json.dumps(sorted(sys.modules)))"
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        cwd=Path(__file__).resolve().parents[1],
    )  # the repository root, where bem/ is
    return {name.split(".")[0] for name in json.loads(out.stdout.splitlines()[-1])}


@pytest.fixture(scope="module")
def after_import():
    return _modules_after("import bem, bem.surfaces, bem.surfaces.statistics, bem.halfspace.periodic, bem.contact")


@pytest.mark.parametrize("name", FORBIDDEN)
def test_import_bem_pulls_in_no_plotting_meshing_fem_or_progress(after_import, name):
    assert name not in after_import


def test_import_bem_needs_numpy_and_scipy(after_import):
    assert {"numpy", "scipy", "bem"} <= after_import


def test_a_solve_without_progress_imports_no_progress_bar():
    """tqdm is imported lazily, by friction_curve only."""
    modules = _modules_after(
        "import bem; from bem import surfaces; "
        "bem.solve(surfaces.sinusoid(32, 1e-3, amplitude=1e-6), bem.Material.elastic(1e7), speed=0, load=1.0)"
    )
    assert not {"tqdm", "matplotlib", "skfem", "pyvista"} & modules
