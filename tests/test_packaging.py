"""The wheel must contain every package and data file the code reads: CI installs with
``pip install .`` (not editable), so a package or data file missing from pyproject.toml only
fails there. Checked here against the source tree."""

import fnmatch
from pathlib import Path

try:
    import tomllib
except ImportError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
CONFIG = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
PACKAGES = set(CONFIG["packages"])
DATA_SUFFIXES = {".json", ".toml", ".csv", ".npy", ".txt"}


def _package_dirs():
    for top in sorted(PACKAGES, key=len):
        for init in (ROOT / top.replace(".", "/")).rglob("__init__.py"):
            yield init.parent


def test_every_subpackage_is_listed():
    found = {".".join(d.relative_to(ROOT).parts) for d in _package_dirs()}
    assert found <= PACKAGES, f"add to [tool.setuptools] packages: {sorted(found - PACKAGES)}"


def test_every_data_file_in_a_package_is_shipped():
    patterns = CONFIG.get("package-data", {})
    missing = []
    for d in set(_package_dirs()):
        package = ".".join(d.relative_to(ROOT).parts)
        for f in d.rglob("*"):
            if f.suffix not in DATA_SUFFIXES or "__pycache__" in f.parts:
                continue
            # data in a sub-folder that is itself a package belongs to that package
            owner = f.parent
            while owner != d and not (owner / "__init__.py").exists():
                owner = owner.parent
            if owner != d:
                continue
            rel = f.relative_to(d).as_posix()
            if not any(fnmatch.fnmatch(rel, p) for p in patterns.get(package, [])):
                missing.append(f"{package}: {rel}")
    assert not missing, f"add to [tool.setuptools.package-data]: {missing}"


PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def test_heavy_optional_parts_are_extras_and_the_test_extra_has_them():
    """``pip install .`` stays lean (no VTK, Dask, PARDISO); ``pip install ".[test]"`` installs
    everything the full test suite exercises."""
    base = " ".join(PROJECT["dependencies"])
    extras = PROJECT["optional-dependencies"]
    for heavy, extra in [("pyvista", "vtk"), ("dask", "dask"), ("pypardiso", "fem")]:
        assert heavy not in base
        assert any(req.startswith(heavy) for req in extras[extra])
    test = extras["test"]
    for extra in ("vtk", "dask", "bench"):
        for req in extras[extra]:
            assert req in test, f"{req} (extra {extra}) missing from the test extra"


def test_every_extra_named_by_the_command_line_exists():
    from viscobem_cli.catalog import EXTRAS

    assert {extra for extra, _ in EXTRAS.values()} <= set(PROJECT["optional-dependencies"])


def test_import_bem_is_lazy():
    """``import bem`` loads no submodule beyond what it needs; each public name loads its
    module on first use."""
    import json
    import subprocess
    import sys

    code = (
        "import sys, json, bem; before = sorted(sys.modules); bem.solve; bem.analysis.persson; "
        "print(json.dumps([before, sorted(sys.modules), sorted(dir(bem))]))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    before, after, names = json.loads(out.stdout)
    for heavy in (
        "scipy.signal",
        "scipy.optimize",
        "bem.analysis.persson",
        "bem.analysis.anisotropy",
        "bem.sliding",
        "bem.materials.material",
    ):
        assert heavy not in before
    assert "bem.sliding" in after and "bem.analysis.persson" in after
    assert "scipy.signal" not in after  # imported only by the function that filters
    assert {"solve", "friction_curve", "Material", "surfaces", "anisotropy", "persson"} <= set(names)
