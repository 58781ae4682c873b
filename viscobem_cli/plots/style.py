"""What every plot of a study shares: the Agg backend, atomic PNG writes, the xi axis and its
speed twin, the sliding arrow, and number labels on short log axes."""

from pathlib import Path

import numpy as np


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, path, *, dpi=120, tight=False):
    """PNG of ``fig`` written atomically (temporary file + rename), then closed: never a
    truncated plot. Returns the file's name."""
    import io

    from ..files import write_atomic

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, **({"bbox_inches": "tight"} if tight else {}))
    write_atomic(path, buffer.getvalue(), mode="wb")
    pyplot().close(fig)
    return Path(path).name


def nan_array(values):
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def sliding_arrow(ax, direction=0.0):
    """The sliding direction (radians from +x) as an arrow above the map."""
    c, s = np.cos(direction), np.sin(direction)
    if direction == 0:
        ax.annotate(
            "", xy=(0.9, 1.04), xytext=(0.6, 1.04), xycoords="axes fraction", arrowprops={"arrowstyle": "->", "lw": 2}
        )
        ax.text(0.58, 1.04, "sliding (+x)", transform=ax.transAxes, ha="right", va="center", fontsize=8)
        return
    ax.annotate(
        "",
        xy=(0.9 + 0.045 * c, 1.04 + 0.045 * s),
        xytext=(0.9 - 0.045 * c, 1.04 - 0.045 * s),
        xycoords="axes fraction",
        arrowprops={"arrowstyle": "->", "lw": 2},
    )
    ax.text(
        0.0,
        1.04,
        f"sliding {np.degrees(direction):.4g}° from +x",
        transform=ax.transAxes,
        ha="left",
        va="center",
        fontsize=8,
    )


def mark_peak(ax, xi, peak):
    if peak is not None:
        ax.axvline(xi[peak], color="0.6", ls=":", lw=1)


def label_log_axis(axis):
    """Numbers on a log axis that spans less than two decades: label its minor ticks too
    (otherwise such an axis may show one label or none)."""
    import matplotlib.ticker as mticker

    lo, hi = axis.get_view_interval()
    if lo > 0 and np.log10(hi / lo) < 2:
        axis.set_minor_formatter(mticker.LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(2, 0.4)))


def speed_first(scene):
    """True when a sweep is plotted against the speed (m/s), xi on the secondary axis: for a fitted
    or many-term material, whose tau in xi = v tau / L is only its longest time (hours for a DMA
    rubber) and means nothing to its user; a one-time material keeps xi, the seed paper's axis."""
    return getattr(scene, "dma", None) is not None or np.size(scene.material.creep_times) > 1


def sweep_axis(ax, scene):
    """The x values of a speed sweep on ``ax`` (log scale, labelled), with the other of speed and
    xi on a secondary axis on top (:func:`speed_first` picks the main one)."""
    k = scene.xi_length / scene.xi_time  # v = k xi
    ax.set_xscale("log")
    if speed_first(scene):
        ax.set_xlabel("sliding speed v (m/s)", fontsize=9)
        top = ax.secondary_xaxis("top", functions=(lambda v: v / k, lambda x: x * k))
        top.set_xlabel(xi_label(scene), fontsize=8)
        x = np.asarray(scene.xi) * k
    else:
        ax.set_xlabel(xi_label(scene), fontsize=9)
        top = ax.secondary_xaxis("top", functions=(lambda x: x * k, lambda v: v / k))
        top.set_xlabel("sliding speed v (m/s)", fontsize=8)
        x = np.asarray(scene.xi)
    top.tick_params(labelsize=7)
    return x


def xi_label(scene):
    where = "a_0" if scene.xi_length != scene.surface.length else "L"
    return rf"$\xi = v\,\tau / {where}$  ($\tau$ = {scene.xi_time:.3g} s, ${where}$ = {scene.xi_length * 1e3:.3g} mm)"
