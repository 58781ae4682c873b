"""The README is a short front door whose commands and quick start work as written."""

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
SETUP = [
    "python3 -m venv .venv && . .venv/bin/activate && pip install . && viscobem run",
    'python3 -m venv .venv && . .venv/bin/activate && pip install ".[test]" && pytest',
]


def test_readme_is_short():
    assert len(README) <= 8000, f"README.md has {len(README)} characters; keep it at most 8000"


def test_readme_starts_with_the_two_setup_commands():
    first_block = re.search(r"```sh\n(.*?)```", README, re.DOTALL).group(1).splitlines()
    assert first_block[:2] == SETUP
    assert README.index("```sh") < README.index("\n## ")


def test_readme_python_quick_start_runs(tmp_path):
    code = re.search(r"```python\n(.*?)```", README, re.DOTALL).group(1)
    run = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300, check=False
    )
    assert run.returncode == 0, run.stderr
    assert "True" in run.stdout  # result.success


def test_readme_links_resolve():
    for target in re.findall(r"\]\(((?!https?:)[^)#]+)\)", README):
        assert (ROOT / target).exists(), f"README links to missing {target}"


def test_readme_says_how_its_scene_differs_from_the_default():
    """The README's scene is smaller than `viscobem run`'s; the numbers it gives for the default
    are the built-in seed scene's."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    from viscobem_cli.catalog import scene_path

    seed = tomllib.loads(scene_path(None).read_text(encoding="utf-8"))
    shown = tomllib.loads(re.search(r"```toml\n(.*?)```", README, re.DOTALL).group(1))
    said = re.search(r"This one is a\s+smaller study than the default \((.*?)\)", README, re.DOTALL).group(1)
    said = " ".join(said.split())
    for key, unit in (("n", "²"), ("scales", "")):
        assert f"{shown['surface'][key]}{unit}" in said and f"{seed['surface'][key]}{unit}" in said
    assert f"{shown['loading']['xi']['num']} speeds instead of {seed['loading']['xi']['num']}" in said
    assert f"{shown['loading']['load']:g} N instead of {seed['loading']['load']:.2f} N" in said
