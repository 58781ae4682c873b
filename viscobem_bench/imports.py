"""``viscobem bench import``: import time of ``bem`` against numpy + scipy, and the CLI's start-up.

Each statement runs in fresh interpreters (``repeats`` times, the minimum kept, so that
a busy machine's noise mostly cancels) and is reported as a ratio to the reference
``import numpy, scipy.fft, scipy.sparse.linalg`` measured in the same run: the least any
FFT solver with Krylov inner solves must load. Two measures: the wall time of the whole
interpreter, and the import time alone (``python -X importtime``: the cumulative time of
the top-level imports, without the interpreter's start-up and ``site``), which is less
sensitive to a loaded machine. Writes ``DIR/import_bench.json``.
"""

import subprocess
import sys
import time
from pathlib import Path

from viscobem_bench import instruments

REFERENCE = "import numpy, scipy.fft, scipy.sparse.linalg"
STATEMENTS = {
    "python": "pass",
    "reference (numpy + scipy.fft + scipy.sparse.linalg)": REFERENCE,
    "import bem": "import bem",
    "a solve's imports (bem.solve, Material, surfaces)": "import bem; bem.solve; bem.Material; bem.surfaces",
    "viscobem --help": "from viscobem_cli.main import build_parser; build_parser().format_help()",
}


def time_statement(statement, repeats):
    """Shortest wall time (s) of a fresh interpreter running ``statement``."""
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", statement], check=True)
        best = min(best, time.perf_counter() - t0)
    return best


def import_time(statement, repeats):
    """Shortest total import time (s) of ``statement``'s top-level imports (``-X importtime``)."""
    best = float("inf")
    for _ in range(repeats):
        proc = subprocess.run(
            [sys.executable, "-X", "importtime", "-c", statement], check=True, capture_output=True, text=True
        )
        total = 0
        for line in proc.stderr.splitlines():
            fields = line.split("|")
            if len(fields) == 3 and fields[1].strip().isdigit():
                name = fields[2]
                if name.startswith(" ") and not name.startswith("  ") and name.strip() not in ("site", "encodings"):
                    total += int(fields[1])
        best = min(best, total * 1e-6)
    return best


def run(out_dir="bench-out", repeats=7, echo=print):
    """Measure, print a table and write ``import_bench.json``; return the numbers."""
    seconds = {name: time_statement(code, repeats) for name, code in STATEMENTS.items()}
    imports = {name: import_time(code, repeats) for name, code in STATEMENTS.items()}
    key = "reference (numpy + scipy.fft + scipy.sparse.linalg)"
    rows = [
        {
            "what": name,
            "statement": STATEMENTS[name],
            "seconds": t,
            "ratio_to_reference": t / seconds[key],
            "import_seconds": imports[name],
            "import_ratio_to_reference": imports[name] / imports[key],
        }
        for name, t in seconds.items()
    ]
    echo(f"{'what':54s} {'wall (s)':>9} {'/ ref':>6} {'imports (s)':>12} {'/ ref':>6}")
    for row in rows:
        echo(
            f"{row['what']:54s} {row['seconds']:9.3f} {row['ratio_to_reference']:6.2f} "
            f"{row['import_seconds']:12.3f} {row['import_ratio_to_reference']:6.2f}"
        )
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    record = {"repeats": repeats, "python": sys.version.split()[0], "rows": rows}

    instruments.write_record(out, "import_bench.json", record)
    return record


if __name__ == "__main__":
    run(sys.argv[1] if len(sys.argv) > 1 else "bench-out")
