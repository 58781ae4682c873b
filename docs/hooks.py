"""MkDocs hooks: pages generated from the code and from measured data.

A page holds a generated block between ``<!-- generated:NAME -->`` and ``<!-- end generated:NAME -->``.
Blocks made from the code alone (scene keys, extras, validation cases, solver settings, the
gallery's scripts, the seed figures' numbers) are committed between their markers, so that the
pages read right in the repository and on the code host; ``python docs/hooks.py --write``
regenerates them and ``tests/docs`` fails when the committed text drifts from the code. Blocks
made from a run (the latest validation report, the benchmarks' records) hold a sentence and a
link in the repository and are filled when the site is built; the gallery gains its scripts'
printed output and figures there. The blocks:

- ``<!-- generated:scene-keys -->``: every scene key the parser accepts
  (``viscobem_cli.scene.SCHEMA``), with the type, unit, default, range and meaning from the
  code's table of keys (``viscobem_cli.scene.schema.KEYS``, each cell escaped so that Markdown
  shows it as written); then the built-in scenes, read from their TOML files, each with its
  measured run time and output size from ``docs/timings.json`` (``docs/timings.py``).
- ``<!-- generated:extras -->``: the pip extras of ``pyproject.toml`` with what each adds
  (``viscobem_cli.catalog.EXTRA_PURPOSE``).
- ``<!-- generated:validation-cases -->``: one row per validation case (``validation.cases.CASES``):
  its title, the solvers compared and the reference they are compared against.
- ``<!-- generated:validation -->``: the latest validation report (``docs/validation/``:
  ``report.json`` rendered by ``validation.report``, else ``report.md``) and the quick set's
  stored baselines (``validation/baselines/quick.json``).
- ``<!-- generated:benchmarks -->``: a table per list of records in every benchmark JSON
  (``docs/benchmarks/*.json`` and the benchmark package's ``results/*.json``).
- TeX between ``$...$`` or ``$$...$$`` becomes MathML at build time, so formulas need no
  script and no network to display.
- ``<!-- generated:solver-settings -->``: the solve defaults, every field of
  ``bem.contact.ContactOptions`` and every named constant of the contact solver
  (``bem/contact/*.py``), each with its value and the reason written under it in the code.
- ``<!-- generated:gallery -->``: every ``examples/*.py``, run in a subprocess at build time,
  shown with its code, its printed output and its figure. Running them here keeps each
  figure true to the code beside it; a failing example fails the build.
"""

from __future__ import annotations

import html
import inspect
import json
import logging
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from mkdocs.structure.files import File

log = logging.getLogger("mkdocs.hooks.viscobem")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # document and run the code of this checkout
DOCS = ROOT / "docs"
EXAMPLES = ROOT / "examples"
SKIPPED_KEYS = {"issue", "targets"}  # bookkeeping of how a number was requested, not data
_gallery = {}  # example stem -> (stdout, figure site path or None)


# --- scenes --------------------------------------------------------------------------------


def _key_table():
    """{section: {key: {type, unit, default, range, doc}}} from the code's table of scene keys."""
    from viscobem_cli.scene import schema

    table = {}
    for k in schema.KEYS:
        table.setdefault(k.section, {})[k.name] = {
            "type": k.type,
            "unit": k.unit,
            "default": _toml_value(k.default),
            "range": k.valid,
            "doc": k.help,
        }
    return table


def _toml_value(v):
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


def _scene_keys():
    from viscobem_cli import scene

    described = _key_table()
    out = []
    for section, keys in scene.SCHEMA.items():
        keys = [k for k in keys if section or k not in scene.SCHEMA]  # top level: not the tables
        if not keys:
            continue
        out.append(f"### `[{section}]`\n" if section else "### Top level\n")
        info = described.get(section, {})
        out.append("| key | type | unit | default | valid values | meaning |")
        out.append("|---|---|---|---|---|---|")
        for key in _ordered(keys, info):
            d = info[key]  # the schema's key names come from the same table
            cells = [d["type"], d["unit"], d["default"] or "none", d["range"], d["doc"]]
            out.append("| " + " | ".join([f"`{key}`"] + [table_cell(c) for c in cells]) + " |")
        out.append("")
    return "\n".join(out)


_MARKUP = re.compile(r"([\\`*_{}\[\]>|#!])")


def table_cell(text):
    """Plain text as a Markdown table cell that renders as written: ``|`` would end the cell, a
    trailing ``{...}`` would become HTML attributes (attr_list), ``*``/``_`` emphasis, ``<`` a tag."""
    return _MARKUP.sub(r"\\\1", str(text)).replace("<", "&lt;")


