"""Prony fits and master curves: viscobem against pyvisco on the same synthetic data.

Run it with ``python -m viscobem_bench.materials [--quick] [--out DIR]`` (or ``viscobem bench
materials``). It prints a table and writes ``DIR/materials.json`` and ``.md``.

Two problems, both from a known truth so that every error is exact:

- **prony12**: one master curve over 12 decades (121 points, 1e-4 to 1e8 rad/s) of an
  11-term series (times 1e-7 to 1e3 s, ``E_inf/E0 = 200``; ``tan delta`` 0.01-0.05 in the
  top decade), with 1 % Gaussian noise on each of ``E'`` and ``E''``.
- **master**: the same series at 296.15 K under WLF ``C1 = 8.86, C2 = 101.6 K``, measured
  from 0.1 to 100 Hz (13 points) every 5 K from 251.15 to 356.15 K (22 sweeps), 1 % noise.
- **cases**: the temperature sets a DMA user brings, noise-free (so every error is the method's),
  from a 12-term series (``E_inf/E0 = 200``, times 10^-9.2 to 10^1.8 s, off any fit grid) under the
  same law, 0.1-100 Hz: every 10 K from -20 to 60 C (the reference 23 C not measured), every 5 K
  from -40 to 60 C (0.33 decade of overlap near -40 C), 0/23/50 C, every 20 K from -30 to 50 C
  (two gaps) and -35/-15/15/60 C (no sweep overlaps its neighbour). viscobem fits the law jointly
  with the series (the default), from the overlap shifts alone (``joint=False``), or imposes the
  true law; pyvisco needs its reference among the measured temperatures, so it gets the nearest
  one and its law and series are then referred to 23 C (exactly, for WLF).

Methods: ``Material.fit_prony`` / ``Material.fit_master_curve`` (viscobem), and pyvisco's
pipeline (pairwise power-law shifts of ``E'``, ``shift.fit_WLF``, ``prony.discretize``
with one term per decade, ``prony.fit`` with and without its ``opt`` minimisation).
Errors are max and rms of ``|E_fit/E_true - 1|`` for ``E'`` and ``E''``: over the band for
prony12, and at every measured (T, f) of the material under its own fitted law for master
(what a user's simulation at that temperature sees) and of the reference curve over the
13.3 decades the shifted sweeps cover (``ref_*``: there the shift errors show, as a
displacement of each sweep's part of the curve), plus the error of the measured shifts
(``shifts_max``, before the law) and of the law (``log_aT_max``) in ``log10 a_T`` (decades), and
of C1, C2. Times are wall-clock seconds in this process (one at a time) and, for the cases, CPU
seconds (``cpu``); the machine may be shared, so CPU time is the one to compare.

Reading the table: pyvisco shifts by ``E'`` alone, which is undetermined where ``E'`` is flat
(the glassy plateau of the coldest sweeps), and fits its series in absolute error (moduli
divided by the glassy modulus) on one term per decade, which leaves the small loss modulus of
the tails almost unweighted.
"""

import argparse
import contextlib
import io
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from bem import Material
from bem.errors import InputError
from bem.materials.temperature import WLF

TREF = 296.15
LAW = WLF(8.86, 101.6, TREF)
W12 = np.logspace(-4, 8, 121)
HZ = np.logspace(-1, 2, 13)
TEMPS = TREF + np.arange(-45.0, 61.0, 5.0)
C = 273.15
CASES = {
    "10 K, T_ref not measured": C + np.arange(-20.0, 61.0, 10.0),
    "5 K, -40..60 C": C + np.arange(-40.0, 61.0, 5.0),
    "0/23/50 C": C + np.array([0.0, 23.0, 50.0]),
    "20 K, two gaps": C + np.arange(-30.0, 51.0, 20.0),
    "no overlap": C + np.array([-35.0, -15.0, 15.0, 60.0]),
}


def truth():
    """The 11-term series (Pa, s) both problems are made from."""
    return Material.from_prony(E0=2e6, moduli=np.full(11, 2e6 * 199 / 11), times=np.logspace(-7, 3, 11))


def truth12():
    """The 12-term series (Pa, s) of the cases, its times between any fit grid's."""
    return Material.from_prony(E0=2e6, moduli=np.full(12, 2e6 * 199 / 12), times=np.logspace(-9.2, 1.8, 12))


def prony12_data(seed):
    m = truth()
    rng = np.random.default_rng(seed)
    e = m.complex_modulus(W12)
    return e.real * (1 + 0.01 * rng.standard_normal(W12.size)), e.imag * (1 + 0.01 * rng.standard_normal(W12.size))


