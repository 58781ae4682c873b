"""Plots of temperature studies: friction over speed and temperature, and the master curve."""

import numpy as np

from .style import pyplot, save


def plot_temperature_sweep(table, out):
    """Heat map of the friction coefficient over (log10 v, T) and curves per temperature."""
    plt = pyplot()

    T = np.array(table["temperature"])
    sweep = table["loads"][0]
    v = np.array(sweep["speed"], dtype=float)
    mu = np.array([[np.nan if x is None else x for x in row] for row in sweep["friction"]], dtype=float)
    written = []
    moving = v > 0
    if moving.sum() >= 2 and T.size >= 2:
        order = np.argsort(T)
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        mesh = ax.pcolormesh(np.log10(v[moving]), T[order], mu[order][:, moving], shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label="friction coefficient")
        ax.set_xlabel("log10 sliding speed (m/s)")
        ax.set_ylabel("temperature (K)")
        ax.set_title(f"friction against speed and temperature (load {sweep['load']:g} N, or N/m for profiles)")
        written.append(save(fig, out / "friction_speed_temperature.png", dpi=110, tight=True))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for k in np.argsort(T):
        ax.plot(v[moving], mu[k][moving], marker="o", ms=3, label=f"{T[k]:.1f} K")
    ax.set_xscale("log")
    ax.set_xlabel("sliding speed (m/s)")
    ax.set_ylabel("friction coefficient")
    ax.legend(fontsize="small")
    written.append(save(fig, out / "friction_curves_temperatures.png", dpi=110, tight=True))
    return written


def plot_master_curve(data, material, law, path):
    """Raw sweeps (E', E'' against w), the same shifted to the reference by ``law``, and the fit."""
    plt = pyplot()

    w, T = data["w"], data["T"]
    wr = w * 10.0 ** law(T)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
    colors = plt.cm.coolwarm((T - T.min()) / max(np.ptp(T), 1e-12))
    for ax, x, title in (
        (axes[0], w, "measured sweeps"),
        (axes[1], wr, f"shifted to {law.reference_temperature:g} K, and the fit"),
    ):
        ax.scatter(x, data["e1"], s=8, c=colors, marker="o", label="E' (data)")
        ax.scatter(x, data["e2"], s=8, c=colors, marker="^", label="E'' (data)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("angular frequency (rad/s)" if x is w else "reduced frequency a_T w (rad/s)")
        ax.set_title(title)
    grid = np.logspace(np.log10(wr.min()), np.log10(wr.max()), 400)
    e = material.complex_modulus(grid)
    axes[1].plot(grid, e.real, "k-", lw=1.2, label="E' (Prony fit)")
    axes[1].plot(grid, e.imag, "k--", lw=1.2, label="E'' (Prony fit)")
    axes[0].set_ylabel("modulus (Pa); colour: temperature (blue cold, red hot)")
    axes[1].legend(fontsize="small")
    name = type(law).__name__
    params = ", ".join(f"{k} = {v:.4g}" for k, v in vars(law).items() if k != "reference_temperature")
    fig.suptitle(f"master curve: {name} ({params})")
    return save(fig, path, dpi=110, tight=True)