def _ordered(keys, info):
    """Keys in the order the descriptions list them, then any others alphabetically."""
    known = [k for k in info if k in keys]
    return known + sorted(set(keys) - set(known))


def _measured_runs():
    """The recorded runs of docs/timings.json (see docs/timings.py), by key."""
    path = DOCS / "timings.json"
    return json.loads(path.read_text(encoding="utf-8")).get("runs", {}) if path.is_file() else {}


def _builtin_scenes():
    from viscobem_cli import scene

    sys.path.insert(0, str(DOCS))
    try:
        import timings
    finally:
        sys.path.remove(str(DOCS))
    runs = _measured_runs()
    out = []
    for name in scene.builtin_scenes():
        text = (scene.SCENE_DIR / f"{name}.toml").read_text(encoding="utf-8")
        run = runs.get(f"run_{name}")
        took = ""
        if run:
            took = f": [{timings.time_text(run['wall_s'])} on 2 cores](timings.md#run_{name})"
            if run.get("output_bytes"):
                took += f", [{timings.size_text(run['output_bytes'])}](timings.md#run_{name}) of output"
        out.append(f"### `{name}`\n\n`viscobem run {name}`{took}\n\n```toml\n{text.rstrip()}\n```\n")
    return "\n".join(out)


def _extras():
    """The pip extras of pyproject.toml, each with what it adds (``viscobem_cli.catalog``)."""
    from viscobem_cli.catalog import EXTRA_PURPOSE

    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]
    rows = ["| extra | install | what it adds |", "|---|---|---|"]
    for name in extras:
        rows.append(f'| `{name}` | `pip install ".[{name}]"` | {EXTRA_PURPOSE.get(name, "")} |')
    return "\n".join(rows) + "\n"


# --- JSON records ----------------------------------------------------------------------------


def _fmt(v):
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.4g}"
    if v is None:
        return ""
    return str(v).replace("|", "\\|").replace("\n", " ")


def _flatten(d, prefix=""):
    flat = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            flat.update(_flatten(v, key + "."))
        elif isinstance(v, (list, tuple)):
            if len(v) <= 4 and all(isinstance(x, (int, float, str)) for x in v):
                flat[key] = ", ".join(_fmt(x) for x in v)
        else:
            flat[key] = v
    return flat


def _table(rows):
    rows = [_flatten(r) for r in rows]
    cols = []
    for r in rows:
        for k, v in r.items():
            if k not in cols and not (isinstance(v, str) and (len(v) > 60 or v.startswith("/"))):
                cols.append(k)
    common = {}
    if len(rows) > 2:  # a column with one value throughout is stated once, above the table
        common = {c: rows[0].get(c) for c in cols if all(r.get(c) == rows[0].get(c) for r in rows)}
        cols = [c for c in cols if c not in common] or cols
    lines = (
        ["Same in every row: " + "; ".join(f"{c} = {_fmt(v)}" for c, v in common.items()) + "\n"]
        if common
        else []
    )
    lines += ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    lines += ["| " + " | ".join(_fmt(r.get(c)) for c in cols) + " |" for r in rows]
    return "\n".join(lines)


def _columns(d):
    """Rows of a table stored by columns (a dict of equal-length lists), else None."""
    lists = {k: v for k, v in d.items() if isinstance(v, list) and v}
    lengths = {len(v) for v in lists.values()}
    if len(lists) < 2 or len(lengths) != 1:
        return None
    scalars = {k: v for k, v in d.items() if not isinstance(v, (list, dict))}
    n = lengths.pop()
    return [dict(scalars, **{k: v[i] for k, v in lists.items()}) for i in range(n)]


