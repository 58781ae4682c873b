"""Shared by the examples: where to write figures (not an example itself)."""

import os
import sys
from pathlib import Path


def output_dir():
    """The folder for figures: the first argument, else $VISCOBEM_EXAMPLE_OUT, else '.'."""
    out = Path(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("VISCOBEM_EXAMPLE_OUT", "."))
    out.mkdir(parents=True, exist_ok=True)
    return out


def figure(name):
    """A matplotlib figure and axes on the non-interactive Agg backend, and its file path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt, output_dir() / f"{name}.png"
