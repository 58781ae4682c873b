"""Partial contact of an elastic half-space with a rigid sinusoid (Westergaard 1939).

The periodic 1-D BEM against the exact pressure at half the full-contact load.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import bem
from validation.references.westergaard import westergaard

E, nu = 1e7, 0.5
wavelength, amplitude = 1e-3, 1e-5  # m
profile = bem.surfaces.sinusoid(512, wavelength, amplitude=amplitude, wavelength=wavelength)
exact_full = westergaard(amplitude, wavelength, 1.0, E, nu)
p_mean = 0.5 * exact_full.full_contact_pressure
exact = westergaard(amplitude, wavelength, p_mean, E, nu)

result = bem.solve(profile, bem.Material.elastic(E, nu=nu), speed=0.0, load=p_mean * wavelength)
x = profile.x
x_exact = x - x[np.argmax(profile.heights)]  # exact solution centred on the crest
p_exact = exact.pressure(x_exact)
error = np.linalg.norm(result.pressure - p_exact) / np.linalg.norm(p_exact)
print(f"contact fraction {result.contact_fraction:.4f}, exact {2 * exact.half_width / wavelength:.4f}")
print(f"relative L2 pressure error {error:.2e}")

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "westergaard.png"
fig, ax = plt.subplots(figsize=(5.5, 3.4))
ax.plot(1e3 * x, 1e-6 * p_exact, "k-", lw=1, label="Westergaard (exact)")
ax.plot(1e3 * x[::6], 1e-6 * result.pressure[::6], "o", ms=3, label="periodic BEM, 512 points")
ax.set_xlabel("x (mm)")
ax.set_ylabel("pressure (MPa)")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
