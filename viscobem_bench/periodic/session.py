"""The state of one run of the periodic benchmark (:mod:`viscobem_bench.periodic`): its temporary
folder, loads, the time spent per case, and the extrapolation that skips a case too slow to run."""

import os
import time
from multiprocessing import TimeoutError as ProcessTimeout

import numpy as np

from viscobem_bench import instruments
from viscobem_bench.periodic.problem import CASES, MiB, surface_heights
from viscobem_bench.periodic.report import fmt
from viscobem_bench.periodic.workers import case_worker, tamaas_worker


def extrapolate(history, n):
    """Seconds a case would take at size ``n`` from its earlier ``[(n, seconds)]``, or None.

    Power law through the last two sizes (exponent clamped to [2, 4.5]), else ``n**2.6``.
    """
    if not history:
        return None
    n1, t1 = history[-1]
    k = 2.6
    if len(history) >= 2:
        n0, t0 = history[-2]
        k = float(np.clip(np.log(t1 / t0) / np.log(n1 / n0), 2.0, 4.5))
    return t1 * (n / n1) ** k


class Session:
    """The state of one run: its temporary folder, loads, time spent per case, and notes."""

    def __init__(self, tmp, env, echo):
        self.tmp, self.env, self.echo = tmp, env, echo
        self.notes, self.cases, self.tamaas_runs = [], [], []
        self.spent = {case: [] for case in CASES + ("tamaas",)}  # [(n, seconds)] per case
        self.best_threads = None
        self.loads = None

    def note(self, text):
        self.notes.append(text)
        self.echo("  " + text)

    def heights_file(self, n):
        path = self.tmp / f"heights_{n}.npy"
        if not path.exists():
            np.save(path, surface_heights(n))
        return str(path)

    def skip(self, case, n, limit):
        estimate = extrapolate(self.spent[case], n)
        if estimate is not None and estimate > limit:
            self.note(f"{case} skipped at n = {n}: extrapolated {estimate:.0f} s > {limit:.0f} s")
            return True
        return False

    def run_case(self, case, n, max_case_seconds, probe_iterations):
        """One of our cases at size ``n`` in a fresh process."""
        spec = {
            "heights": self.heights_file(n),
            "case": case,
            "load": self.loads[case],
            "tight_budget": -1.0 if probe_iterations else max_case_seconds / 2,
            "maxiter": probe_iterations,
        }
        if case == "elastic":
            spec["save_reference"] = str(self.tmp / f"reference_{n}.npy")
        try:
            res = instruments.run_in_fresh_process(case_worker, spec, env=self.env, timeout=4 * max_case_seconds)
        except ProcessTimeout:
            self.note(f"{case} at n = {n} stopped after {4 * max_case_seconds:.0f} s")
            self.spent[case].append((n, 4 * max_case_seconds))
            return
        except Exception as err:  # a crash in one case must not lose the others
            self.note(f"{case} at n = {n} failed: {type(err).__name__}: {err}")
            return
        self.spent[case].append((n, res["wall_time"]))
        self.cases.append(res)
        if res["reference"] is None and not probe_iterations:
            self.notes.append(
                f"{case} at n = {n}: tight solve skipped (default solve "
                f"{res['wall_time']:.0f} s > {max_case_seconds / 2:.0f} s)"
            )
        self.echo(
            f"  n = {n:5d} {case:9s} wall {res['wall_time']:8.3f} s, {res['matvecs']:5d} matvecs, "
            f"contact {res['contact_fraction']:.4f}, peak {res['peak_rss'] / MiB:.0f} MiB, "
            f"p err {fmt(res['pressure_error_l2'], '.1e')}, converged {res['success']}"
        )

    def run_tamaas(self, n, tol, threads, max_seconds):
        """tamaas at size ``n``: given ``threads``, or 1 and all cores while cheap (the faster kept)."""
        spec = {
            "heights": self.heights_file(n),
            "load": self.loads["elastic"],
            "tol": tol,
            "reference": str(self.tmp / f"reference_{n}.npy"),
        }
        estimate = extrapolate(self.spent["tamaas"], n) or 0.0
        cheap = not (self.best_threads and estimate > max_seconds / 4)
        trials = threads or (sorted({1, os.cpu_count() or 1}) if cheap else [self.best_threads])
        runs, seconds = {}, []
        for k in trials:
            t0 = time.perf_counter()
            try:
                runs[k] = instruments.run_in_fresh_process(
                    tamaas_worker, spec, timeout=2 * max_seconds, env=instruments.thread_environment(1, omp_threads=k)
                )
            except ProcessTimeout:
                self.note(f"tamaas ({k} threads) at n = {n} stopped after {2 * max_seconds:.0f} s")
            except Exception as err:
                self.note(f"tamaas at n = {n} failed: {type(err).__name__}: {err}")
            seconds.append(time.perf_counter() - t0)
        self.spent["tamaas"].append((n, min(seconds)))
        if not runs:
            return
        self.best_threads = min(runs, key=lambda k: runs[k]["wall_time"])
        t = dict(
            runs[self.best_threads],
            omp_threads=self.best_threads,
            wall_time_by_threads={str(k): v["wall_time"] for k, v in runs.items()},
        )
        self.tamaas_runs.append(t)  # its speed-up is set by _more_rounds, from our final time
        self.echo(
            f"  n = {n:5d} tamaas    wall {t['wall_time']:8.3f} s, {t['iterations']} iterations, "
            f"p err {t['pressure_error_l2']:.1e}, threads {t['wall_time_by_threads']}"
        )
