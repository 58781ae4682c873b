"""One material, two forms: a Prony (relaxation) series and its exact creep series.

A three-term Prony series is converted to its retardation (creep) form; the product
E(w) J(w) is 1 to round-off over twelve decades of frequency.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import bem

material = bem.Material.from_prony(E0=1e6, moduli=[2e6, 1e7, 5e7], times=[1e-1, 1e-3, 1e-5])
print("relaxation times (s):", material.relaxation_times)
print("creep (retardation) times (s):", material.creep_times)
print("creep compliances (1/Pa):", material.compliances)

w = np.logspace(-4, 8, 400)  # rad/s
E = material.complex_modulus(w)
J = material.complex_compliance(w)
print(f"max |E(w) J(w) - 1| = {np.max(np.abs(E * J - 1)):.1e}")

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")  # the figure's folder
out.mkdir(parents=True, exist_ok=True)
path = out / "material_forms.png"
fig, ax = plt.subplots(figsize=(5.5, 3.6))
ax.loglog(w, E.real, label="storage E'")
ax.loglog(w, E.imag, label="loss E''")
ax.loglog(w, (1 / J).real, "k:", label="1 / J(w), real part")
ax.set_xlabel(r"angular frequency $\omega$ (rad/s)")
ax.set_ylabel("modulus (Pa)")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(path, dpi=110)
print(f"wrote {path.name}")
