"""Generated documentation renders what the code holds: the scene keys table, cell by cell."""

import html
import re
from html.parser import HTMLParser

from docs_fixtures import hooks, render  # noqa: F401  (fixtures)


class _Cells(HTMLParser):
    """Rows of every table: a list of cell texts (tags dropped, entities decoded)."""

    def __init__(self):
        super().__init__()
        self.rows, self._row, self._cell = [], None, None

    def handle_starttag(self, tag, attrs):
        if tag == "tr":
            self._row = []
        elif tag in ("td", "th"):
            self._cell = []
            if attrs:  # attributes on a cell come from markup inside the text (attr_list)
                self._cell.append("<attributes %s>" % attrs)

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self._row.append("".join(self._cell).strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.rows.append(self._row)
            self._row = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)


def table_rows(page_html):
    parser = _Cells()
    parser.feed(page_html)
    return parser.rows


def test_scene_keys_table_shows_every_value_as_written(hooks, render):
    from viscobem_cli.scene import schema

    rows = {}
    for block in hooks._scene_keys().split("### ")[1:]:  # one heading and table per section
        heading, _, table = block.partition("\n")
        section = heading.strip().strip("`[]") if heading.startswith("`") else ""
        for r in table_rows(render(table)):
            if r and r[0] != "key":
                rows[(section, r[0])] = r[1:]
    for key in schema.KEYS:
        expected = [key.type, key.unit, hooks._toml_value(key.default) or "none", key.valid, key.help]
        got = rows.get((key.section, key.name))
        assert got == [str(x) for x in expected], f"[{key.section}] {key.name} renders as {got}"


def test_table_cell_survives_markup(hooks, render):
    """The characters that Markdown would eat: a trailing {...} (attr_list), |, *, _, <, [."""
    text = '{law = "wlf", C1} | {law = "arrhenius", E_a} *not* _em_ <b> [x](y) a\\b'
    cells = table_rows(render("| a |\n|---|\n| " + hooks.table_cell(text) + " |\n"))
    assert cells[1] == [text]


def test_page_text_has_no_stray_attribute_lists(hooks, render):
    """No hand-written page ends a paragraph or cell with {...} that attr_list would swallow."""
    from pathlib import Path

    docs = Path(hooks.DOCS)
    for page in docs.rglob("*.md"):
        rendered = render(page.read_text(encoding="utf-8"))
        found = re.findall(r"<(?:td|th|p|li)\s+(?!class|id|style|align)[^>]*>", rendered)
        assert not found, f"{page.name}: markup turned into attributes: {html.unescape(found[0])}"


def test_committed_blocks_are_what_the_code_generates(hooks):
    """Pages read right in the repository: every block made from the code is committed between its
    markers, and a block that drifts from the code (or is left empty) fails here; regenerate with
    ``python docs/hooks.py --write``."""
    from pathlib import Path

    pages = {p: p.read_text(encoding="utf-8") for p in sorted(Path(hooks.DOCS).rglob("*.md"))}
    found = {m.group(2) for text in pages.values() for m in hooks._BLOCK.finditer(text)}
    assert set(hooks.COMMITTED) | set(hooks.BUILT) <= found, "a generated block lost its markers"
    stale = [p.name for p, text in pages.items() if hooks.rewrite(text, hooks.committed_text) != text]
    assert not stale, f"stale generated blocks (python docs/hooks.py --write): {stale}"
    scenes = pages[Path(hooks.DOCS) / "scenes.md"]
    assert "| `dma` |" in scenes and "| `kind` |" in scenes  # the committed key table, not a placeholder
    emptied = scenes.replace("| `dma` |", "| `dma_file` |", 1)
    assert hooks.rewrite(emptied, hooks.committed_text) != emptied  # the check can fail


def test_the_validation_case_table_lists_every_case(hooks):
    from validation.cases import CASES

    rows = hooks._validation_cases().splitlines()[2:]
    assert [r.split("|")[1].strip().strip("`") for r in rows] == list(CASES)


def test_no_absolute_machine_path_in_generated_text(hooks):
    """Published pages name no folder of the machine that made a record (the baselines' command
    was run with an absolute --out)."""
    texts = [hooks.committed_text(name) for name in hooks.COMMITTED]
    texts += [hooks.public(hooks._validation()), hooks.public(hooks._benchmarks())]  # as on_page_markdown shows them
    assert hooks.public("source: /work/main/bem, `--out /tmp/v6`") == "source: bem, `--out v6`"
    for text in texts:
        found = re.findall(r"(?<![\w:/.])/(?:work|home|tmp|root|Users|private|var)/[^\s`)]*", text)
        assert not found, found