def master_data(seed, m=None, temps=TEMPS, noise=0.01):
    """Columns Hz, K, E' (Pa), E'' (Pa) of sweeps at ``temps`` (K) of ``m`` (the 11-term truth)."""
    m = truth() if m is None else m
    rng = np.random.default_rng(seed)
    cols = [[], [], [], []]
    for t in temps:
        e = m.at_temperature(t, LAW).complex_modulus(2 * np.pi * HZ)
        for c, v in zip(
            cols,
            (
                HZ,
                np.full(HZ.size, t),
                e.real * (1 + noise * rng.standard_normal(HZ.size)),
                e.imag * (1 + noise * rng.standard_normal(HZ.size)),
            ),
        ):
            c.append(v)
    return [np.concatenate(c) for c in cols]


def _errors(fitted, true):
    r1 = np.abs(fitted.real / true.real - 1)
    r2 = np.abs(fitted.imag / true.imag - 1)
    return {
        "storage_max": float(r1.max()),
        "storage_rms": float(np.sqrt(np.mean(r1**2))),
        "loss_max": float(r2.max()),
        "loss_rms": float(np.sqrt(np.mean(r2**2))),
    }


def _pyvisco_master(frame):
    """pyvisco's frequency-domain master-curve frame (Hz, MPa) with its attributes."""
    frame = frame.sort_values(by=["f"]).reset_index(drop=True)
    frame["omega"] = 2 * np.pi * frame["f"]
    frame["t"] = 1 / frame["f"]
    frame.domain, frame.modul, frame.RefT = "freq", "E", TREF - 273.15
    return frame


class _Series:
    """A Prony series evaluated as pyvisco defines it (its relaxed modulus may come out 0,
    which :class:`bem.Material` rejects): ``E0 + sum E_k i w tau_k / (1 + i w tau_k)``."""

    def __init__(self, E0, moduli, times):
        self.E0, self.moduli, self.relaxation_times = E0, moduli, times

    def complex_modulus(self, w):
        iwt = 1j * np.asarray(w)[:, None] * self.relaxation_times
        return self.E0 + np.sum(self.moduli * iwt / (1 + iwt), axis=1)

    def at_temperature(self, T, law):
        return _Series(self.E0, self.moduli, self.relaxation_times * law.shift_factor(T))


def _pyvisco_prony(df_master, opt):
    """The series from pyvisco's discretisation (one term per decade) and fit."""
    from pyvisco import master, prony

    df_master = master.smooth(df_master, 1)
    with contextlib.redirect_stdout(io.StringIO()):
        df_dis = prony.discretize(df_master)
        series, _ = prony.fit(df_dis, df_master, opt=opt)
    terms = series["df_terms"]
    e_glassy = series["E_0"] * 1e6
    alpha, tau = terms["alpha_i"].values, terms["tau_i"].values
    keep = alpha > 1e-12
    return _Series(e_glassy * (1 - alpha.sum()), e_glassy * alpha[keep], tau[keep])


def run_prony12(seed):
    import pandas as pd

    m = truth()
    e1, e2 = prony12_data(seed)
    true = m.complex_modulus(W12)
    rows = []
    t0 = time.perf_counter()
    fit = Material.fit_prony(W12, e1, e2)
    rows.append(
        {
            "method": "viscobem fit_prony",
            "time": time.perf_counter() - t0,
            "terms": int(fit.moduli.size),
            **_errors(fit.complex_modulus(W12), true),
        }
    )
    frame = pd.DataFrame({"f": W12 / (2 * np.pi), "E_stor": e1 / 1e6, "E_loss": e2 / 1e6})
    for opt in (False, True):
        t0 = time.perf_counter()
        mat = _pyvisco_prony(_pyvisco_master(frame.copy()), opt)
        rows.append(
            {
                "method": f"pyvisco{' opt' if opt else ''}",
                "time": time.perf_counter() - t0,
                "terms": int(mat.moduli.size),
                **_errors(mat.complex_modulus(W12), true),
            }
        )
    return rows


def _data_errors(material, law, m, temps=TEMPS):
    """Errors of ``material`` under ``law`` at every measured (T, f), against the truth."""
    w = 2 * np.pi * HZ
    fitted = np.concatenate([material.at_temperature(t, law).complex_modulus(w) for t in temps])
    true = np.concatenate([m.at_temperature(t, LAW).complex_modulus(w) for t in temps])
    return _errors(fitted, true)


def _reference_errors(material, m=None, temps=TEMPS):
    """Max errors of the reference (296.15 K) curve over the reduced band the sweeps cover."""
    m = truth() if m is None else m
    lo, hi = 2 * np.pi * HZ[0] * 10.0 ** LAW(temps[-1]), 2 * np.pi * HZ[-1] * 10.0 ** LAW(temps[0])
    w = np.logspace(np.log10(lo), np.log10(hi), 400)
    e = _errors(material.complex_modulus(w), m.complex_modulus(w))
    return {"ref_storage_max": e["storage_max"], "ref_loss_max": e["loss_max"]}