def _record(path, title):
    data = json.loads(path.read_text(encoding="utf-8"))
    rel = path.relative_to(ROOT)
    out = [f"### {title}\n", f"From `{rel}`.\n"]
    if not isinstance(data, dict):
        data = {"records": data}
    scalars = {
        k: v for k, v in data.items() if k not in SKIPPED_KEYS and not isinstance(v, (dict, list))
    }
    if scalars:
        out.append(", ".join(f"{k}: {_fmt(v)}" for k, v in scalars.items()) + "\n")
    xi = next(
        (v["xi"] for v in data.values() if isinstance(v, dict) and isinstance(v.get("xi"), list)),
        None,
    )
    for key, value in data.items():
        if key in SKIPPED_KEYS:
            continue
        if isinstance(value, list) and value and all(isinstance(r, dict) for r in value):
            body = _table(value)
            fold = "???" if len(value) > 25 else "!!!"
            out.append(f'{fold} note "{key} ({len(value)} rows)"\n')
            out.append("\n".join("    " + line for line in body.splitlines()) + "\n")
        elif isinstance(value, list) and value and all(isinstance(r, str) for r in value):
            out.append(f"**{key}**: " + "; ".join(value) + "\n")
        elif isinstance(value, dict) and _columns(value):
            rows = _columns(value)
            if xi and "xi" not in value and len(xi) == len(rows):  # the sweep's speeds, shared
                rows = [{"xi": x, **r} for x, r in zip(xi, rows)]
            body = _table(rows)
            out.append(f'!!! note "{key}"\n')
            out.append("\n".join("    " + line for line in body.splitlines()) + "\n")
        elif isinstance(value, dict) and value:
            flat = _flatten(value)
            if flat and len(flat) <= 40:
                out.append(
                    f"**{key}**: "
                    + "; ".join(
                        f"{k} = {_fmt(v)}"
                        for k, v in flat.items()
                        if not (isinstance(v, str) and len(v) > 200)
                    )
                    + "\n"
                )
    return "\n".join(out)


def _benchmarks():
    paths = sorted((DOCS / "benchmarks").glob("*.json")) + sorted(
        ROOT.glob("*bench*/results/*.json")
    )
    if not paths:
        return "No benchmark records are present in this build.\n"
    return "\n".join(_record(p, p.stem.replace("_", " ")) for p in paths)


def _validation():
    out = []
    report_json, report_md = DOCS / "validation" / "report.json", DOCS / "validation" / "report.md"
    if report_json.is_file():
        from validation import report

        with tempfile.TemporaryDirectory() as tmp:
            target = Path(tmp) / "report.md"
            report.write_markdown(json.loads(report_json.read_text(encoding="utf-8")), target)
            text = target.read_text(encoding="utf-8")
    elif report_md.is_file():
        text = report_md.read_text(encoding="utf-8")
    else:
        text = "No full validation report is present in this build.\n"
    out.append(_demote(text))
    baselines = ROOT / "validation" / "baselines" / "quick.json"
    if baselines.is_file():
        data = json.loads(baselines.read_text(encoding="utf-8"))
        out.append("## Stored baselines of the quick set\n")
        out.append(
            f"From `validation/baselines/quick.json`. Comparison rule: {data.get('comparison', {}).get('rule', '')}\n"
        )
        prov = data.get("provenance", {})
        command = re.sub(r"--out \S+", "--out DIR", str(prov.get("command", "")))  # not the machine's folder
        out.append(f"Made by `{command}` on {prov.get('date', '')}.\n")
        for case, values in sorted(data.get("values", {}).items()):
            rows = [{"metric": k, "value": v} for k, v in values.items()]
            out.append(f'??? note "{case} ({len(rows)} values)"\n')
            out.append("\n".join("    " + line for line in _table(rows).splitlines()) + "\n")
    return "\n".join(out)


def _validation_cases():
    """One row per validation case, from the registry: what it compares with what."""
    from validation.cases import CASES

    rows = ["| case | what it checks | solvers under test | against |", "|---|---|---|---|"]
    for name, case in CASES.items():
        tested = ", ".join(s for s in case.solvers if s != case.reference)
        rows.append(f"| `{name}` | {table_cell(case.description)} | {tested} | {table_cell(case.reference)} |")
    return "\n".join(rows) + "\n"


def _demote(markdown):
    """Shift headings one level down, so a report's title nests under the page's."""
    return (
        "\n".join("#" + line if line.startswith("#") else line for line in markdown.splitlines())
        + "\n"
    )


# --- gallery ---------------------------------------------------------------------------------


GALLERY_ORDER = [
    "friction_curve",
    "hunter_cylinder",
    "sphere_sliding",
    "westergaard",
    "material_forms",
    "temperature_shift",
    "anisotropy",
]


def _scripts():
    """The examples: those named in GALLERY_ORDER first, in that order, then the others."""
    scripts = [p for p in EXAMPLES.glob("*.py") if not p.name.startswith("_")]
    rank = {name: i for i, name in enumerate(GALLERY_ORDER)}
    return sorted(scripts, key=lambda p: (rank.get(p.stem, len(rank)), p.stem))


