"""Temperature shifts the friction curve along the speed axis (time-temperature superposition).

A standard linear solid with a WLF shift law: at a temperature 10 K above the reference every
relaxation time is multiplied by a_T < 1, so the solid answers at speed v as the reference
solid at a_T v. The friction curve computed at that temperature lies on the reference curve
shifted by log10 a_T decades.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import bem
from bem.temperature import WLF

reference = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
law = WLF(8.86, 101.6, 296.15)  # C1, C2 (K), reference temperature (K)
warm = 306.15  # K
log_aT = float(law(warm))
print(f"log10 a_T at {warm - 273.15:.0f} C: {log_aT:.3f}")

surface = bem.surfaces.self_affine(64, 0.01, hurst=0.8, scales=16, rms_height=2e-5, seed=1)
speeds = np.logspace(-5, 1, 9)  # m/s
at_reference = bem.friction_curve(surface, reference, speeds=speeds, load=1.0)
at_warm = bem.friction_curve(surface, reference.at_temperature(warm, law), speeds=speeds, load=1.0)
shifted = bem.friction_curve(surface, reference, speeds=speeds * 10**log_aT, load=1.0)
error = np.max(np.abs(at_warm.friction - shifted.friction) / np.max(shifted.friction))
print(f"friction at {warm - 273.15:.0f} C against the shifted reference curve: {error:.1e}")

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "temperature_shift.png"
fig, ax = plt.subplots(figsize=(5.5, 3.6))
ax.semilogx(speeds, at_reference.friction, "o-", label="23 C (reference)")
ax.semilogx(speeds, at_warm.friction, "s-", label=f"{warm - 273.15:.0f} C")
ax.semilogx(speeds / 10**log_aT, at_reference.friction, "k:", label="23 C curve shifted by a_T")
ax.set_xlabel("sliding speed v (m/s)")
ax.set_ylabel(r"friction coefficient $\mu$")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
