"""Import rules of the library packages, read from the sources with ``ast`` (no import runs):

- no import cycle between modules, nor between packages, nor between the subpackages and
  top-level modules of ``bem`` (``bem.contact``, ``bem.halfspace``, ``bem.result``, ...: the
  operators sit below the solvers, which sit below the results); imports inside functions count:
  a deferred import is still a dependency;
- no private name (``_x``) taken from another module, neither imported nor reached as an
  attribute of an imported module: what modules share is public (within their subpackage);
- every module parses as Python 3.10 (``requires-python``) and reads TOML through the
  ``tomli`` fallback where ``tomllib`` (3.11+) is missing.
"""

import ast
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("bem", "fem_reference", "validation", "viscobem_cli", "viscobem_bench")


def _module_name(path, root):
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _sources(root=ROOT):
    """``{module name: (path, syntax tree)}`` of the library packages under ``root``."""
    return {
        _module_name(path, root): (path, ast.parse(path.read_text(), filename=str(path)))
        for top in PACKAGES
        for path in sorted((root / top).rglob("*.py"))
    }


SOURCES = _sources()


def _resolve(module, node, sources):
    """Absolute name of the module a ``from ... import`` statement reads from."""
    if not node.level:
        return node.module
    path = sources[module][0]
    base = module.split(".")
    base = base if path.name == "__init__.py" else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(module, tree, sources):
    """``(target module, imported name or None, line, bound alias)`` for every import in ``tree``."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, None, node.lineno, a.asname or a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom):
            source = _resolve(module, node, sources)
            for a in node.names:
                sub = f"{source}.{a.name}"
                if sub in sources:  # ``from pkg import submodule``
                    yield sub, None, node.lineno, a.asname or a.name
                else:
                    yield source, a.name, node.lineno, a.asname or a.name


def _graph(sources):
    edges = {m: set() for m in sources}
    for m, (_, tree) in sources.items():
        for target, _, _, _ in _imports(m, tree, sources):
            while target and target not in sources:  # ``import a.b.c`` of a non-module attribute
                target = target.rpartition(".")[0]
            if target and target != m:
                edges[m].add(target)
    return edges


def _cycles(edges):
    """Strongly connected components with more than one node (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def _package_edges(edges):
    top = {}
    for m, targets in edges.items():
        top.setdefault(m.split(".")[0], set()).update(
            t.split(".")[0] for t in targets if t.split(".")[0] != m.split(".")[0]
        )
    return top


def _subpackage_edges(edges, top="bem"):
    """The module graph of ``top`` folded onto its subpackages and top-level modules
    (``bem.halfspace.periodic`` -> ``bem.halfspace``); the package's own ``__init__`` re-exports
    everything and stays out."""

    def unit(m):
        return ".".join(m.split(".")[:2])

    folded = {}
    for m, targets in edges.items():
        if m.split(".")[0] != top or m == top:
            continue
        folded.setdefault(unit(m), set()).update(
            unit(t) for t in targets if t.split(".")[0] == top and t != top and unit(t) != unit(m)
        )
    return folded


def _private_uses(sources):
    """``module:line name`` for every private name taken from another module."""
    found = []
    for m, (_, tree) in sources.items():
        modules = {}  # names bound to other modules of the library packages
        for target, name, line, alias in _imports(m, tree, sources):
            if target == m or target.split(".")[0] not in PACKAGES:
                continue
            private_module = any(p.startswith("_") and not p.startswith("__") for p in target.split("."))
            if private_module or (name and name.startswith("_")):
                found.append(f"{m}:{line} {target}{'.' + name if name else ''}")
            if name is None:
                modules[alias] = target
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Attribute)
                and node.attr.startswith("_")
                and not node.attr.startswith("__")
                and isinstance(node.value, (ast.Name, ast.Attribute))
            ):
                base = ast.unparse(node.value)
                if base in modules or base.split(".")[0] in modules and base.split(".")[0] != base:
                    found.append(f"{m}:{node.lineno} {base}.{node.attr}")
    return found


def test_no_import_cycle_between_modules():
    assert _cycles(_graph(SOURCES)) == []


def test_no_import_cycle_between_packages():
    assert _cycles(_package_edges(_graph(SOURCES))) == []


def test_no_import_cycle_between_the_subpackages_of_bem():
    """E.g. an operator package that imports a result type, which imports the accuracy estimates,
    which build operators: each layer must be importable and testable below the next."""
    assert _cycles(_subpackage_edges(_graph(SOURCES))) == []


def test_every_bem_module_imports():
    """The graph above is read from the sources; this imports each module for real."""
    import importlib

    for name in sorted(m for m in SOURCES if m.split(".")[0] == "bem"):
        importlib.import_module(name)


def test_no_private_name_is_taken_from_another_module():
    assert _private_uses(SOURCES) == []


