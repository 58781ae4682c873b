"""Every gallery example (examples/*.py) runs as a user would run it, and writes its figure.

Each script is copied alone into an empty folder and run there in a fresh interpreter, with the
folder as its working directory and no path to the repository: an example that leans on a
helper file beside it (``from _common import ...``) or on being started from ``examples/``
fails here, as it would for a user who copies it from the gallery.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SCRIPTS = sorted(EXAMPLES.glob("*.py"))


def test_examples_are_found():
    assert len(SCRIPTS) >= 5, f"expected the gallery scripts in {EXAMPLES}, found {SCRIPTS}"


def test_examples_folder_holds_only_examples():
    """Every file in examples/ is a gallery page: no helper module they could import."""
    helpers = [p.name for p in EXAMPLES.iterdir() if p.suffix == ".py" and p.name.startswith("_")]
    assert not helpers, f"examples/ holds helper modules {helpers}; each example must be self-contained"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_example_runs_when_copied_alone(script, tmp_path):
    alone = tmp_path / "copied"
    alone.mkdir()
    shutil.copy(script, alone / script.name)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["MPLBACKEND"] = "Agg"
    run = subprocess.run(
        [sys.executable, script.name, "figures"],
        check=False,
        cwd=alone,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, f"{script.name} failed when copied alone:\n{run.stdout}\n{run.stderr}"
    figure = alone / "figures" / f"{script.stem}.png"
    assert figure.is_file() and figure.stat().st_size > 1000, f"{script.name} wrote no figure"
    assert f"wrote {figure.name}" in run.stdout
