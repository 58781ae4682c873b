"""fem_reference shares only data types with bem (docs/theory.md §9): never its kernels or solvers."""

import ast
import pathlib

import fem_reference

ALLOWED = {"bem.materials.material", "bem.errors", "bem.checks", "bem"}


def test_only_shared_types_imported_from_bem():
    root = pathlib.Path(fem_reference.__file__).parent
    for path in root.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "bem":
                assert node.module in ALLOWED, f"{path.name} imports {node.module}"
                if node.module == "bem":
                    names = {a.name for a in node.names}
                    assert names <= {"Material", "InputError", "ConvergenceError"}, (path.name, names)
            if isinstance(node, ast.Import):
                for a in node.names:
                    assert a.name.split(".")[0] != "bem" or a.name in ALLOWED, f"{path.name} imports {a.name}"