def _run_example(script, out_dir):
    env = dict(
        os.environ,
        MPLBACKEND="Agg",
        PYTHONPATH=os.pathsep.join(
            [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
        ),
    )
    out_dir.mkdir(parents=True)
    run = subprocess.run(  # run from an empty folder, as a user who copied the script would
        [sys.executable, str(script), str(out_dir)],
        cwd=out_dir,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    return script, run


def _gallery_files(config, files):
    scripts = _scripts()
    with tempfile.TemporaryDirectory() as tmp, ThreadPoolExecutor(max_workers=2) as pool:
        runs = list(pool.map(lambda s: _run_example(s, Path(tmp) / s.stem), scripts))
        for script, run in runs:
            if run.returncode != 0:
                log.error("example %s failed:\n%s", script.name, run.stderr[-2000:])
                _gallery[script.stem] = (run.stdout + run.stderr, None)
                continue
            figure = Path(tmp) / script.stem / f"{script.stem}.png"
            site_path = f"gallery_figures/{script.stem}.png" if figure.is_file() else None
            if site_path:
                files.append(File.generated(config, site_path, content=figure.read_bytes()))
            _gallery[script.stem] = (run.stdout, site_path)


def _gallery_markdown(with_runs=True):
    """Each example's title, text, command and code; with ``with_runs``, its printed output and
    figure from running it at build time (the committed page has a line saying where they are)."""
    out = []
    for script in _scripts():
        stdout, figure = _gallery.get(script.stem, ("", None))
        source = script.read_text(encoding="utf-8")
        doc = source.split('"""')[1].strip() if source.startswith('"""') else ""
        title, _, rest = doc.partition("\n")
        out.append(f"## {title.rstrip('.')}\n\n{rest.strip()}\n")
        out.append(f"`python examples/{script.name} [OUTDIR]`\n")
        out.append(f'```python title="examples/{script.name}"\n{source.rstrip()}\n```\n')
        if not with_runs:
            out.append("Running it prints its numbers and draws its figure; the built site shows both.\n")
            continue
        if stdout:
            out.append(f"Output:\n\n```text\n{stdout.rstrip()}\n```\n")
        if figure:
            out.append(f"![{title}]({figure})\n")
    return "\n".join(out)


# --- MkDocs events ---------------------------------------------------------------------------


def on_files(files, config):
    _gallery_files(config, files)
    return files


_MATH = re.compile(r'<(span|div) class="arithmatex">\\[(\[](.*?)\\[)\]]</\1>', re.DOTALL)


def _mathml(match):
    from latex2mathml.converter import convert

    tag, tex = match.group(1), html.unescape(match.group(2)).strip()
    return convert(tex, display="block" if tag == "div" else "inline")


_ROLE = re.compile(r":(?:mod|func|class|meth|attr|data|obj|exc):(?=<code>)")


def on_page_content(content, page, config, files):
    """TeX (from pymdownx.arithmatex) to MathML, which browsers render without scripts; the
    Sphinx roles of numpydoc docstrings (``:func:`x` ``) shown as plain code."""
    return _ROLE.sub("", _MATH.sub(_mathml, content))


_API = re.compile(r"^::: (bem\.[A-Za-z_]\w*)$", re.MULTILINE)


def _defining_path(match):
    """``::: bem.NAME`` as the path where NAME is defined: the package may re-export its public
    names lazily (module ``__getattr__``), which static analysis cannot follow."""
    import importlib

    name = match.group(1)
    try:
        obj = getattr(importlib.import_module("bem"), name.split(".", 1)[1])
    except AttributeError:
        return match.group(0)
    path = obj.__name__ if inspect.ismodule(obj) else f"{obj.__module__}.{obj.__qualname__}"
    return f"::: {path}"


# --- solver settings --------------------------------------------------------------------------


def _documented_names(path, scope=None):
    """``[(name, value source, docstring)]`` of the assignments in ``path`` (at module level, or in
    the class ``scope``) that have a string literal right under them."""
    import ast

    tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    body = tree.body
    if scope is not None:
        body = next(n.body for n in tree.body if isinstance(n, ast.ClassDef) and n.name == scope)
    out = []
    for node, after in zip(body, body[1:]):
        target = node.target if isinstance(node, ast.AnnAssign) else getattr(node, "targets", [None])[0]
        doc = after.value.value if isinstance(after, ast.Expr) and isinstance(after.value, ast.Constant) else None
        if isinstance(target, ast.Name) and isinstance(doc, str) and node.value is not None:
            out.append((target.id, ast.get_source_segment(path.read_text(encoding="utf-8"), node.value), doc))
    return out


def _one_line(doc):
    """A docstring on one table line: roles and double backquotes as plain code, pipes escaped."""
    text = re.sub(r":\w+:`~?([^`]+)`", r"`\1`", " ".join(doc.split()))
    return text.replace("``", "`").replace("|", "\\|")


def _solver_settings():
    """Tables of the solve defaults, the options a user may set, and the solver's constants."""
    contact = ROOT / "bem" / "contact"
    defaults = [(n, v, d) for n, v, d in _documented_names(contact / "options.py") if n in ("RTOL", "MAXITER")]
    rows = ["| name | default | meaning |", "|---|---|---|"]
    rows += [f"| `{n}` | `{v}` | {_one_line(d)} |" for n, v, d in defaults]
    out = ["**Solve defaults** (`bem.contact.options`; `bem.solve`, `bem.friction_curve` and the scene's "
           "`[solver]` table use them):", "", *rows, ""]
    rows = ["| option | default | what it trades |", "|---|---|---|"]
    rows += [f"| `{n}` | `{v}` | {_one_line(d)} |" for n, v, d in _documented_names(contact / "options.py", "ContactOptions")]
    out += ["**`bem.contact.ContactOptions`**, what a user may set:", "", *rows, ""]
    rows = ["| constant | value | module | reason |", "|---|---|---|---|"]
    for path in sorted(contact.glob("*.py")):
        for n, v, d in _documented_names(path):
            if n.isupper() and n not in ("RTOL", "MAXITER"):
                rows.append(f"| `{n}` | `{v}` | `bem.contact.{path.stem}` | {_one_line(d)} |")
    out += ["**Constants of the contact solver**, each in the module that uses it:", "", *rows, ""]
    return "\n".join(out)


# blocks made from the code alone: committed between their markers (``--write``), checked by tests/docs
COMMITTED = {
    "scene-keys": lambda: _scene_keys() + "\n## Built-in scenes\n\n" + _builtin_scenes(),
    "extras": _extras,
    "validation-cases": _validation_cases,
    "solver-settings": _solver_settings,
    "seed-figures": lambda: _record(DOCS / "figures" / "seed_figures_summary.json", "Numbers behind the figures"),
    "gallery": lambda: _gallery_markdown(with_runs=False),
}
# blocks made from runs, filled at build time; in the repository, a sentence and a link
BUILT = {
    "validation": (
        _validation,
        "The built site (`mkdocs build`, the docs extra) shows the latest full report here, from the run CI "
        "has just made; `viscobem validate --out DIR` writes the same report as `DIR/report.html`.",
    ),
    "benchmarks": (
        _benchmarks,
        "The built site (`mkdocs build`, the docs extra) shows every record here as tables; the records "
        "themselves are the JSON files in [`docs/benchmarks/`](benchmarks/periodic.json).",
    ),
    "gallery": (_gallery_markdown, None),
}
_MACHINE_PATH = re.compile(r"(?<![\w:/.~])/(?:work|home|tmp|root|Users|private|var|opt|mnt)/[^\s`)|\"',;]*")


def public(text):
    """``text`` without the absolute folders of the machine that made a record (a benchmark's
    source checkout, a run's output folder): each is cut to its last component."""
    return _MACHINE_PATH.sub(lambda m: m.group(0).rstrip("/").rsplit("/", 1)[-1], text)


_BLOCK = re.compile(r"(<!-- generated:([\w-]+) -->\n)(.*?)(<!-- end generated:\2 -->)", re.DOTALL)


def committed_text(name):
    """The text committed between the markers of block ``name``."""
    if name in COMMITTED:
        return public(COMMITTED[name]()).rstrip("\n") + "\n"
    return BUILT[name][1] + "\n"


def rewrite(markdown, render):
    """``markdown`` with the text between every pair of markers replaced by ``render(name)``."""

    def block(match):
        return match.group(1) + render(match.group(2)) + match.group(4)

    return _BLOCK.sub(block, markdown)


def on_page_markdown(markdown, page, config, files):
    markdown = _API.sub(_defining_path, markdown)

    def built(name):
        return public(BUILT[name][0]()) if name in BUILT else committed_text(name)

    return rewrite(markdown, built)


def main(argv=None):
    """``python docs/hooks.py --write``: regenerate the committed blocks of every page;
    ``--check``: exit 1 naming the pages whose committed blocks differ from the code."""
    args = sys.argv[1:] if argv is None else argv
    stale = []
    for page in sorted(DOCS.rglob("*.md")):
        text = page.read_text(encoding="utf-8")
        new = rewrite(text, committed_text)
        if new != text:
            stale.append(page.relative_to(ROOT).as_posix())
            if "--write" in args:
                page.write_text(new, encoding="utf-8")
    if stale and "--write" not in args:
        print("stale generated blocks (python docs/hooks.py --write): " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
