"""Fixtures of the documentation tests: the site's hooks module and its Markdown renderer
(imported by the test modules: a conftest.py here would shadow the suite's own ``conftest``).

They need the docs extra (``pip install ".[docs]"``); without it they are skipped, and CI runs
them in its documentation step.
"""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def hooks():
    pytest.importorskip("mkdocs", reason="the docs extra")
    spec = importlib.util.spec_from_file_location("viscobem_docs_hooks", ROOT / "docs" / "hooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def render():
    """Markdown -> HTML with the extensions and settings of mkdocs.yml."""
    markdown = pytest.importorskip("markdown", reason="the docs extra")
    yaml = pytest.importorskip("yaml", reason="the docs extra")
    config = yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))
    names, settings = [], {}
    for entry in config["markdown_extensions"]:
        name, options = next(iter(entry.items())) if isinstance(entry, dict) else (entry, None)
        names.append(name)
        if options:
            settings[name] = options
    return lambda text: markdown.markdown(text, extensions=names, extension_configs=settings)
