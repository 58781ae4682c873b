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


def plot_grosch(table, out):
    """Grosch's picture of a superposed study: the friction against the speed at each temperature,
    and the same points against the reduced speed v a_T, where they fall on the one curve that was
    solved (its nodes drawn as a line). ``[]`` unless the table holds that curve."""
    sweep = table["loads"][0]
    if not sweep.get("curve"):
        return []
    plt = pyplot()
    T = np.array(table["temperature"])
    v = np.array(sweep["speed"], dtype=float)
    mu = np.array(sweep["friction"], dtype=float)
    reduced = np.array(sweep["reduced_speed"], dtype=float)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11.0, 4.4), sharey=True)
    colors = plt.cm.coolwarm((T - T.min()) / max(np.ptp(T), 1e-12))
    for k in np.argsort(T):
        left.plot(v, mu[k], "o-", ms=3, lw=1, color=colors[k], label=f"{T[k]:.1f} K")
        right.plot(reduced[k], mu[k], "o", ms=3, color=colors[k])
    curve = sweep["curve"]
    right.plot(curve["reduced_speed"], np.array(curve["friction"], dtype=float), "k-", lw=1, label="the solved curve")
    left.set_xlabel("sliding speed v (m/s)")
    right.set_xlabel(f"reduced speed v a_T (m/s), at {table['shift']['reference_temperature']:g} K")
    left.set_ylabel("friction coefficient")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.grid(True, which="both", alpha=0.3)
    left.legend(fontsize="small")
    right.legend(fontsize="small")
    fig.suptitle(f"friction by time-temperature superposition (load {sweep['load']:g} N, or N/m for profiles)")
    return [save(fig, out / "friction_master_curve.png", dpi=110, tight=True)]


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
