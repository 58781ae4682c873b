"""PNG plots of a study: the friction curve and a pressure map (matplotlib, Agg)."""
from pathlib import Path

import numpy as np


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path):
    """PNG of ``fig`` written atomically (temporary file + rename): never a truncated plot."""
    import io

    from .study import write_atomic

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=120)
    write_atomic(path, buffer.getvalue(), mode="wb")


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
    _save(fig, path)
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
    _save(fig, path)
    plt.close(fig)


def write_all(scene, curve, fields, out):
    """Write the plots of a study; return the file names."""
    out = Path(out)
    names = []
    if scene.outputs["friction_curve"] and np.any(curve.success):
        friction_curve(scene, curve, out / "friction_curve.png")
        names.append("friction_curve.png")
    if fields:
        # the pressure map at the friction peak, where the contact is most distorted
        i = max(fields, key=lambda k: fields[k].friction)
        pressure_map(scene.surface, fields[i], scene.xi[i], out / "pressure_map.png")
        names.append("pressure_map.png")
    return names