def _law_errors(law, temps=TEMPS):
    return {
        "C1_rel": law.C1 / LAW.C1 - 1,
        "C2_rel": law.C2 / LAW.C2 - 1,
        "log_aT_max": float(np.max(np.abs(law(temps) - LAW(temps)))),
    }


def _pyvisco_master_curve(f, T, e1, e2, opt, temps=TEMPS):
    """pyvisco's shifts, WLF law and series, with its reference the measured temperature nearest
    23 C (it needs one), referred to 23 C: ``(series, law, shifts error)``."""
    import pandas as pd
    from pyvisco import master, shift

    label = np.searchsorted(temps, T - 1e-6)
    df_raw = pd.DataFrame({"f_set": f, "E_stor": e1 / 1e6, "E_loss": e2 / 1e6, "T": T - 273.15, "Set": label})
    df_raw["T_round"] = df_raw["T"].round()
    df_raw.domain, df_raw.modul = "freq", "E"
    t_meas = float(temps[np.argmin(np.abs(temps - TREF))])
    ref = round(t_meas - 273.15)
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # pyvisco's own overflows; its result is scored below
        df_aT, _ = master.get_aT(df_raw, ref)
        df_master = master.get_curve(df_raw, df_aT, ref)
        coeff = shift.fit_WLF(ref, df_aT)
    law = WLF(float(coeff["C1"].iloc[0]), float(coeff["C2"].iloc[0]), t_meas)
    T_aT = df_aT["T"].values + 273.15
    shifts = float(np.max(np.abs(df_aT["log_aT"].values - (LAW(T_aT) - LAW(t_meas)))))
    series = _pyvisco_prony(df_master, opt)
    if t_meas != TREF:  # the same law and series referred to 23 C
        series, law = series.at_temperature(TREF, law), law.referenced_to(TREF)
    return series, law, shifts


def run_master(seed):
    m = truth()
    f, T, e1, e2 = master_data(seed)
    rows = []
    t0 = time.perf_counter()
    fit, law = Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True)
    shifts = float(np.max(np.abs(np.array(fit.fit_report.log_shift) - LAW(TEMPS))))
    rows.append(
        {
            "method": "viscobem fit_master_curve",
            "time": time.perf_counter() - t0,
            "terms": int(fit.moduli.size),
            "shifts_max": shifts,
            **_law_errors(law),
            **_data_errors(fit, law, m),
            **_reference_errors(fit),
        }
    )
    for opt in (False, True):
        t0 = time.perf_counter()
        mat, law, shifts = _pyvisco_master_curve(f, T, e1, e2, opt)
        rows.append(
            {
                "method": f"pyvisco{' opt' if opt else ''}",
                "time": time.perf_counter() - t0,
                "terms": int(mat.moduli.size),
                "shifts_max": shifts,
                **_law_errors(law),
                **_data_errors(mat, law, m),
                **_reference_errors(mat),
            }
        )
    return rows


def _case_row(method, fit, law, m, temps, cpu, wall, shifts=None):
    row = {"method": method, "time": wall, "cpu": cpu, "terms": int(fit.moduli.size)}
    row.update(_law_errors(law, temps))
    row.update(_data_errors(fit, law, m, temps))
    row.update(_reference_errors(fit, m, temps))
    report = getattr(fit, "fit_report", None)
    row["law_sigma_max"] = float(max(report.law_sigma)) if report is not None and report.law_sigma else None
    row["warnings"] = len(getattr(fit, "warnings", ()))
    if shifts is not None:
        row["shifts_max"] = shifts
    return row


