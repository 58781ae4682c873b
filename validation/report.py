"""Validation reports: ``report.json`` (every number), ``report.md`` (a quick look), a
self-contained ``report.html`` and every plot as its own PNG under ``plots/``.

Both readable reports answer first: one row per case (what is compared with what, pass or fail,
its worst check as value / tolerance) under a sentence saying how the tolerances were set
(:mod:`validation.explain`); then, in the HTML, per case the pressure overlays with their errors,
the sweeps from each solver and the timings, each captioned with the checks it illustrates; then
every check with its plain name, identifier, tolerance basis and reason.

``report.html`` works offline and alone: the pressure overlays are drawn in the page from their
data (inline SVG by ``report_plot.js``, inlined: drag to zoom, double-click to reset), because
the differences that matter sit in a leading-edge layer a few cells wide; the other plots are
PNG embedded as base64. Tick labels never overlap: :func:`declutter` drops minor labels, then
thins major ones, until their boxes are apart (checked by :func:`overlapping_ticks`)."""

from __future__ import annotations

import base64
import html
import io
import json
import math
import re
from pathlib import Path

import numpy as np

from .explain import basis, basis_sentence, illustrated, metric_name, worst_by_metric, worst_check

__all__ = [
    "write_reports",
    "write_json",
    "write_markdown",
    "write_html",
    "plots",
    "write_pngs",
    "declutter",
    "overlapping_ticks",
    "overlay_spec",
]


def _fmt(v):
    if v is None:
        return "-"
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return f"{v:.3g}" if v != 0 else "0"
    return str(v)


def write_json(record, path):
    Path(path).write_text(json.dumps(record, indent=1, allow_nan=True))


def _status(c):
    return {"passed": "PASS", "failed": "FAIL", "error": "ERROR"}[c["status"]]


def _check_status(k):
    return "PASS" if k["passed"] and k["judged"] else ("FAIL" if not k["passed"] else "info")


def _worst(case):
    """Per (metric, solver): the worst check (:func:`validation.explain.worst_by_metric`)."""
    return [k for ks in worst_by_metric(case["checks"]).values() for k in ks]


def compared(case):
    """What a case compares with what: ``"bem-periodic, fem against exact"``."""
    tested = [s for s in case["solvers"] if s != case.get("reference")]
    return f"{', '.join(tested)} against {case.get('reference') or 'each other'}"


def case_rows(record):
    """One row per case: ``(name, case, worst check or None, passed/judged count, info count)``."""
    rows = []
    for name, c in record["cases"].items():
        checks = c.get("checks", [])
        judged = [k for k in checks if k["judged"]]
        passed = sum(k["passed"] for k in judged)
        rows.append((name, c, worst_check(checks), f"{passed}/{len(judged)}", len(checks) - len(judged)))
    return rows


def _worst_text(k):
    if k is None:
        return "-", "-"
    return f"{metric_name(k['metric'])} ({k['solver']}, {k['label']})", f"{_fmt(k['value'])} / {_fmt(k['tolerance'])}"


