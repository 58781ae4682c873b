"""A rigid sphere sliding on a standard linear solid: the contact turns asymmetric.

Isolated contact (zero-padded FFT on a 96² domain of four relaxed contact radii). At low
speed the pressure is Hertz's with the relaxed modulus; near V tau ~ a0 the pressure piles up
toward the leading edge (+x) and the trailing side of the contact shrinks.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt

import bem

material = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
R, F = 0.01, 1.0  # m, N
sphere = bem.surfaces.sphere(radius=R, n=96, length=0.005)
a0 = (3 * F * R * (1 - 0.5**2) / (4 * material.E0)) ** (1 / 3)  # relaxed Hertz radius (m)
print(f"relaxed Hertz contact radius a0 = {1e3 * a0:.3f} mm")

x = 1e3 * sphere.x
ratios = [0.03, 0.3, 3.0]  # V tau / a0, tau the creep time
results = [bem.solve(sphere, material, speed=r * a0 / 0.01, load=F, periodic=False) for r in ratios]
peak = max(1e-6 * r.pressure.max() for r in results)

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "sphere_sliding.png"
fig, axes = plt.subplots(1, 3, figsize=(9.6, 3.3), sharey=True, layout="constrained")
for ax, ratio, result in zip(axes, ratios, results):
    area = result.contact_fraction * sphere.length**2
    print(
        f"V tau/a0 = {ratio:4.2f}: friction {result.friction:.4f}, "
        f"contact area {1e6 * area:.3f} mm², peak {1e-6 * result.pressure.max():.3f} MPa"
    )
    image = ax.pcolormesh(x, x, 1e-6 * result.pressure.T, shading="nearest", cmap="viridis", vmin=0, vmax=peak)
    ax.contour(x, x, (result.pressure > 0).T.astype(float), levels=[0.5], colors="w")
    ax.set_title(rf"$V\tau/a_0$ = {ratio:g}", fontsize=10)
    ax.set_xlabel("x (mm), sliding toward +x")
    ax.set_aspect("equal")
    ax.set_xlim(-2, 2)
    ax.set_ylim(-2, 2)
axes[0].set_ylabel("y (mm)")
fig.colorbar(image, ax=axes, label="pressure (MPa)", shrink=0.85)
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
