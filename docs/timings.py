"""Measured run times and output sizes: the record behind every figure the README and docs state.

    python docs/timings.py                  # measure every run, then render
    python docs/timings.py run_seed tests   # measure only these (the others are kept)
    python docs/timings.py --render         # no measuring: rewrite the stated figures only
    python docs/timings.py --import KEY SECONDS DATE SOURCE   # a run measured elsewhere
    python docs/timings.py --record KEY SECONDS SOURCE        # CI's own run, dated now, stated figures kept

Each run of :data:`RUNS` is a command, started from the repository root with this Python's
environment; it is timed (wall clock, and the CPU time and peak resident memory of the
process and its children), the load average is sampled every few seconds while it runs, and
the size of its output folder is measured. ``docs/timings.json`` keeps one entry per run, with
the machine (cores, CPU, memory), the date and the commit. A run measured elsewhere (a report,
a CI log) can be recorded with ``--import`` and its source; it has no CPU time or load average,
and the next measurement of that key replaces it. ``--record`` stores such a run without restating
the figures, marked ``"upper": true``: CI records the runs it makes as it goes (``.ci/run``), and
the documentation test of its later step fails when one took more than twice the time the pages
state. That check is one-sided, since a stated time is a promise of at most about that long: a
faster machine keeps it, and the figure was measured on the slower of the machines seen.

A stated figure is a Markdown link whose target is this record's page and key,
``[75 s on 2 cores](timings.md#validate_quick)`` (``docs/timings.md#...`` from the README):
rendering rewrites the figure of every such link in ``README.md`` and ``docs/*.md`` from the
record, and writes ``docs/timings.md``. ``tests/docs/test_timings.py`` fails when a stated
figure and the record differ by more than a factor of 2, when a figure is stated without such
a link, or when a required run is missing from the record.

Times are only as good as the machine was quiet: on a shared machine the wall clock grows
with the load average recorded beside it; measure on a quiet one (load average below the
number of cores) before a release.
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "docs" / "timings.json"
PAGE = ROOT / "docs" / "timings.md"
COMMAND = "python docs/timings.py"

# key -> (what, argv after the program, program: "viscobem" or "pytest", writes an output folder)
RUNS = {
    "run_seed": ("`viscobem run`: the built-in seed study", ["run", "--no-progress"], "viscobem", True),
    "run_sphere": ("`viscobem run sphere`", ["run", "sphere", "--no-progress"], "viscobem", True),
    "run_cylinder": ("`viscobem run cylinder`", ["run", "cylinder", "--no-progress"], "viscobem", True),
    "run_temperature": ("`viscobem run temperature`", ["run", "temperature", "--no-progress"], "viscobem", True),
    "run_seed_figures": (
        "`viscobem run seed_figures`",
        ["run", "seed_figures", "--no-progress"],
        "viscobem",
        True,
    ),
    "validate_quick": ("`viscobem validate --quick`", ["validate", "--quick", "--no-progress"], "viscobem", True),
    "validate_full": ("`viscobem validate` (the full set)", ["validate", "--no-progress"], "viscobem", True),
    "tests": ("`pytest`: the default test run", [], "pytest", False),
    "tests_slow": ("`pytest -m slow`", ["-m", "slow"], "pytest", False),
}
CLAIM = re.compile(r"\[([^\]]*)\]\(((?:docs/)?timings\.md)#([a-z0-9_]+)\)")
FIGURE = re.compile(r"(\d+(?:\.\d+)?)\s*(s|min|h|kB|MB|GB)\b")
SECONDS = {"s": 1.0, "min": 60.0, "h": 3600.0}
BYTES = {"kB": 1e3, "MB": 1e6, "GB": 1e9}


# --- measuring ---------------------------------------------------------------------------------


def machine():
    """Cores, CPU model, memory, OS and Python of this machine."""
    model, memory = "", 0.0
    try:
        cpuinfo = Path("/proc/cpuinfo").read_text()
        model = next((line.split(":", 1)[1].strip() for line in cpuinfo.splitlines() if "model name" in line), "")
        meminfo = Path("/proc/meminfo").read_text().split()
        memory = float(meminfo[meminfo.index("MemTotal:") + 1]) / 2**20
    except (OSError, ValueError, StopIteration):
        pass
    return {
        "cores": os.cpu_count(),
        "cpu": model or platform.processor(),
        "memory_gib": round(memory, 1),
        "platform": platform.platform(),
        "python": platform.python_version(),
    }


def _commit():
    try:
        run = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10)
        dirty = subprocess.run(
            ["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
            capture_output=True,
            text=True,
            timeout=10,
        ).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return run.stdout.strip()[:12] + (" (dirty)" if dirty else "")


def _program(name):
    if name == "pytest":
        # the record's own checks (tests/docs/test_timings.py) read the entry this run is making:
        # left out of the timed run, they take about a second
        ignore = ["--ignore", str(Path("tests") / "docs" / "test_timings.py")]
        return [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *ignore]
    found = shutil.which("viscobem", path=str(Path(sys.executable).parent)) or shutil.which("viscobem")
    return [found] if found else [sys.executable, "-m", "viscobem_cli.main"]


def _size(folder):
    return sum(p.stat().st_size for p in Path(folder).rglob("*") if p.is_file())


class _LoadSampler(threading.Thread):
    """The 1-minute load average every ``period`` seconds while a run lasts."""

    def __init__(self, period=5.0):
        super().__init__(daemon=True)
        self.period, self.samples, self._done = period, [], threading.Event()

    def run(self):
        while not self._done.is_set():
            self.samples.append(os.getloadavg()[0])
            self._done.wait(self.period)

    def stop(self):
        self._done.set()
        self.join()
        return self.samples


def measure(key):
    """Run ``RUNS[key]`` once; its entry of the record."""
    what, args, program, writes = RUNS[key]
    with tempfile.TemporaryDirectory(prefix=f"viscobem-timing-{key}-") as tmp:
        argv = _program(program) + args + (["--out", str(Path(tmp) / "out")] if writes else [])
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        load_before = os.getloadavg()
        sampler = _LoadSampler()
        sampler.start()
        t0 = time.perf_counter()
        done = subprocess.run(argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
        wall = time.perf_counter() - t0
        samples = sampler.stop()
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        size = _size(Path(tmp) / "out") if writes and (Path(tmp) / "out").exists() else None
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    tail = done.stdout.strip().splitlines()[-1:] or [""]
    return {
        "what": what,
        "command": " ".join([program] + args + (["--out", "DIR"] if writes else [])),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": _commit(),
        "exit_status": done.returncode,
        "last_line": tail[0][-300:],
        "wall_s": round(wall, 1),
        "cpu_s": round(cpu, 1),
        "peak_rss_mib": round(after.ru_maxrss / 1024.0, 1),  # the largest process, KiB on Linux
        "output_bytes": size,
        "load_average": {
            "before": [round(x, 2) for x in load_before],
            "during_mean_1min": round(sum(samples) / len(samples), 2) if samples else None,
            "during_max_1min": round(max(samples), 2) if samples else None,
        },
    }


def load_record():
    if RECORD.is_file():
        return json.loads(RECORD.read_text(encoding="utf-8"))
    return {"regenerate": COMMAND, "runs": {}}


def save_record(record):
    RECORD.write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")


# --- stating -----------------------------------------------------------------------------------


def time_text(seconds):
    """A wall time as stated: ``45 s``, ``3.5 min``, ``12 min``, ``1.4 h``."""
    if seconds < 90:
        return f"{seconds:.2g} s" if seconds < 10 else f"{round(seconds):d} s"
    minutes = seconds / 60
    if minutes < 90:
        return f"{minutes:.1f} min" if minutes < 10 else f"{round(minutes):d} min"
    return f"{minutes / 60:.1f} h"


def size_text(size):
    for unit, factor in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if size >= factor:
            value = size / factor
            return f"{value:.2g} {unit}" if value < 10 else f"{round(value):d} {unit}"
    return f"{size} B"


def stated(text):
    """``(value, kind)`` of the first figure in a claim's text: seconds ("time") or bytes ("size")."""
    match = FIGURE.search(text)
    if match is None:
        return None, None
    value, unit = float(match.group(1)), match.group(2)
    return (value * SECONDS[unit], "time") if unit in SECONDS else (value * BYTES[unit], "size")


