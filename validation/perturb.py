"""Deliberately wrong inputs for the solvers under test (``viscobem validate --sensitivity``).

A check is only as good as the mistake it catches. A :class:`Perturbation` scales one input
of a case -- the glassy modulus ``E_inf`` or the relaxed one ``E0`` (the other held fixed),
every relaxation time, the speed or the load -- and a :class:`Tamper` applies it to the
solvers under test while the references (exact solutions, the FEM where it is the reference)
keep the true inputs. The tamper records which solvers it actually changed: a perturbation
that leaves a solver's inputs as they were (the speed of a solve at rest, the relaxation
times of an elastic solid) does not change its physics and need not be caught.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Perturbation", "Tamper", "PERTURBATIONS", "NONE"]


@dataclass(frozen=True)
class Perturbation:
    """Factors on the inputs: ``E_inf`` and ``E0`` (each with the other modulus fixed, the
    Prony moduli scaled together), every relaxation time, speed and load."""

    name: str
    E_inf: float = 1.0
    E0: float = 1.0
    times: float = 1.0
    speed: float = 1.0
    load: float = 1.0

    @property
    def active(self):
        """Names of the inputs this perturbation changes."""
        return tuple(k for k in ("E_inf", "E0", "times", "speed", "load") if getattr(self, k) != 1.0)

    def material(self, m):
        """The perturbed :class:`bem.Material` (``m`` itself when nothing changes)."""
        from bem import Material

        if self.E_inf == 1.0 and self.E0 == 1.0 and (self.times == 1.0 or m.is_elastic):
            return m
        if m.is_elastic:  # one modulus: E_inf = E0 = E
            return Material.elastic(m.E0 * self.E_inf * self.E0, m.nu)
        E0, E_inf = m.E0 * self.E0, m.E_inf * self.E_inf
        moduli = np.asarray(m.moduli) * (E_inf - E0) / (m.E_inf - m.E0)
        return Material.from_prony(E0=E0, moduli=moduli, times=np.asarray(m.relaxation_times) * self.times, nu=m.nu)


NONE = Perturbation("none")
PERTURBATIONS = (
    Perturbation("E_inf +2%", E_inf=1.02),
    Perturbation("E_inf -2%", E_inf=0.98),
    Perturbation("E0 +2%", E0=1.02),
    Perturbation("E0 -2%", E0=0.98),
    Perturbation("relaxation times +5%", times=1.05),
    Perturbation("speed +5%", speed=1.05),
    Perturbation("load +2%", load=1.02),
)


class Tamper:
    """Applies one :class:`Perturbation` to the inputs of named solvers and remembers which
    solvers it changed (``changed``). ``cache`` keeps reference results between the runs of
    one case under different perturbations (the references never change)."""

    def __init__(self, perturbation=NONE, cache=None):
        self.perturbation = perturbation
        self.changed = set()
        self.cache = {} if cache is None else cache

    def inputs(self, solver, material, speed, load, insensitive=()):
        """``(material, speed, load)`` as solver ``solver`` should see them.

        ``insensitive`` names the inputs (``"times"``, ``"speed"``, ...) the compared quantities do
        not depend on (e.g. the relaxation times in the two elastic limits of a step load): a
        perturbation of those is applied but not counted as a change of the solver's physics."""
        p = self.perturbation
        m2, v2, l2 = p.material(material), speed * p.speed, load * p.load
        if (m2 is not material or v2 != speed or l2 != load) and not set(p.active) & set(insensitive):
            self.changed.add(solver)
        return m2, v2, l2

    def reference(self, key, fn, *args, **kwargs):
        """``fn(*args, **kwargs)``, computed once per ``key`` for every perturbation."""
        if key not in self.cache:
            self.cache[key] = fn(*args, **kwargs)
        return self.cache[key]
