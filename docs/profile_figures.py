"""The figure of docs/fem-profile.md: the FEM's and the BEM's pressure on a rough periodic profile.

    python docs/profile_figures.py

It solves the page's case (a self-affine profile of 16 wavelengths, a 4-term rubber at E_inf/E0 = 111
near its friction peak, 40 N/m a period) with :func:`fem_reference.sliding_profile`'s default call
and with the BEM on 4096 points, and draws both pressures over the profile into
``docs/figures/profile_pressures.png`` (matplotlib). The documentation build only shows the committed
PNG: it never runs this script.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

FIGURES = Path(__file__).resolve().parent / "figures"
L = 1e-3


def case():
    """The page's profile (heights, m) and rubber."""
    import bem

    rng = np.random.default_rng(3)
    x = np.arange(64) * L / 64
    h = sum(k**-1.8 * np.cos(2 * np.pi * k * x / L + rng.uniform(0, 2 * np.pi)) for k in range(1, 17))
    h = h * 2e-5 / np.ptp(h)
    rubber = bem.Material.from_prony(
        E0=1e6, moduli=np.array([5e7, 3e7, 2e7, 1e7]), times=np.array([1e-6, 1e-5, 1e-4, 1e-3]), nu=0.5
    )
    return h, rubber


def main():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import bem
    from bem.surfaces import Surface
    from fem_reference import sliding_profile
    from fem_reference.profile import profile_nodes

    h, rubber = case()
    xb = np.arange(4096) * L / 4096
    hb, _ = profile_nodes(h, L, xb)
    b = bem.solve(Surface(hb, L), rubber, speed=0.1, load=40.0)
    r = sliding_profile(rubber, heights=h, length=L, load=40.0, speed=0.1)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True, height_ratios=(1, 2))
    top.plot(xb * 1e3, hb * 1e6, color="0.3")
    top.set_ylabel("height (µm)")
    top.set_title(
        f"V = 0.1 m/s, 40 N/m: friction FEM {r.friction:.4f} (moment) / {r.friction_dissipation:.4f} "
        f"(dissipation), BEM {b.friction_eq6:.4f} / {b.friction:.4f}",
        fontsize=9,
    )
    bottom.plot(xb * 1e3, b.pressure / 1e6, color="tab:blue", lw=1.2, label="BEM, 4096 points")
    bottom.plot(r.x * 1e3, r.pressure / 1e6, "o", ms=2.5, color="tab:red", label=f"FEM nodes ({r.n_unknowns:,} unknowns)")
    for trail, lead in r.spots:  # a spot that wraps past x = L is drawn in two pieces
        bottom.axvspan(trail * 1e3, min(lead, L) * 1e3, color="tab:red", alpha=0.08, lw=0)
        if lead > L:
            bottom.axvspan(0.0, (lead - L) * 1e3, color="tab:red", alpha=0.08, lw=0)
    bottom.set_xlabel("x (mm); the profile slides in +x")
    bottom.set_ylabel("pressure (MPa)")
    bottom.legend(fontsize=8)
    fig.tight_layout()
    FIGURES.mkdir(exist_ok=True)
    fig.savefig(FIGURES / "profile_pressures.png", dpi=130)
    print(FIGURES / "profile_pressures.png")


if __name__ == "__main__":
    main()
