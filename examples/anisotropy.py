"""Sliding makes an isotropic surface's deformed shape anisotropic.

The second spectral moment m2(theta) of the deformed surface (the displacement field) at a
slow and a fast speed, each whitened by the same realisation at rest, so that only the
speed-induced part remains.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import bem

material = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
L, tau = 0.01, 0.01
surface = bem.surfaces.self_affine(128, L, hurst=0.8, scales=32, rms_height=2e-5, seed=3)
theta = np.linspace(0, 2 * np.pi, 181)

rest = bem.solve(surface, material, speed=0.0, load=0.3)
reference = bem.anisotropy.spectral_moments(rest.displacement, L)
out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "anisotropy.png"
fig, ax = plt.subplots(figsize=(4.2, 4.2), subplot_kw={"projection": "polar"})
for xi in (1e-2, 1.0):
    result = bem.solve(surface, material, speed=xi * L / tau, load=0.3)
    moments = bem.anisotropy.spectral_moments(result.displacement, L)
    relative = bem.anisotropy.relative_moments(moments, reference)
    print(
        f"xi = {xi:g}: gamma = {moments.gamma:.3f}, relative gamma = {relative.gamma:.3f}, "
        f"Theta = {np.degrees(relative.theta_max):.0f} deg"
    )
    m2 = relative.m2(theta)
    ax.plot(theta, m2 / m2.max(), label=rf"$\xi$ = {xi:g}")
ax.set_title("relative m2(θ), normalised (sliding along θ = 0)", fontsize=9)
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(-0.12, 1.08))
fig.tight_layout()
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
