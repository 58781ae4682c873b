"""Reports of ``viscobem bench``: Pareto fronts, plots and the Markdown table of ``bench.md``."""

import numpy as np

MiB = 2.0**20


def pareto_front(points):
    """Indices of the points not dominated in (time, error), sorted by time."""
    pts = sorted((p["time"], p["error"], i) for i, p in enumerate(points) if p.get("error") is not None)
    front, best = [], np.inf
    for _, e, i in pts:
        if e < best:
            front.append(i)
            best = e
    return front


def plots(result, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    files = []
    for name, entry in result["solvers"].items():
        pts = [p for p in entry["points"] if p.get("error") is not None and p["error"] > 0]
        if not pts:
            continue
        fig, ax = plt.subplots(figsize=(5.5, 4))
        knob = entry["knobs"][0]
        values = sorted({p[knob] for p in pts})
        cmap = plt.get_cmap("viridis", max(len(values), 2))
        for j, v in enumerate(values):
            sel = [p for p in pts if p[knob] == v]
            ax.scatter([p["time"] for p in sel], [p["error"] for p in sel], color=cmap(j), label=f"{knob} = {v}")
        front = [entry["points"][i] for i in entry["pareto"] if entry["points"][i]["error"] > 0]
        ax.plot([p["time"] for p in front], [p["error"] for p in front], "k--", lw=1, label="Pareto front")
        ax.set(
            xscale="log",
            yscale="log",
            xlabel="wall time (s)",
            ylabel=entry["error"],
            title=f"{entry['solver']}: {name}\nreference: {entry['reference']}",
        )
        ax.title.set_fontsize(9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(out / f"pareto_{name}.png", dpi=110)
        plt.close(fig)
        files.append(f"pareto_{name}.png")
    rows = result["scaling"]["rows"]
    if rows:
        fig, ax = plt.subplots(figsize=(5.5, 4))
        N = np.array([r["n"] ** 2 for r in rows], dtype=float)
        ax.loglog(N, [r["time"] for r in rows], "o-", label="viscobem periodic BEM")
        ax.loglog(N, [r["fft_pair_time"] * r["matvecs"] for r in rows], "s:", label="products x FFT-pair time")
        if any("tamaas_time" in r for r in rows):
            ax.loglog(
                [n for n, r in zip(N, rows) if "tamaas_time" in r],
                [r["tamaas_time"] for r in rows if "tamaas_time" in r],
                "^-",
                label="tamaas PolonskyKeerRey",
            )
        ref = N * np.log(N)
        ax.loglog(N, ref / ref[-1] * rows[-1]["time"], "k--", lw=1, label="N log N")
        ax.set(xlabel="N = n²", ylabel="wall time (s)", title="elastic rough contact, ~10 % contact, rtol 1e-8")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(out / "scaling.png", dpi=110)
        plt.close(fig)
        files.append("scaling.png")
    return files


def _g(x, spec=".3g"):
    return "" if x is None else format(x, spec)


def markdown(result):
    """The README table (and bench.md): Pareto fronts, scaling, skipping."""
    lines = [
        "'rtol's share': rel. L2 pressure error against rtol 1e-12 on the same grid (where measured).",
        "",
        f"Measured by `viscobem bench{' --quick' if result['quick'] else ''}` on {result['date']} "
        f"({result['machine']['cpu_count']} cores, load average {result['machine']['load_average']}); "
        "regenerate with that command.",
        "",
        "| solver | problem | reference | knobs on the Pareto front | error | rtol's share | time (s) "
        "| peak RSS (MiB) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, e in result["solvers"].items():
        for i in e["pareto"]:
            p = e["points"][i]
            knobs = ", ".join(f"{k} {p[k]:g}" for k in e["knobs"] if k in p)
            lines.append(
                f"| {e['solver']} | {name} | {e['reference']} | {knobs} | {_g(p['error'], '.2e')} "
                f"| {_g(p.get('tolerance_error'), '.1e')} | {_g(p['time'])} | {p['peak_rss'] / MiB:.0f} |"
            )
    sc = result["scaling"]
    if sc["rows"]:
        lines += [
            "",
            "| n² | time (s) | products | FFT pair (ms) | time / (products x pair) | tamaas (s) | tamaas / ours |",
            "|---|---|---|---|---|---|---|",
        ]
        for r in sc["rows"]:
            lines.append(
                f"| {r['n']}² | {_g(r['time'])} | {r['matvecs']} | {_g(1e3 * r['fft_pair_time'])} "
                f"| {_g(r['fft_pair_ratio'])} | {_g(r.get('tamaas_time'))} | {_g(r.get('tamaas_ratio'))} |"
            )
        if sc["fit"]:
            lines += [
                "",
                f"Scaling: t ∝ N^{sc['fit']['exponent_time']:.2f} (N = n²); t / (N log N) ∝ "
                f"N^{sc['fit']['exponent_time_over_NlogN']:.2f}; time per operator product ∝ "
                f"N^{sc['fit']['exponent_time_per_product']:.2f}. tamaas {sc['tamaas'] or 'not installed'}"
                f" ({sc['tamaas_threads']} OpenMP threads).",
            ]
    s = result.get("skip")
    if s:
        f0, f1, r, w = s["fold_full"], s["fold_folded"], s["reuse_operator"], s["warm_start"]
        sweep = r["time_cached"]
        saved_builds = (r["solves"] - 1) * r["operator_build_time"]
        lines += [
            "",
            f"Skipping what a scene does not need ({s['n']}²; 'saved' is the share of that run's time):",
            "",
            "| what | without | with | saved |",
            "|---|---|---|---|",
            f"| fold inactive Prony terms ({f0['terms']} -> {f1['terms']}): operator build | "
            f"{1e3 * f0['operator_build_time']:.2f} ms | {1e3 * f1['operator_build_time']:.2f} ms | "
            f"{(f0['operator_build_time'] - f1['operator_build_time']) / f1['solve_time']:.1e} of a solve "
            f"(friction changes {s['fold_friction_change']:.1e}) |",
            f"| reuse the operator over a sweep of {r['solves']} loads: builds | {r['solves']} x "
            f"{1e3 * r['operator_build_time']:.2f} ms | 1 | {saved_builds / sweep:.1e} of the sweep "
            f"(sweeps measured {r['time_rebuilt']:.3f} s / {r['time_cached']:.3f} s: noise) |",
            f"| warm starts over {w['speeds']} speeds | {w['time_cold']:.3f} s | {w['time_warm']:.3f} s "
            f"| {1 - w['time_warm'] / w['time_cold']:.0%} |",
        ]
        o = s.get("outputs")
        if o:
            lines.append(
                f"| unrequested outputs (fields, plots, VTK) | {o['all']['total']:.3f} s | "
                f"{o['needed']['total']:.3f} s | {1 - o['needed']['total'] / o['all']['total']:.0%} |"
            )
    return "\n".join(lines)