def _write(root, files):
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def test_the_rules_catch_a_cycle_and_a_private_import(tmp_path):
    """The checks above on a small made-up tree: a deferred module cycle, a package cycle, two
    private names taken across packages and one taken from a sibling module are all reported."""
    _write(
        tmp_path,
        {
            "bem/__init__.py": "",
            "bem/a.py": "def f():\n    from .b import g\n",
            "bem/b.py": "from . import a\n",
            "bem/ops/__init__.py": "",
            "bem/ops/kernel.py": "from ..result import R\n",
            "bem/ops/periodic.py": "",
            "bem/result.py": "from .est.estimate import E\n",
            "bem/est/__init__.py": "",
            "bem/est/estimate.py": "",
            "bem/est/refined.py": "from ..ops.periodic import P\n",
            "viscobem_cli/__init__.py": "",
            "viscobem_cli/main.py": "from viscobem_bench import suite\n",
            "viscobem_bench/__init__.py": "",
            "viscobem_bench/suite.py": "import bem.a\nfrom viscobem_cli.main import x\nbem.a._cache.clear()\n"
            "from bem.b import _check\n",
            "validation/__init__.py": "",
            "validation/plots.py": "from validation.style import _save\n",
            "validation/style.py": "def _save():\n    pass\n",
            "fem_reference/__init__.py": "",
        },
    )
    fake = _sources(tmp_path)
    edges = _graph(fake)
    assert _cycles(edges) == [["bem.a", "bem.b"], ["viscobem_bench.suite", "viscobem_cli.main"]]
    assert _cycles(_package_edges(edges)) == [["viscobem_bench", "viscobem_cli"]]
    assert _cycles(_subpackage_edges(edges)) == [["bem.a", "bem.b"], ["bem.est", "bem.ops", "bem.result"]]
    assert sorted(u.split()[1] for u in _private_uses(fake)) == [
        "bem.a._cache",
        "bem.b._check",
        "validation.style._save",
    ]


@pytest.mark.parametrize("module", sorted(SOURCES))
def test_module_parses_as_python_3_10(module):
    path = SOURCES[module][0]
    ast.parse(path.read_text(), filename=str(path), feature_version=(3, 10))


def _python_3_10():
    """A Python 3.10 interpreter on this machine, or None."""
    import shutil
    import subprocess

    for exe in (shutil.which("python3.10"), *sorted(Path("/root/.pyenv/versions").glob("3.10*/bin/python3.10"))):
        if (
            exe
            and subprocess.run(
                [str(exe), "-c", "import sys; assert sys.version_info[:2] == (3, 10)"], capture_output=True
            ).returncode
            == 0
        ):
            return str(exe)
    return None


def test_every_module_compiles_under_a_real_python_3_10():
    """The interpreter's own compiler, where one is installed (the ast check above is best effort)."""
    import subprocess

    exe = _python_3_10()
    if exe is None:
        pytest.skip("no Python 3.10 interpreter on this machine")
    files = [str(p) for p, _ in SOURCES.values()] + [str(p) for p in sorted((ROOT / "tests").glob("*.py"))]
    code = "import sys\nfor p in sys.argv[1:]:\n    compile(open(p, encoding='utf-8').read(), p, 'exec')\n"
    out = subprocess.run([exe, "-c", code, *files], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]


def _imports_tomli(body):
    return any(isinstance(s, ast.Import) and s.names[0].name == "tomli" for s in body)


def _tomllib_guarded(tree):
    """Every ``import tomllib`` sits in a ``try`` whose ``ImportError`` handler imports ``tomli``
    instead, or in the branch of an ``if sys.version_info ...`` whose other branch does."""
    guarded = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Try) and any(
            isinstance(h.type, ast.Name)
            and h.type.id in ("ImportError", "ModuleNotFoundError")
            and _imports_tomli(h.body)
            for h in node.handlers
        ):
            guarded.update(id(s) for s in node.body)
        if isinstance(node, ast.If) and "version_info" in ast.unparse(node.test):
            if _imports_tomli(node.orelse):
                guarded.update(id(s) for s in node.body)
            if _imports_tomli(node.body):
                guarded.update(id(s) for s in node.orelse)
    return all(
        id(n) in guarded
        for n in ast.walk(tree)
        if isinstance(n, ast.Import) and any(a.name == "tomllib" for a in n.names)
    )


@pytest.mark.parametrize(
    "path",
    sorted([*(p for p, _ in SOURCES.values()), *(ROOT / "tests").glob("*.py")]),
    ids=lambda p: str(p.relative_to(ROOT)),
)
def test_tomllib_has_the_tomli_fallback(path):
    assert _tomllib_guarded(ast.parse(path.read_text())), (
        "use: try: import tomllib / except ImportError: import tomli as tomllib"
    )


def test_tomli_is_a_dependency_below_python_3_11():
    text = (ROOT / "pyproject.toml").read_text()
    assert 'requires-python = ">=3.10"' in text and "tomli>=2.0; python_version < '3.11'" in text
    if sys.version_info < (3, 11):
        import tomli  # noqa: F401
