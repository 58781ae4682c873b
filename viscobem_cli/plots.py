"""PNG plots of a study: the friction curve and a pressure map, or for isolated indenters
pressure maps at three speeds and contact outlines (matplotlib, Agg)."""
from pathlib import Path

import numpy as np


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def friction_curve(scene, curve, path):
    """Friction (both forms) and contact fraction against xi, log axes."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.2), constrained_layout=True)
    ok = curve.success
    ax.semilogx(scene.xi[ok], curve.friction[ok], "o-", label=r"$\mu$ (dissipation)")
    ax.semilogx(scene.xi[ok], curve.friction_eq6[ok], "s--", ms=4, label=r"$\mu$ (eq. 6)")
    ax.set_xlabel(r"$\xi = v\,\tau / L$")
    ax.set_ylabel("friction coefficient")
    ax.grid(True, which="both", alpha=0.3)
    ax2 = ax.twinx()
    ax2.semilogx(scene.xi[ok], curve.contact_fraction[ok], "^:", color="tab:green", label="contact fraction")
    ax2.set_ylabel("contact fraction", color="tab:green")
    lines = ax.get_legend_handles_labels()
    lines2 = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], loc="best", fontsize=8)
    ax.set_title(scene.title, fontsize=9)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def pressure_map(surface, result, xi, path):
    """Pressure (1-D: profile; 2-D: map with the sliding direction marked)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5.6, 4.6), constrained_layout=True)
    x = surface.x * 1e3
    if surface.ndim == 1:
        ax.plot(x, result.pressure / 1e6)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("pressure (MPa)")
    else:
        ext = [0, surface.length * 1e3, 0, surface.length * 1e3]
        im = ax.imshow(result.pressure.T / 1e6, origin="lower", extent=ext, cmap="magma", interpolation="nearest")
        fig.colorbar(im, ax=ax, label="pressure (MPa)")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.annotate("", xy=(0.9, 1.04), xytext=(0.6, 1.04), xycoords="axes fraction",
                    arrowprops={"arrowstyle": "->", "lw": 2})
        ax.text(0.58, 1.04, "sliding (+x)", transform=ax.transAxes, ha="right", va="center", fontsize=8)
    ax.set_title(rf"$\xi$ = {xi:.3g}: $\mu$ = {result.friction:.4g}, contact {100 * result.contact_fraction:.2f} %",
                 fontsize=9, pad=18)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _three_speeds(fields):
    """Indices of the slowest point, the friction peak and the fastest point (distinct, sorted)."""
    keys = sorted(fields, key=lambda k: fields[k].speed)
    peak = max(fields, key=lambda k: fields[k].friction)
    return sorted({keys[0], peak, keys[-1]}, key=lambda k: fields[k].speed)


def indenter_maps(scene, fields, out):
    """Isolated indenter: pressure at three speeds (slowest, friction peak, fastest) and the
    contact outlines of every computed speed. Returns the file names written."""
    plt = _pyplot()
    surface = scene.surface
    x = surface.x * 1e3
    picks = _three_speeds(fields)
    if surface.ndim == 1:
        fig, ax = plt.subplots(figsize=(6.4, 4.2), constrained_layout=True)
        for k in picks:
            r = fields[k]
            ax.plot(x, r.pressure / 1e6, label=rf"$\xi$ = {scene.xi[k]:.3g}, $\mu$ = {r.friction:.3g}")
        ax.set_xlabel("x (mm), sliding toward +x")
        ax.set_ylabel("pressure (MPa)")
        ax.legend(fontsize=8)
        ax.set_title(scene.title, fontsize=9)
        fig.savefig(out / "pressure_profiles.png", dpi=120)
        plt.close(fig)
        return ["pressure_profiles.png"]
    ext = [x[0] - surface.spacing * 5e2, x[-1] + surface.spacing * 5e2] * 2
    fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 4.0), constrained_layout=True,
                             squeeze=False)
    for ax, k in zip(axes[0], picks):
        r = fields[k]
        im = ax.imshow(r.pressure.T / 1e6, origin="lower", extent=ext, cmap="magma", interpolation="nearest")
        ax.contour(x, x, (r.pressure > 0).T.astype(float), levels=[0.5], colors="c", linewidths=0.8)
        fig.colorbar(im, ax=ax, label="pressure (MPa)", shrink=0.8)
        ax.set_xlabel("x (mm), sliding toward +x")
        ax.set_ylabel("y (mm)")
        ax.set_title(rf"$\xi$ = {scene.xi[k]:.3g}: $\mu$ = {r.friction:.3g}", fontsize=9)
    fig.savefig(out / "pressure_maps.png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5.2, 4.6), constrained_layout=True)
    keys = sorted(fields, key=lambda k: fields[k].speed)
    colours = plt.cm.viridis(np.linspace(0, 1, len(keys)))
    for c, k in zip(colours, keys):
        ax.contour(x, x, (fields[k].pressure > 0).T.astype(float), levels=[0.5], colors=[c], linewidths=1.0)
    sm = plt.cm.ScalarMappable(cmap="viridis", norm=plt.matplotlib.colors.LogNorm(
        vmin=scene.xi[keys[0]], vmax=max(scene.xi[keys[-1]], scene.xi[keys[0]] * 1.0001)))
    fig.colorbar(sm, ax=ax, label=r"$\xi = v\,\tau / L$")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm), sliding toward +x")
    ax.set_ylabel("y (mm)")
    ax.set_title("contact outlines", fontsize=9)
    fig.savefig(out / "contact_outlines.png", dpi=120)
    plt.close(fig)
    return ["pressure_maps.png", "contact_outlines.png"]


def write_all(scene, curve, fields, out):
    """Write the plots of a study; return the file names."""
    out = Path(out)
    names = []
    if scene.outputs["friction_curve"] and np.any(curve.success):
        friction_curve(scene, curve, out / "friction_curve.png")
        names.append("friction_curve.png")
    if fields and not scene.periodic:
        names += indenter_maps(scene, fields, out)
    elif fields:
        # the pressure map at the friction peak, where the contact is most distorted
        i = max(fields, key=lambda k: fields[k].friction)
        pressure_map(scene.surface, fields[i], scene.xi[i], out / "pressure_map.png")
        names.append("pressure_map.png")
    return names
