"""The result of one steady sliding solve, :class:`SlidingResult`, shared by every solver."""

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from .accuracy.estimate import not_estimated

__all__ = ["SlidingResult"]


@dataclass(frozen=True, eq=False)
class SlidingResult:
    """Steady sliding contact solution (arrays shaped like the heights).

    Attributes
    ----------
    pressure : ndarray
        Contact pressure (Pa), >= 0.
    displacement : ndarray
        Normal surface displacement (m, positive into the solid). Periodic cells: zero mean
        (the periodic half-space has no defined mean displacement; the approach carries it).
        Isolated 2-D contacts: absolute (zero at infinity); isolated profiles: up to the
        constant of plane strain (see :mod:`bem.halfspace.isolated`).
    gap : ndarray
        ``displacement - (h - max(h) + approach)`` (m), >= 0, zero in contact.
    approach : float
        Rigid approach from first touch (m): relative to the mean plane of the deformed
        surface on periodic cells, to the undeformed surface far away for isolated 2-D
        contacts, and with the displacement's constant for isolated profiles.
    contact_fraction : float
        Fraction of the cell (isolated contacts: of the domain) in contact (``pressure > 0``).
    friction, friction_eq6 : float
        Viscoelastic friction coefficient, dissipation form and eq. 6 (see module doc).
    dissipated_power : float
        ``friction * load * speed`` (W; W/m for profiles).
    load, speed : float
        Normal force (N; N/m for profiles) and sliding speed (m/s).
    iterations, matvecs : int
        Active-set iterations and operator applications (FFT pairs).
    residual : float
        Complementarity residual reached (see :mod:`bem.contact`).
    success : bool
    message : str
    wall_time : float
        Seconds spent in the solve.
    error_estimate : bem.accuracy.ErrorEstimate
        Estimated relative discretisation error of ``friction``, ``contact_fraction`` and
        ``peak_pressure`` (a mapping; ``None`` where no estimate exists, with the reason in
        ``error_estimate.reasons``), see :mod:`bem.accuracy` and docs/theory.md §13.
    warnings : tuple of str
        One plain sentence per finding (an estimated error above 5 %, friction forms that
        disagree, a solve that did not converge, ...), each saying what to change.
    attainable : float or None
        When a solve stopped at its round-off floor (``rtol`` below what floating point allows
        this problem), the lowest residual it reached plus that floor (another path's round-off
        settles up to a floor higher): ask for at least this. Otherwise ``None``.
    """

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    approach: float
    contact_fraction: float
    friction: float
    friction_eq6: float
    dissipated_power: float
    load: float
    speed: float
    iterations: int
    matvecs: int
    residual: float
    success: bool
    message: str
    wall_time: float = 0.0
    error_estimate: Mapping = field(default_factory=lambda: not_estimated("not estimated"))
    warnings: tuple = ()
    attainable: float | None = None

    @property
    def peak_pressure(self):
        """Largest pressure (Pa) on the grid."""
        return float(np.max(self.pressure))

    def __repr__(self):
        """One line: the scalars and the fields' shape, never the arrays themselves."""
        status = "converged" if self.success else "NOT converged"
        return (
            f"{type(self).__name__}({status}, shape={self.pressure.shape}, speed={self.speed:.6g} m/s, "
            f"load={self.load:.6g}, friction={self.friction:.6g}, friction_eq6={self.friction_eq6:.6g}, "
            f"contact_fraction={self.contact_fraction:.6g}, approach={self.approach:.6g} m, "
            f"iterations={self.iterations}, matvecs={self.matvecs}, residual={self.residual:.3g})"
        )
