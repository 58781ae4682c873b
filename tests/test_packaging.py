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
