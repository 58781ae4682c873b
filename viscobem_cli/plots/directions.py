"""Polar plot of friction against the sliding direction."""

import numpy as np

from .style import pyplot, save


def polar_plot(table, path):
    """Polar plot of mu(theta): one closed curve per speed (directions as given, sorted)."""
    plt = pyplot()
    fig = plt.figure(figsize=(5.6, 5.2), constrained_layout=True)
    ax = fig.add_subplot(projection="polar")
    theta = np.asarray(table["direction_rad"], dtype=float)
    order = np.argsort(theta % (2 * np.pi))
    mu = np.array([[np.nan if v is None else v for v in row] for row in table["friction"]], dtype=float)
    for j, xi in enumerate(table["xi"]):
        t, m = theta[order], mu[order, j]
        closed = len(t) > 2
        ax.plot(
            np.append(t, t[0]) if closed else t, np.append(m, m[0]) if closed else m, "o-", ms=4, label=f"xi = {xi:.3g}"
        )
    ax.set_title("friction coefficient against sliding direction\n(angle from +x toward +y)", fontsize=9)
    ax.legend(fontsize=7, loc="lower left", bbox_to_anchor=(-0.1, -0.12))
    save(fig, path)