def write_markdown(record, path, baseline=None):
    env, s = record["environment"], record["summary"]
    lines = [
        f"# viscobem validation ({'quick' if record['quick'] else 'full'} set)",
        "",
        f"Commit `{env['commit'][:12]}`{' (dirty)' if env.get('dirty') else ''}, {env['date']}, {env['machine']}, "
        f"Python {env['python']}; {record['seconds']:.1f} s in total.",
        "",
        f"**{s['passed']} of {s['cases']} cases passed** ({s['checks']} checks"
        f"{', failing: ' + ', '.join(s['failed']) if s['failed'] else ''}).",
        "",
    ]
    if baseline is not None:
        lines += [
            f"Baseline comparison ({baseline['path']}): "
            + (
                "all values within tolerance."
                if baseline["ok"]
                else f"**{len(baseline['regressions'])} regressions**, {len(baseline['missing'])} missing values."
            ),
            "",
        ]
    lines += [
        basis_sentence(record),
        "",
        "| case | compares | status | checks passed | worst check | value / tolerance | time (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, c, k, count, _ in case_rows(record):
        what, ratio = _worst_text(k)
        lines.append(f"| `{name}` | {compared(c)} | {_status(c)} | {count} | {what} | {ratio} | {c['seconds']:.1f} |")
    for name, c in record["cases"].items():
        lines += ["", f"## `{name}`: {c['title']}", "", c["description"], ""]
        if c["status"] == "error":
            lines += [f"**Error:** `{c['error']}`", ""]
            continue
        lines += [
            "Worst value of each metric over the points (tolerance, its basis and why):",
            "",
            "| metric | solver | at | value | tolerance | status | basis | why |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for k in _worst(c):
            lines.append(
                f"| {metric_name(k['metric'])} (`{k['metric']}`) | {k['solver']} | {k['label']} | {_fmt(k['value'])} "
                f"| {_fmt(k['tolerance'])} | {_check_status(k)} | {basis(k)} | {k['why']} |"
            )
        lines += ["", "| solver | point | time (s) | peak memory (MiB) | detail |", "|---|---|---|---|---|"]
        for r in c["runs"]:
            lines.append(f"| {r['solver']} | {r['label']} | {r['seconds']:.3g} | {r['peak_mib']:.3g} | {r['detail']} |")
    lines += sensitivity_markdown(record)
    Path(path).write_text("\n".join(lines) + "\n")


def _sensitivity_rows(record):
    """``(cases x solvers) x perturbations`` cells: ``(row, {perturbation: (text, css)})``."""
    entries = record.get("sensitivity") or []
    perts = list(dict.fromkeys(e["perturbation"] for e in entries))
    rows = {}
    for e in entries:
        if e.get("outcome") == "error":
            cell = ("RAISED (not a detection): " + ", ".join(e["by"]), "FAIL")
        elif e["detected"]:
            cell = ("caught by " + ", ".join(e["by"]), "PASS")
        elif e["required"]:
            cell = ("MISSED", "FAIL")
        else:
            cell = ("no effect on this solver's inputs", "info")
        rows.setdefault((e["case"], e["solver"]), {})[e["perturbation"]] = cell
    return perts, rows


def sensitivity_markdown(record):
    perts, rows = _sensitivity_rows(record)
    if not rows:
        return []
    lines = [
        "",
        "## Sensitivity: deliberately wrong inputs",
        "",
        "| case | solver | " + " | ".join(perts) + " |",
        "|---|---|" + "---|" * len(perts),
    ]
    for (case, solver), cells in rows.items():
        lines.append(f"| `{case}` | {solver} | " + " | ".join(cells.get(p, ("-", ""))[0] for p in perts) + " |")
    return lines


def sensitivity_html(record):
    perts, rows = _sensitivity_rows(record)
    if not rows:
        return []
    e = html.escape
    parts = [
        "<h2 id='sensitivity'>Sensitivity: deliberately wrong inputs</h2><p>Each case rerun with the "
        "solvers under test given one wrong input (references keep the true one). A cell names the checks "
        "that failed; MISSED means the wrong input passed every check, RAISED that the case raised an exception "
        "under it (its own outcome: no check measured the error).</p><table><tr><th>case</th>"
        "<th>solver</th>" + "".join(f"<th>{e(p)}</th>" for p in perts) + "</tr>"
    ]
    for (case, solver), cells in rows.items():
        tds = "".join(f"<td class='{cells[p][1]}'>{e(cells[p][0])}</td>" if p in cells else "<td>-</td>" for p in perts)
        parts.append(f"<tr><td>{e(case)}</td><td>{e(solver)}</td>{tds}</tr>")
    parts.append("</table>")
    return parts


# ----------------------------------------------------------------------------- plots
def _figures(case):
    """The case's matplotlib figures: ``[(title, figure, kind), ...]``, kind ``overlay``,
    ``sweep`` or ``timings``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figs = []
    for prof in case["profiles"]:
        # plotted in MPa and mm (the JSON keeps SI); the exact curve is a line, computed ones markers
        fig, (ax, ae) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True, gridspec_kw=dict(height_ratios=[3, 2]))
        for name, (x, p) in prof["curves"].items():
            exact = name == prof["reference"]
            style = dict(lw=1.6, color="k") if exact else dict(marker=".", ms=3, lw=0.6, alpha=0.85)
            ax.plot(np.asarray(x) * 1e3, np.asarray(p) / 1e6, label=name, **style)
        ax.set_ylabel("pressure (MPa)")
        ax.legend(fontsize=8)
        ax.set_title(prof["label"], fontsize=9)
        for name, (x, e) in prof["errors"].items():
            ae.plot(
                np.asarray(x) * 1e3,
                np.asarray(e) / 1e6,
                marker=".",
                ms=3,
                lw=0.8,
                label=f"{name} - {prof['reference']}",
            )
        ae.axhline(0, color="k", lw=0.5)
        ae.set_ylabel("pressure error (MPa)")
        ae.set_xlabel(prof["xlabel"].replace("(m)", "(mm)"))
        ae.legend(fontsize=8)
        fig.subplots_adjust(left=0.13, right=0.97, top=0.93, bottom=0.1, hspace=0.08)
        figs.append((f"pressure: {prof['label']}", fig, "overlay"))
    for sw in case["sweeps"]:
        fig, ax = plt.subplots(figsize=(7, 4))
        for name, (x, y) in sw["curves"].items():
            # a dense (exact) curve is a line; computed points are markers only, never joined
            # by straight lines that would cut across the exact curve between them
            dense = len(x) > 12
            ax.plot(x, y, label=name, **(dict(lw=1.5, color="k") if dense else dict(marker="o", ms=5, ls="none")))
        ax.set_xscale("log" if sw["logx"] else "linear")
        ax.set_yscale("log" if sw["logy"] else "linear")
        ax.set_xlabel(sw["xlabel"])
        ax.set_ylabel(sw["ylabel"])
        ax.set_title(sw["title"], fontsize=9)
        ax.legend(fontsize=8)
        fig.subplots_adjust(left=0.13, right=0.97, top=0.92, bottom=0.13)
        figs.append((sw["title"], fig, "sweep"))
    if case["runs"]:
        height = 0.35 * len(case["runs"]) + 1.2
        fig, ax = plt.subplots(figsize=(7, height))
        labels = [f"{r['solver']} {r['label']}" for r in case["runs"]]
        ax.barh(range(len(labels)), [r["seconds"] for r in case["runs"]])
        ax.set_yticks(range(len(labels)), labels, fontsize=7)
        ax.set_xscale("log")
        ax.set_xlabel("wall time (s)")
        ax.invert_yaxis()
        fig.subplots_adjust(left=0.4, right=0.97, top=1 - 0.15 / height, bottom=0.65 / height)
        figs.append(("timings", fig, "timings"))
    return figs


def overlapping_ticks(fig):
    """Pairs of tick labels whose boxes overlap, as ``(axis, text, text)``; draws the figure."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    pairs = []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            labels = [t for t in axis.get_ticklabels(which="both") if t.get_visible() and t.get_text()]
            boxes = [t.get_window_extent(renderer) for t in labels]
            pairs += [
                (axis.axis_name, labels[i].get_text(), labels[j].get_text())
                for i in range(len(boxes))
                for j in range(i + 1, len(boxes))
                if boxes[i].overlaps(boxes[j])
            ]
    return pairs


def declutter(fig, attempts=4):
    """Remove tick labels until none overlap: first the minor labels of a crowded axis (a log
    axis over less than two decades labels its minor ticks), then fewer major ticks."""
    import matplotlib.ticker as mticker

    for _ in range(attempts):
        crowded = {name for name, _, _ in overlapping_ticks(fig)}
        if not crowded:
            return fig
        for ax in fig.axes:
            for axis in (ax.xaxis, ax.yaxis):
                if axis.axis_name not in crowded:
                    continue
                if any(t.get_text() for t in axis.get_ticklabels(which="minor")):
                    axis.set_minor_formatter(mticker.NullFormatter())
                elif axis.get_scale() == "log":
                    axis.set_major_locator(mticker.LogLocator(numticks=max(2, len(axis.get_majorticklocs()) // 2)))
                else:
                    axis.set_major_locator(mticker.MaxNLocator(nbins=max(2, len(axis.get_majorticklocs()) // 2)))
    return fig


def plots(case):
    """PNG bytes of the case's figures, tick labels decluttered: ``[(title, png), ...]``."""
    import matplotlib.pyplot as plt

    out = []
    for title, fig, _ in _figures(case):  # fixed margins: tight_layout costs a third of the plotting time
        declutter(fig)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=90)
        plt.close(fig)
        out.append((title, buf.getvalue()))
    return out


def _slug(text):
    return re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_")[:60] or "plot"


def write_pngs(record, out_dir):
    """Every plot of every case as its own PNG under ``out_dir/plots/``; returns
    ``{case: [(title, png, relative path), ...]}`` (the same figures the HTML embeds)."""
    folder = Path(out_dir) / "plots"
    figures = {}
    for name, c in record["cases"].items():
        figures[name] = []
        if c["status"] == "error":
            continue
        for k, (title, png) in enumerate(plots(c)):
            path = folder / f"{name}_{k:02d}_{_slug(title)}.png"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(png)
            figures[name].append((title, png, path.relative_to(out_dir).as_posix()))
    return figures


def _round(values, digits=6):
    return [float(f"{v:.{digits}g}") if math.isfinite(v) else None for v in np.asarray(values, float)]


def overlay_spec(prof):
    """The data of one pressure overlay for the page's zoomable plot (mm, MPa)."""
    curves = [
        {"name": n, "x": _round(np.asarray(x) * 1e3), "y": _round(np.asarray(p) / 1e6), "exact": n == prof["reference"]}
        for n, (x, p) in prof["curves"].items()
    ]
    errors = [
        {"name": f"{n} - {prof['reference']}", "x": _round(np.asarray(x) * 1e3), "y": _round(np.asarray(e) / 1e6)}
        for n, (x, e) in prof["errors"].items()
    ]
    return {
        "title": prof["label"],
        "xlabel": prof["xlabel"].replace("(m)", "(mm)"),
        "panels": [
            {"ylabel": "pressure (MPa)", "series": curves},
            {"ylabel": "pressure error (MPa)", "series": errors, "zero": True},
        ],
    }


_CSS = (
    "body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}table{border-collapse:collapse;"
    "margin:0.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}.PASS{background:#d4f4d4}"
    ".FAIL,.ERROR{background:#f8c8c8}.info{background:#eee}img{max-width:100%}figure{margin:1em 0}"
    "figcaption{font-size:12px;color:#555}.vb-zoom svg{user-select:none;cursor:crosshair;max-width:860px}"
    ".vb-frame{fill:none;stroke:#444;stroke-width:1}.vb-grid{stroke:#e4e4e4;stroke-width:1}"
    ".vb-zero{stroke:#000;stroke-width:0.6}.vb-tick{font-size:11px;fill:#222}.vb-label{font-size:12px;fill:#222}"
    ".vb-title{font-size:13px;fill:#222}.vb-exact{fill:none;stroke-width:1.6}.vb-line{fill:none;stroke-width:0.7;"
    "opacity:0.85}.vb-dots{fill:none;stroke-width:3.5;stroke-linecap:round;opacity:0.85}"
    ".vb-band{fill:#1f77b4;opacity:0.15}.vb-legend{font-size:12px;max-width:860px}.vb-key{cursor:pointer;"
    "margin-right:1em;white-space:nowrap}.vb-key i{display:inline-block;width:12px;height:3px;margin-right:4px;"
    "vertical-align:middle}.vb-off{opacity:0.35;text-decoration:line-through}"
)
_SCRIPT = Path(__file__).with_name("report_plot.js")


def _overlay_html(name, k, prof, png_path, checks=""):
    """A zoomable overlay: the data as JSON beside the figure, drawn by report_plot.js, captioned
    with ``checks``, the checks it illustrates."""
    e = html.escape
    data = json.dumps(overlay_spec(prof), allow_nan=False, separators=(",", ":")).replace("</", "<\\/")
    link = f" <a href='{e(png_path)}'>PNG</a>" if png_path else ""
    return (
        f"<figure class='vb-zoom vb-plot' id='{e(name)}-overlay-{k}'><script type='application/json'>{data}</script>"
        f"<figcaption>pressure: {e(prof['label'])}. {e(checks)} Drag across the plot to zoom into an x range, "
        f"double-click to reset; click a legend entry to hide it.{link}</figcaption></figure>"
    )


def _plot_caption(case, title, solvers, kind):
    """The checks a plot illustrates, as text: each metric's worst value / tolerance per solver."""
    if kind == "timings":
        return "Wall time of each solver call: cost, not judged."
    rows = worst_by_metric(illustrated(case, title, solvers, kind))
    if not rows:
        return "No check is made on this plot's quantity: it is shown for context."
    parts = []
    for metric, ks in rows.items():
        vals = ", ".join(
            f"{k['solver']} {_fmt(k['value'])} / {_fmt(k['tolerance']) if k['judged'] else 'info'}" for k in ks
        )
        parts.append(f"{metric_name(metric)}: {vals}")
    return "Checks shown (worst value / tolerance): " + "; ".join(parts) + "."


def _figure_kinds(case, count):
    """``(title, solvers, kind)`` of a case's figures in the order :func:`_figures` makes them."""
    kinds = [(p["label"], list(p["curves"]), "overlay") for p in case["profiles"]]
    kinds += [(sw["title"], list(sw["curves"]), "sweep") for sw in case["sweeps"]]
    kinds += [("timings", [], "timings")] * (count - len(kinds))
    return kinds


def _summary_html(record):
    e = html.escape
    parts = [
        "<table id='summary'><tr><th>case</th><th>compares</th><th>status</th><th>checks passed</th>"
        "<th>worst check</th><th>value / tolerance</th></tr>"
    ]
    for name, c, k, count, info in case_rows(record):
        st = _status(c)
        what, ratio = _worst_text(k)
        if c["status"] == "error":
            what, ratio = f"raised: {c['error']}", "-"
        extra = f" (+{info} info)" if info else ""
        parts.append(
            f"<tr class='case'><td><a href='#{e(name)}'>{e(name)}</a><br><small>{e(c['title'])}</small></td>"
            f"<td>{e(compared(c))}</td><td class='{st}'>{st}</td><td>{count}{extra}</td><td>{e(what)}</td>"
            f"<td>{e(ratio)}</td></tr>"
        )
    parts.append("</table>")
    return parts


def _checks_html(record):
    """The full table: per case, the worst check of each metric and solver, with its basis and why."""
    e = html.escape
    parts = [
        "<h2 id='checks'>All checks</h2><p>Per case, the worst value of each metric for each solver over "
        "the points; <i>basis</i> is how the tolerance was set (margin: a regression margin over the error "
        "measured when it was set; bound: from the discretisation or the physics; info: reported, not judged). "
        "Each case's section below lists every point.</p>"
        "<table id='all-checks'><tr><th>case</th><th>metric</th><th>solver</th><th>worst at</th><th>value</th>"
        "<th>tolerance</th><th>status</th><th>basis</th><th>why</th></tr>"
    ]
    for name, c in record["cases"].items():
        if c["status"] == "error":
            parts.append(f"<tr><td>{e(name)}</td><td colspan=7>{e(c['error'])}</td><td class='ERROR'>ERROR</td></tr>")
        for k in _worst(c):
            st = _check_status(k)
            parts.append(
                f"<tr><td><a href='#{e(name)}'>{e(name)}</a></td><td>{e(metric_name(k['metric']))}<br>"
                f"<code>{e(k['metric'])}</code></td><td>{e(k['solver'])}</td><td>{e(k['label'])}</td>"
                f"<td>{_fmt(k['value'])}</td><td>{_fmt(k['tolerance'])}</td><td class='{st}'>{st}</td>"
                f"<td>{basis(k)}</td><td>{e(k['why'])}</td></tr>"
            )
    parts.append("</table>")
    return parts


def write_html(record, path, baseline=None, figures=None, with_plots=True):
    """``figures[name] = [(title, png[, path]), ...]`` (default: :func:`plots` of each case, unless
    ``with_plots`` is false: then the report holds the tables only). A case's pressure overlays
    (its first figures, one per profile) are drawn zoomable from their data; ``path``, the
    figure's PNG file relative to the report, is linked under each figure.

    The page answers first: the summary sentence, how the tolerances were set, one row per case;
    then the plots of each case, each captioned with the checks it shows; then every check."""
    e = html.escape
    env, s = record["environment"], record["summary"]
    verdict = "all passed" if s["passed"] == s["cases"] else f"{s['cases'] - s['passed']} failed"
    parts = [
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>viscobem validation</title>"
        f"<style>{_CSS}</style></head><body>",
        f"<h1>viscobem validation ({'quick' if record['quick'] else 'full'} set): "
        f"<span class='{'PASS' if not s['failed'] else 'FAIL'}'>{s['passed']} of {s['cases']} cases passed</span></h1>",
        f"<p id='answer'><b>{s['passed']} of {s['cases']} cases passed</b> ({verdict}; {s['checks']} checks). "
        f"Commit <code>{e(env['commit'][:12])}</code>, {e(env['date'])}, {e(env['machine'])}; "
        f"{record['seconds']:.1f} s.",
    ]
    if baseline is not None:
        parts[-1] += " Baselines: " + (
            "every value matches."
            if baseline["ok"]
            else f"<b class='FAIL'>{len(baseline['regressions'])} regressions</b>, {len(baseline['missing'])} missing."
        )
    parts[-1] += "</p>"
    parts.append(f"<p id='basis'>{e(basis_sentence(record))}</p>")
    parts += _summary_html(record)
    parts += sensitivity_html(record)
    count = 0
    for name, c in record["cases"].items():
        parts.append(
            f"<h2 id='{e(name)}'>{e(name)}: {e(c['title'])} <span class='{_status(c)}'>{_status(c)}</span></h2>"
            f"<p>{e(c['description'])} Compares {e(compared(c))}.</p>"
        )
        if c["status"] == "error":
            parts.append(f"<pre>{e(c['traceback'])}</pre>")
            continue
        figs = figures[name] if figures is not None else (plots(c) if with_plots else [])
        if figs:
            kinds = _figure_kinds(c, len(figs))
            overlays = len(c["profiles"])
            for k, prof in enumerate(c["profiles"]):
                caption = _plot_caption(c, *kinds[k])
                parts.append(_overlay_html(name, k, prof, figs[k][2] if len(figs[k]) > 2 else None, caption))
            for fig, kind in zip(figs[overlays:], kinds[overlays:]):
                title, png = fig[0], fig[1]
                link = f" <a href='{e(fig[2])}'>PNG</a>" if len(fig) > 2 else ""
                parts.append(
                    f"<figure class='vb-plot'><img alt='{e(title)}' src='data:image/png;base64,"
                    f"{base64.b64encode(png).decode()}'/><figcaption>{e(title)}. "
                    f"{e(_plot_caption(c, *kind))}{link}</figcaption></figure>"
                )
            count += len(figs)
        parts.append(
            "<details><summary>every check of this case</summary><table><tr><th>metric</th><th>solver</th>"
            "<th>at</th><th>value</th><th>tolerance</th><th>status</th><th>basis</th><th>why</th></tr>"
        )
        for k in c["checks"]:
            st = _check_status(k)
            parts.append(
                f"<tr><td>{e(metric_name(k['metric']))} <code>{e(k['metric'])}</code></td><td>{e(k['solver'])}</td>"
                f"<td>{e(k['label'])}</td><td>{_fmt(k['value'])}</td><td>{_fmt(k['tolerance'])}</td>"
                f"<td class='{st}'>{st}</td><td>{basis(k)}</td><td>{e(k['why'])}</td></tr>"
            )
        parts.append("</table></details>")
        parts.append("<table><tr><th>solver</th><th>point</th><th>time (s)</th><th>peak MiB</th><th>detail</th></tr>")
        for r in c["runs"]:
            parts.append(
                f"<tr><td>{e(r['solver'])}</td><td>{e(r['label'])}</td><td>{r['seconds']:.3g}</td>"
                f"<td>{r['peak_mib']:.3g}</td><td>{e(r['detail'])}</td></tr>"
            )
        parts.append("</table>")
        if c["files"]:
            parts.append(
                "<p>VTK (open the .pvd files in ParaView): "
                + ", ".join(f"<code>{e(f)}</code>" for f in c["files"] if f.endswith(".pvd"))
                + "</p>"
            )
    parts += _checks_html(record)
    parts.append(f"<script>{_SCRIPT.read_text(encoding='utf-8')}</script>")
    parts.append("</body></html>")
    parts[0] = parts[0].replace("<body>", f"<body data-plots='{count}' data-cases='{len(record['cases'])}'>")
    Path(path).write_text("\n".join(parts))


def write_reports(record, out_dir, baseline=None, with_plots=True):
    """Write report.json, report.md and report.html into ``out_dir``, and with plots each plot as
    its own PNG under ``out_dir/plots/``; return the report paths."""
    out_dir = Path(out_dir)
    if baseline is not None:
        record = dict(record, baseline=baseline)
    paths = [out_dir / "report.json", out_dir / "report.md", out_dir / "report.html"]
    write_json(record, paths[0])
    write_markdown(record, paths[1], baseline)
    figures = write_pngs(record, out_dir) if with_plots else None
    write_html(record, paths[2], baseline, figures=figures, with_plots=with_plots)
    return paths
