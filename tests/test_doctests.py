"""Every example in the library's docstrings runs, as part of the default suite.

Modules are found by their source (any ``>>>`` line) and imported by name, so the examples
run against the same installed package as the other tests.
"""

import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("bem", "fem_reference", "validation", "viscobem_cli", "viscobem_bench")


def _modules_with_examples():
    for top in PACKAGES:
        for path in sorted((ROOT / top).rglob("*.py")):
            if ">>> " in path.read_text():
                parts = list(path.relative_to(ROOT).with_suffix("").parts)
                yield ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = list(_modules_with_examples())


def test_the_library_has_examples():
    assert len(MODULES) >= 10 and "bem.sliding" in MODULES


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_run(name):
    module = importlib.import_module(name)
    result = doctest.testmod(
        module,
        optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
        raise_on_error=False,
        verbose=False,
        report=True,
    )
    assert result.attempted > 0, f"{name}: its examples were not collected"
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed (see the output)"
