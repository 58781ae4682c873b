"""Friction against speed: a rough surface sliding over a standard linear solid.

A self-affine surface (H = 0.8, 16 scales) on a 64² periodic cell slides over the seed
paper's material. Friction is small at both ends, where the solid answers elastically
with E0 (slow) or E_inf (fast), and peaks in between: the bell-shaped curve.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import bem

material = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
L = 0.01  # m, cell side
surface = bem.surfaces.self_affine(64, L, hurst=0.8, scales=16, rms_height=2e-5, seed=1)
tau = 0.01  # s, the time that makes the speed dimensionless: xi = v tau / L
xi = np.logspace(-4, 2, 13)
curve = bem.friction_curve(surface, material, speeds=xi * L / tau, load=0.3)
assert curve.all_converged, curve.messages

peak = np.argmax(curve.friction)
print(f"friction peak {curve.friction[peak]:.4f} at xi = {xi[peak]:.3g}")
print(f"contact area {100 * curve.contact_fraction[0]:.2f} % (slow) .. {100 * curve.contact_fraction[-1]:.2f} % (fast)")

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "friction_curve.png"
fig, ax = plt.subplots(figsize=(5.5, 3.6))
ax.semilogx(xi, curve.friction, "o-", label="dissipation form (friction)")
ax.semilogx(xi, curve.friction_eq6, "x--", label="direct form (friction_eq6)")
ax.set_xlabel(r"$\xi = v\tau/L$")
ax.set_ylabel(r"friction coefficient $\mu$")
ax.legend()
fig.tight_layout()
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
