"""Every gallery example (examples/*.py) runs as written and writes its figure.

Each runs in a fresh interpreter, as a user would run it, with a temporary output folder.
"""

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SCRIPTS = sorted(p for p in EXAMPLES.glob("*.py") if not p.name.startswith("_"))


def test_examples_are_found():
    assert len(SCRIPTS) >= 5, f"expected the gallery scripts in {EXAMPLES}, found {SCRIPTS}"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_example_runs(script, tmp_path):
    run = subprocess.run(
        [sys.executable, str(script), str(tmp_path)],
        check=False,
        cwd=EXAMPLES,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, f"{script.name} failed:\n{run.stdout}\n{run.stderr}"
    figure = tmp_path / f"{script.stem}.png"
    assert figure.is_file() and figure.stat().st_size > 1000, f"{script.name} wrote no figure"
    assert f"wrote {figure.name}" in run.stdout
