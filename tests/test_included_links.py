"""Markdown files pulled into the documentation site by a snippet line (``--8<-- "FILE"``) are
rendered as if they lived in ``docs/``: a relative link in them must resolve from there, not from
the file's own folder. ``mkdocs build --strict`` catches a wrong one too, but only late in CI and
only with the docs extra; this check needs nothing but the files."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SNIPPET = re.compile(r'^--8<--\s+"([^"]+)"\s*$', re.MULTILINE)
LINK = re.compile(r"\]\(([^)\s]+)\)")


def _included():
    """(page in docs/, included file) for every snippet line of every page."""
    for page in sorted((ROOT / "docs").rglob("*.md")):
        for name in SNIPPET.findall(page.read_text(encoding="utf-8")):
            yield page, ROOT / name


def _broken(page, included):
    """Relative link targets of ``included`` that do not exist as seen from ``page``'s folder."""
    broken = []
    for target in LINK.findall(included.read_text(encoding="utf-8")):
        path = target.split("#", 1)[0]
        if not path or re.match(r"^[a-z]+:", path):  # anchors on the page itself, or URLs
            continue
        if not (page.parent / path).exists():
            broken.append(target)
    return broken


def test_links_in_included_files_resolve_from_the_page_that_includes_them():
    pairs = list(_included())
    assert any(inc.name == "CHANGELOG.md" for _, inc in pairs), "the changelog page no longer includes CHANGELOG.md"
    for page, included in pairs:
        broken = _broken(page, included)
        assert not broken, (
            f"{included.name} is included by {page.relative_to(ROOT)}; these links do not resolve from "
            f"{page.parent.relative_to(ROOT)}/: {broken}"
        )


def test_the_check_sees_a_link_written_from_the_repository_root(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "theory.md").write_text("# theory\n")
    page = tmp_path / "docs" / "changelog.md"
    included = tmp_path / "CHANGELOG.md"
    included.write_text("see [theory](docs/theory.md#x) and [ok](theory.md) and [web](https://a.b/c)\n")
    assert _broken(page, included) == ["docs/theory.md#x"]