def _timed(call, *args, **kwargs):
    """``(call(*args, **kwargs), cpu s, wall s)``."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = call(*args, **kwargs)
    return out, time.process_time() - c0, time.perf_counter() - t0


def run_cases(with_pyvisco=True):
    """The issue's temperature sets, noise-free: one row (``case``, ``method``, errors) per method
    and case."""
    m = truth12()
    out = []
    for name, temps in CASES.items():
        f, T, e1, e2 = master_data(0, m, temps, noise=0.0)
        rows = []
        methods = [
            ("viscobem joint", dict(reference_temperature=TREF)),
            ("viscobem overlap only", dict(reference_temperature=TREF, joint=False)),
            ("viscobem imposed law", dict(shift=LAW)),
        ]
        for method, kw in methods:
            try:
                (fit, law), cpu, wall = _timed(Material.fit_master_curve, f, T, e1, e2, hz=True, **kw)
            except InputError as err:
                rows.append({"method": method, "failed": str(err)})
                continue
            rows.append(_case_row(method, fit, law, m, temps, cpu, wall))
        if with_pyvisco:
            try:
                (series, law, shifts), cpu, wall = _timed(_pyvisco_master_curve, f, T, e1, e2, False, temps)
                rows.append(_case_row("pyvisco", series, law, m, temps, cpu, wall, shifts))
            except Exception as err:  # pyvisco's own failures are a result of this benchmark
                rows.append({"method": "pyvisco", "failed": f"{type(err).__name__}: {err}"})
        out += [{"case": name, **row} for row in rows]
    return out


def _summary(rows_by_seed):
    """Per method: the worst over seeds of every error, the median time."""
    out = []
    for method in [r["method"] for r in rows_by_seed[0]]:
        rows = [r for seeds in rows_by_seed for r in seeds if r["method"] == method]
        row = {
            "method": method,
            "seeds": len(rows),
            "time": float(np.median([r["time"] for r in rows])),
            "terms": int(np.median([r["terms"] for r in rows])),
        }
        for key in rows[0]:
            if key not in row:
                row[key] = float(np.max(np.abs([r[key] for r in rows])))
        out.append(row)
    return out


def _table(result, markdown=False):
    lines = []
    for problem, cols in (
        ("prony12", ["storage_max", "storage_rms", "loss_max", "loss_rms"]),
        (
            "master",
            [
                "shifts_max",
                "C1_rel",
                "C2_rel",
                "log_aT_max",
                "storage_max",
                "storage_rms",
                "loss_max",
                "loss_rms",
                "ref_storage_max",
                "ref_loss_max",
            ],
        ),
    ):
        heads = ["method", "terms"] + cols + ["time s"]
        rows = [
            [r["method"], str(r["terms"])] + [f"{r[c]:.4f}" for c in cols] + [f"{r['time']:.2f}"]
            for r in result[problem]
        ]
        title = f"{problem} (worst over {result['seeds']} seeds; relative errors, log_aT in decades)"
        lines += _render(title, heads, rows, markdown)
    lines += _cases_table(result["cases"], markdown)
    return "\n".join(lines)


CASE_COLUMNS = [
    "C1_rel",
    "log_aT_max",
    "storage_max",
    "loss_max",
    "ref_storage_max",
    "ref_loss_max",
    "law_sigma_max",
    "warnings",
    "cpu",
]


def _cell(value):
    if value is None:
        return "-"
    if isinstance(value, int):
        return str(value)
    return f"{value:.2e}" if value != 0 and (abs(value) < 1e-3 or abs(value) >= 1e3) else f"{value:.4f}"


def _cases_table(cases, markdown):
    """One table per case: noise-free errors (relative; log_aT, law_sigma in decades; cpu in s)."""
    lines = []
    for name in dict.fromkeys(r["case"] for r in cases):
        rows = [r for r in cases if r["case"] == name]
        heads = ["method"] + CASE_COLUMNS
        body = [
            [r["method"]]
            + (
                [f"failed: {r['failed'][:60]}"] + [""] * (len(CASE_COLUMNS) - 1)
                if "failed" in r
                else [_cell(r[c]) for c in CASE_COLUMNS]
            )
            for r in rows
        ]
        title = f"case {name} (noise-free; relative errors, log_aT and law_sigma in decades, cpu s)"
        lines += _render(title, heads, body, markdown)
    return lines


def _render(title, heads, rows, markdown):
    """A titled table: markdown, or aligned text."""
    if markdown:
        return (
            [title, "", "| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]
            + ["| " + " | ".join(r) + " |" for r in rows]
            + [""]
        )
    widths = [max(len(x) for x in col) for col in zip(heads, *rows)]
    return [title] + ["  ".join(x.ljust(w) for x, w in zip(r, widths)) for r in [heads] + rows]


def run(quick=False, out_dir=None, seeds=None, echo=print):
    """prony12 and master over ``seeds``, and the cases; print the tables, write JSON and markdown,
    return the result."""
    seeds = list(seeds or ([1] if quick else [1, 2, 3]))
    result = {
        "benchmark": "materials",
        "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "seeds": len(seeds),
        "wlf_truth": {"C1": LAW.C1, "C2": LAW.C2, "reference_temperature": TREF},
        "prony12": _summary([run_prony12(s) for s in seeds]),
        "master": _summary([run_master(s) for s in seeds]),
        "cases": run_cases(),
    }
    echo(_table(result))
    if out_dir is not None:
        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        (out / "materials.json").write_text(json.dumps(result, indent=1))
        about = __doc__.split("\n\n", 2)[2]  # the problems and methods, from this module's docstring
        (out / "materials.md").write_text(
            "# Prony fits and master curves: viscobem and pyvisco\n\n"
            + about
            + "\n"
            + _table(result, markdown=True)
            + "\n"
        )
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.materials", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="one seed (smoke test)")
    parser.add_argument("--seeds", type=int, nargs="+", help="noise seeds (default 1 2 3)")
    parser.add_argument("--out", default=None, help="directory for materials.json and .md")
    args = parser.parse_args(argv)
    run(args.quick, args.out, args.seeds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