def recorded(entry, kind):
    return entry["wall_s"] if kind == "time" else entry["output_bytes"]


def restate(text, entry):
    """The claim text with its figure replaced by the record's."""
    _, kind = stated(text)
    if kind is None:
        return text
    value = recorded(entry, kind)
    new = time_text(value) if kind == "time" else size_text(value)
    return FIGURE.sub(new, text, count=1)


def rewrite_claims(markdown, runs):
    """Every claim link of ``markdown`` restated from ``runs`` (unknown keys left as they are)."""

    def one(match):
        text, target, key = match.groups()
        if key not in runs:
            return match.group(0)
        return f"[{restate(text, runs[key])}]({target}#{key})"

    return CLAIM.sub(one, markdown)


def claim_files():
    return [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").glob("*.md") if p != PAGE)


def page(record):
    """docs/timings.md from the record."""
    m = record.get("machine", {})
    lines = [
        "# Measured times and sizes",
        "",
        "Every run time and output size that the README and this documentation state links to its",
        "entry here, and comes from this record (`docs/timings.json`); a test fails when a stated",
        "figure and the record differ by more than a factor of 2. Regenerate it with",
        f"`{record.get('regenerate', COMMAND)}` (every run; name keys to measure only those).",
        "",
        f"Machine: {m.get('cores', '?')} cores ({m.get('cpu', '?')}), {m.get('memory_gib', '?')} GiB, "
        f"{m.get('platform', '?')}, Python {m.get('python', '?')}.",
        "",
        "Wall times grow with the machine's load: each entry gives the 1-minute load average while it",
        f"ran; on this {m.get('cores', '?')}-core machine, above {m.get('cores', '?')} means other work shared the cores,",
        "and the CPU time is then the steadier figure.",
        "",
    ]
    for key, e in record.get("runs", {}).items():
        load = e["load_average"]
        lines += [f"### {key}", "", f"{e['what']}: `{e['command']}`", ""]
        if e.get("source"):
            lines += [
                f"- wall time **{time_text(e['wall_s'])}** ({e['wall_s']} s), measured elsewhere: {e['source']}",
                f"- {e['date']}; no CPU time or load average recorded: measure it here to replace this entry",
                "",
            ]
            continue
        lines += [
            f"- wall time **{time_text(e['wall_s'])}** ({e['wall_s']} s); CPU time {e['cpu_s']} s; "
            f"peak memory {e['peak_rss_mib']} MiB"
            + (f"; output {size_text(e['output_bytes'])}" if e.get("output_bytes") else ""),
            f"- load average {load['during_mean_1min']} (mean while it ran; max {load['during_max_1min']}; "
            f"{load['before'][0]} before)",
            f"- {e['date']}, commit `{e['commit']}`, exit status {e['exit_status']}",
            "",
        ]
    return "\n".join(lines).rstrip() + "\n"


def render(record):
    """Write docs/timings.md and restate every claim in README.md and docs/*.md; return the changed files."""
    changed = []
    text = page(record)
    if not PAGE.is_file() or PAGE.read_text(encoding="utf-8") != text:
        PAGE.write_text(text, encoding="utf-8")
        changed.append(PAGE)
    for path in claim_files():
        old = path.read_text(encoding="utf-8")
        new = rewrite_claims(old, record.get("runs", {}))
        if new != old:
            path.write_text(new, encoding="utf-8")
            changed.append(path)
    return changed


def imported(key, seconds, date, source):
    """The entry of a run measured elsewhere: its wall time, date and source."""
    what, args, program, writes = RUNS[key]
    return {
        "what": what,
        "command": " ".join([program] + args + (["--out", "DIR"] if writes else [])),
        "date": date,
        "commit": "unknown",
        "exit_status": 0,
        "last_line": "",
        "wall_s": float(seconds),
        "cpu_s": None,
        "peak_rss_mib": None,
        "output_bytes": None,
        "load_average": {"before": None, "during_mean_1min": None, "during_max_1min": None},
        "source": source,
    }


def main(argv=None):
    args = list(sys.argv[1:] if argv is None else argv)
    record = load_record()
    if args[:1] == ["--record"]:  # keep the stated figures: the docs test holds them to this run
        key, seconds, source = args[1:4]
        now = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
        record.setdefault("runs", {})[key] = dict(imported(key, seconds, now, source), upper=True)
        save_record(record)
        PAGE.write_text(page(record), encoding="utf-8")  # the record's own page, not the figures stated
        return
    if args[:1] == ["--import"]:
        key, seconds, date, source = args[1:5]
        record.setdefault("runs", {})[key] = imported(key, seconds, date, source)
        record["runs"] = {k: record["runs"][k] for k in RUNS if k in record["runs"]}
        save_record(record)
        args = ["--render"]
    if "--render" not in args:
        keys = args or list(RUNS)
        unknown = [k for k in keys if k not in RUNS]
        if unknown:
            sys.exit(f"unknown run(s) {unknown}; known: {', '.join(RUNS)}")
        for key in keys:
            print(f"measuring {key}: {RUNS[key][0]} ...", flush=True)
            entry = measure(key)
            record["machine"] = machine()
            record["regenerate"] = COMMAND
            record.setdefault("runs", {})[key] = entry
            record["runs"] = {k: record["runs"][k] for k in RUNS if k in record["runs"]}
            save_record(record)  # after each run: a long session keeps what it measured
            print(
                f"  {time_text(entry['wall_s'])} wall, {entry['cpu_s']} s CPU, load {entry['load_average']['during_mean_1min']}, "
                f"exit {entry['exit_status']}",
                flush=True,
            )
    for path in render(record):
        print(f"rewrote {path.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
