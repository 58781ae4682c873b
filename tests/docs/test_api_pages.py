"""The API reference covers every public module, and shows the code's own defaults.

A module is covered when an API page renders it (``::: module``) or an object defined in it
(``::: module.Name``, or a package page whose ``__all__`` re-exports that object). The
defaults check loads the packages with griffe and the site's extension
(``docs/griffe_defaults.py``), as mkdocstrings does, and compares every default in every
parameters table with the signature, and every literal signature default with the value
Python really uses.
"""

import ast
import importlib
import inspect
import pkgutil
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
API = ROOT / "docs" / "api"
PACKAGES = ("bem", "fem_reference", "validation")
DIRECTIVE = re.compile(r"^::: ([\w.]+)\s*$", re.MULTILINE)


def public_modules():
    names = []
    for top in PACKAGES:
        package = importlib.import_module(top)
        names.append(top)
        for info in pkgutil.walk_packages(package.__path__, prefix=f"{top}."):
            if not any(part.startswith("_") for part in info.name.split(".")):
                names.append(info.name)
    return names


def _resolve(path):
    """The live object of a ``:::`` path (bem's lazy public names resolve on getattr)."""
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for part in parts[i:]:
            obj = getattr(obj, part)
        return obj
    raise ImportError(path)


def documented():
    """{module name: how it is covered} from every ``:::`` directive of docs/api."""
    covered = {}
    for page in sorted(API.glob("*.md")):
        for path in DIRECTIVE.findall(page.read_text(encoding="utf-8")):
            obj = _resolve(path)
            if inspect.ismodule(obj):
                covered[obj.__name__] = page.name
                for name in getattr(obj, "__all__", []):  # a package page shows what it re-exports
                    member = getattr(obj, name)
                    owner = member.__name__ if inspect.ismodule(member) else getattr(member, "__module__", None)
                    if owner:
                        covered.setdefault(owner, page.name)
            else:
                covered.setdefault(obj.__module__, page.name)
    return covered


def test_every_public_module_has_an_api_page():
    covered = documented()
    missing = [m for m in public_modules() if m not in covered]
    assert not missing, f"public modules with no API page (add a '::: module' to docs/api/*.md): {missing}"


def test_bem_public_names_have_api_pages():
    """The names ``import bem`` offers (bem.persson, bem.anisotropy, ...) are each on a page."""
    import bem

    covered = documented()
    for name in bem.__all__:
        obj = getattr(bem, name)
        module = obj.__name__ if inspect.ismodule(obj) else obj.__module__
        assert module in covered, f"bem.{name} ({module}) has no API page"


def test_every_api_page_is_in_the_navigation():
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    for page in API.glob("*.md"):
        assert f"api/{page.name}" in nav, f"docs/api/{page.name} is not in mkdocs.yml's nav"


# --- defaults ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def loaded():
    griffe = pytest.importorskip("griffe", reason="the docs extra (mkdocstrings) provides griffe")
    sys.path.insert(0, str(ROOT / "docs"))
    try:
        from griffe_defaults import DefaultsFromCode
    finally:
        sys.path.remove(str(ROOT / "docs"))
    extensions = griffe.load_extensions(DefaultsFromCode())
    return [
        griffe.load(top, search_paths=[str(ROOT)], docstring_parser="numpy", extensions=extensions)
        for top in PACKAGES
    ]


def _documented_objects(obj):
    for member in obj.members.values():
        if member.is_alias or member.name.startswith("_"):
            continue
        if member.is_function or member.is_class:
            yield member
        if member.is_module or member.is_class:
            yield from _documented_objects(member)


def _literal(text):
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return inspect.Parameter.empty


def test_parameter_tables_show_the_signature_defaults(loaded):
    import griffe

    wrong = []
    for package in loaded:
        for obj in _documented_objects(package):
            if obj.docstring is None or not getattr(obj, "parameters", None):
                continue
            for section in obj.docstring.parsed:
                if section.kind is not griffe.DocstringSectionKind.parameters:
                    continue
                for row in section.value:
                    if row.name in obj.parameters:
                        code = obj.parameters[row.name].default
                        if str(row.value) != str(code):
                            wrong.append(f"{obj.path}({row.name}): table {row.value}, code {code}")
    assert not wrong, "parameters tables whose default is not the code's:\n" + "\n".join(wrong)


def test_signature_defaults_are_the_values_python_uses(loaded):
    """A literal default as shown equals the live default; a named constant is shown as its value."""
    sys.path.insert(0, str(ROOT / "docs"))
    try:
        from griffe_defaults import live_object
    finally:
        sys.path.remove(str(ROOT / "docs"))
    wrong, checked = [], 0
    for package in loaded:
        for obj in _documented_objects(package):
            parameters = getattr(obj, "parameters", None)
            live = live_object(obj) if parameters else None
            if live is None:
                continue
            try:
                signature = inspect.signature(live)
            except (TypeError, ValueError):
                continue
            for p in parameters:
                if p.default is None or p.name not in signature.parameters:
                    continue
                shown, actual = _literal(str(p.default)), signature.parameters[p.name].default
                if shown is inspect.Parameter.empty or actual is inspect.Parameter.empty:
                    continue
                checked += 1
                if type(shown) is not type(actual) and not (
                    isinstance(shown, (int, float)) and isinstance(actual, (int, float))
                ):
                    wrong.append(f"{obj.path}({p.name}): shown {p.default}, code {actual!r}")
                elif shown != actual and not (shown != shown and actual != actual):
                    wrong.append(f"{obj.path}({p.name}): shown {p.default}, code {actual!r}")
    assert checked > 100, f"only {checked} defaults compared: the walk found too little"
    assert not wrong, "\n".join(wrong)


def test_fit_master_curve_table_defaults(loaded):
    """The reported case: one docstring line documents terms_per_decade, smoothing and nu."""
    bem_pkg = loaded[0]
    func = bem_pkg["materials.material.Material.fit_master_curve"]
    rows = {r.name: r.value for s in func.docstring.parsed if s.kind.value == "parameters" for r in s.value}
    assert (str(rows["terms_per_decade"]), str(rows["smoothing"]), str(rows["nu"])) == ("3.0", "0.0", "0.5")
