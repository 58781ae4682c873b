"""A rigid cylinder rolling on a standard linear solid, against Hunter's exact solution.

The 1-D isolated BEM (plane strain, DC-FFT) is compared with Hunter's (1961) closed form at
three speeds: the pressure peak moves to the leading edge (+x) as the speed rises.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import bem
from validation.references.hunter import rolling_cylinder

material = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
R, P = 0.01, 1000.0  # m, N/m
profile = bem.surfaces.cylinder(radius=R, n=1024, length=0.012)
x = profile.x

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "hunter_cylinder.png"
fig, ax = plt.subplots(figsize=(5.5, 3.6))
for speed, colour in [(0.02, "C0"), (0.2, "C1"), (2.0, "C2")]:
    result = bem.solve(profile, material, speed=speed, load=P, periodic=False)
    exact = rolling_cylinder(material, radius=R, load=P, speed=speed)
    error = abs(result.friction - exact.friction) / exact.friction
    print(
        f"v = {speed:5.2f} m/s: friction {result.friction:.5f}, Hunter {exact.friction:.5f} "
        f"(relative difference {error:.1e})"
    )
    dense = np.linspace(exact.trailing_edge, exact.leading_edge, 400)
    ax.plot(1e3 * dense, 1e-6 * exact.pressure(dense), "-", color=colour, lw=1, label=f"Hunter, v = {speed} m/s")
    ax.plot(1e3 * x[::8], 1e-6 * result.pressure[::8], "o", color=colour, ms=3)
ax.set_xlim(-2.5, 2.5)
ax.set_xlabel("x (mm), rolling toward +x")
ax.set_ylabel("pressure (MPa)")
ax.legend(fontsize=8, title="lines: exact; markers: BEM", title_fontsize=8)
fig.tight_layout()
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
