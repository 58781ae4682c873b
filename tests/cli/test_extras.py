"""Every entry point with every optional package absent: one line naming the extra, never a
traceback.

Each command runs in a fresh interpreter in which the optional packages are made unimportable
(a ``sitecustomize`` on ``PYTHONPATH`` puts a finder first on ``sys.meta_path`` that raises
``ModuleNotFoundError`` for them and their submodules, as for a package that is not
installed; worker processes inherit it). Commands that merely could use an extra must run
through; commands that were asked for one must stop before any work, with status 2 and a
single line that names the extra.
"""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from conftest import make_tiny_scene

from viscobem_cli.catalog import EXTRAS

ROOT = Path(__file__).resolve().parents[2]
ALL = sorted(EXTRAS)
BLOCKER = textwrap.dedent(
    """
    import os, sys

    class _Absent:
        blocked = set(filter(None, os.environ.get("VISCOBEM_TEST_ABSENT", "").split(",")))

        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in self.blocked:
                raise ModuleNotFoundError(f"No module named {name!r}", name=name)
            return None

    sys.meta_path.insert(0, _Absent())
    """
)
SCENE = make_tiny_scene("plots = false\nvtk = {vtk}")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    folder = tmp_path_factory.mktemp("absent")
    (folder / "sitecustomize.py").write_text(BLOCKER)
    return folder


def viscobem(site, absent, *args, cwd, timeout=600):
    env = dict(os.environ, VISCOBEM_TEST_ABSENT=",".join(absent), MPLBACKEND="Agg")
    env["PYTHONPATH"] = os.pathsep.join([str(site), str(ROOT)] + [p for p in [os.environ.get("PYTHONPATH")] if p])
    return subprocess.run(
        [sys.executable, "-m", "viscobem_cli.main", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def one_line_naming(run, extra):
    lines = run.stderr.strip().splitlines()
    assert "Traceback" not in run.stderr + run.stdout, run.stderr
    assert run.returncode == 2, (run.returncode, run.stdout, run.stderr)
    assert len(lines) == 1 and f'pip install "viscobem[{extra}]"' in lines[0], run.stderr


def test_the_blocker_blocks(site, tmp_path):
    """The check can fail: with pyvista absent, importing it raises as for a missing package."""
    env = dict(os.environ, VISCOBEM_TEST_ABSENT="pyvista", PYTHONPATH=str(site))
    run = subprocess.run(
        [sys.executable, "-c", "import pyvista"], env=env, capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert run.returncode == 1 and "ModuleNotFoundError: No module named 'pyvista'" in run.stderr


@pytest.mark.parametrize("args", [["--help"], ["--version"], ["scene"], ["scene", "sphere"]], ids=lambda a: " ".join(a))
def test_light_commands_need_no_extra(site, tmp_path, args):
    run = viscobem(site, ALL, *args, cwd=tmp_path)
    assert run.returncode == 0 and not run.stderr, run.stderr


def test_run_needs_no_extra(site, tmp_path):
    (tmp_path / "s.toml").write_text(SCENE.format(vtk="false"))
    run = viscobem(site, ALL, "run", "s.toml", "--out", "out", "--no-progress", cwd=tmp_path)
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stderr
    assert (tmp_path / "out" / "results.json").is_file()


def test_validate_on_the_basic_install(site, tmp_path):
    """Without pyvista: every report but the VTK files, and one line on how to get them; the FEM
    on SuperLU without pypardiso, said in one line."""
    run = viscobem(
        site,
        ALL,
        "validate",
        "--quick",
        "--case",
        "westergaard",
        "--case",
        "cylinder_sls_r3",
        "--no-plots",
        "--no-progress",
        "--no-baseline",
        "--out",
        "v",
        cwd=tmp_path,
    )
    assert run.returncode == 0 and "Traceback" not in run.stderr + run.stdout, run.stdout + run.stderr
    notes = [line for line in run.stdout.splitlines() if "pip install" in line]
    assert len(notes) == 2, run.stdout
    assert "no VTK files" in notes[0] and 'pip install "viscobem[vtk]"' in notes[0]
    assert "SuperLU" in notes[1] and 'pip install "viscobem[fem]"' in notes[1]
    for name in ("report.json", "report.md", "report.html"):
        assert (tmp_path / "v" / name).is_file()
    assert not (tmp_path / "v" / "vtk").exists()


def test_vtk_asked_for(site, tmp_path):
    (tmp_path / "s.toml").write_text(SCENE.format(vtk="true"))
    one_line_naming(viscobem(site, ["pyvista", "vtk"], "run", "s.toml", "--out", "out", cwd=tmp_path), "vtk")
    assert not (tmp_path / "out").exists()  # stopped before any work


def test_dask_scheduler_asked_for(site, tmp_path):
    (tmp_path / "s.toml").write_text(SCENE.format(vtk="false"))
    run = viscobem(
        site, ["dask", "distributed"], "run", "s.toml", "--scheduler", "tcp://127.0.0.1:1", "--out", "o", cwd=tmp_path
    )
    one_line_naming(run, "dask")


def test_measured_topography_asked_for(site, tmp_path):
    (tmp_path / "scan.x3p").write_bytes(b"not read: the reader is missing")
    scene = SCENE.format(vtk="false").replace('kind = "self_affine"', 'kind = "measured"\npath = "scan.x3p"')
    scene = "\n".join(
        line
        for line in scene.splitlines()
        if line.split(" =")[0] not in {"length", "hurst", "scales", "rms_height", "seed", "nu"}
    )
    (tmp_path / "m.toml").write_text(scene)
    one_line_naming(viscobem(site, ["SurfaceTopography"], "run", "m.toml", "--out", "o", cwd=tmp_path), "topography")


def test_pyvisco_benchmark_asked_for(site, tmp_path):
    one_line_naming(viscobem(site, ["pyvisco"], "bench", "materials", "--quick", "--out", "b", cwd=tmp_path), "pyvisco")


def test_import_benchmark_without_psutil(site, tmp_path):
    run = viscobem(site, ALL, "bench", "import", "--quick", "--out", "b", cwd=tmp_path)
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stderr
