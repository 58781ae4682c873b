"""The estimated relative discretisation error of a result, :class:`ErrorEstimate`, and the
default estimate from a solution's own indicators (:func:`from_indicators`).

What is estimated: for each quantity ``Q`` in :data:`QUANTITIES`, ``|Q_n - Q_2n| / |Q_2n|``,
the change of ``Q`` when the same surface content is solved on a grid with twice the points
per axis (docs/theory.md §13). The default estimate is an expected magnitude built from
:mod:`bem.accuracy.indicators`; the errors themselves move erratically with the grid (a contact
edge lands anywhere within a cell), so on any one case it is a typical value, not a bound.
``estimate="refined"`` (:mod:`bem.accuracy.refined`) measures the error itself.

The constants below were fitted once, on 97 solves of 2-D rough cells, 1-D rough profiles,
cylinders and spheres (standard solid and rubbers of 4 to 12 terms, ``E_inf/E0`` 3 to 1000,
speeds five decades about the friction peak, 1 % to 97 % contact), each against its solve on
the grid twice as fine; the peak weights were set on the tuning cases of ``viscobem bench
coverage``, which also measures all of them on cases held out from tuning (docs/theory.md §13.5).
"""

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

__all__ = ["QUANTITIES", "ErrorEstimate", "from_indicators", "not_estimated", "unresolved_peak", "unresolved_reason"]

QUANTITIES = ("friction", "contact_fraction", "peak_pressure")

# Contact area (Yastrebov, Anciaux & Molinari 2017): every contact-edge face holds a share of
# a cell counted whole or not at all. A systematic share per face (the discrete area is too
# large on every grid) and a random one per edge that averages over sqrt(faces). Fitted: 97 %
# of the training cases within a factor 3 of their measured error.
AREA_PER_FACE = 0.06
AREA_RANDOM = 0.2
# Friction: the dissipation's near-Nyquist moment, in full where the pressure is smooth inside
# the contact (the near-Nyquist content is the edges the grid cuts short), less where it is
# rough at the grid scale (much of that content is roughness the finer grid carries too).
# Profiles carry one edge per spot where surfaces carry a perimeter: twice the weight.
FRICTION_WEIGHT = {1: 2.0, 2: 1.0}
FRICTION_ROUGHNESS = 0.5
# Peak pressure: a share of how far the peak stands above its neighbours (a smooth maximum
# sampled anywhere within a cell moves by ~1/12 of that). Measured median ratio of error to
# sharpness on the tuning cases of ``viscobem bench coverage``: 0.14 to 0.24 for a peak inside
# the contact, 0.12 on the contact's edge, 0.085 two cells from it.
PEAK_WEIGHT = 0.15
PEAK_EDGE_WEIGHT = {1: 0.12, 2: 0.085}


@dataclass(frozen=True, eq=False)
class ErrorEstimate(Mapping):
    """Estimated relative discretisation errors, a read-only mapping ``quantity -> float or None``.

    Keys are :data:`QUANTITIES` (``friction``, ``contact_fraction``, ``peak_pressure``); a value
    is the estimated ``|Q_n - Q_2n| / |Q_2n|`` (dimensionless, 0.05 = 5 %), or ``None`` where no
    estimate exists, with the reason in ``reasons[quantity]``.

    Attributes
    ----------
    method : str
        ``"indicators"`` (the default estimate, from the solution itself), ``"refined"`` (measured
        against a solve on the grid twice as fine) or ``"none"``.
    reasons : mapping
        Why a quantity has no estimate (only for the ``None`` values).
    indicators : mapping
        The indicators it was built from (:mod:`bem.accuracy.indicators`; for ``"refined"``, also
        ``refined_friction``, ``refined_contact_fraction`` and ``refined_peak_pressure``, the
        finer solve's values).
    seconds : float
        Time spent estimating (s), the finer solve included.
    """

    values: Mapping
    method: str = "indicators"
    reasons: Mapping = field(default_factory=dict)
    indicators: Mapping = field(default_factory=dict)
    seconds: float = 0.0

    def __post_init__(self):
        values = {q: (None if self.values.get(q) is None else float(self.values[q])) for q in QUANTITIES}
        reasons = {q: str(self.reasons.get(q, "not estimated")) for q in QUANTITIES if values[q] is None}
        object.__setattr__(self, "values", MappingProxyType(values))
        object.__setattr__(self, "reasons", MappingProxyType(reasons))
        object.__setattr__(self, "indicators", MappingProxyType(dict(self.indicators)))

    def __getitem__(self, key):
        return self.values[key]

    def __iter__(self):
        return iter(QUANTITIES)

    def __len__(self):
        return len(QUANTITIES)

    def __repr__(self):
        shown = ", ".join(f"{q}={'None' if v is None else f'{v:.2g}'}" for q, v in self.values.items())
        return f"ErrorEstimate({shown}, method={self.method!r})"

    def worst(self):
        """``(quantity, value)`` of the largest estimate, or ``(None, None)`` if none exists."""
        known = [(v, q) for q, v in self.values.items() if v is not None]
        if not known:
            return None, None
        value, quantity = max(known)
        return quantity, value

    def as_dict(self):
        """Plain JSON-ready form: the three values, ``method``, ``reasons``, ``seconds`` and ``indicators``."""
        return {
            **dict(self.values),
            "method": self.method,
            "seconds": self.seconds,
            "reasons": dict(self.reasons),
            "indicators": {k: _plain(v) for k, v in self.indicators.items()},
        }


def _plain(value):
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "item"):
        return value.item()
    return value


def not_estimated(reason, method="none"):
    """An estimate with every value ``None`` and ``reason`` for each."""
    return ErrorEstimate({}, method=method, reasons={q: reason for q in QUANTITIES})


def unresolved_peak(ind):
    """Whether the peak pressure lies in leading-edge layers thinner than a cell: the pressure inside
    the edge cell rises above the grid's peak (``edge_spike > 1``) and a grid twice as fine raises
    the edge cell's pressure (``edge_growth > 1``), as it keeps doing until the cells are as thin as
    the layers (docs/theory.md §13.4)."""
    return ind.get("edge_spike", 0.0) > 1.0 and ind.get("edge_growth", 0.0) > 1.0


def unresolved_reason(ind):
    """The sentence that says why the peak pressure has no estimate."""
    layers = ind.get("subcell_layers") or []
    thinnest = f"{min(t[1] for t in layers) * ind['spacing']:.2g} m" if layers else "below a cell"
    return (
        f"unresolved: leading-edge layers V tau_k thinner than a cell ({len(layers)} Prony term(s), down to "
        f"{thinnest}, cells of {ind['spacing']:.2g} m) raise the pressure inside the edge cell to "
        f"{ind['edge_spike']:.2g} times the grid's peak, and every finer grid that is still coarser than "
        f"the layers shows a higher one (the edge cell's pressure grows {ind['edge_growth']:.2g}x per halving)"
    )


def from_indicators(ind, ndim):
    """The default estimate from the indicators of :func:`bem.accuracy.assess.indicators_of`.

    ``contact_fraction = (0.06 faces + 0.2 sqrt(faces)) / contact cells``;
    ``friction = w_d m4 / (1 + R / 0.5)`` with ``w_1 = 2``, ``w_2 = 1``, ``m4`` the dissipation
    moment and ``R`` the interior roughness (``None`` where nothing dissipates: friction is then
    zero on every grid and has no relative error); ``peak_pressure = 0.15 (p_max - mean of its
    neighbours) / p_max``, 0.12 times it for a peak on the contact's edge and 0.085 two cells from
    it; ``None`` where it lies in leading-edge layers thinner than a cell (:func:`unresolved_peak`).
    """
    values, reasons = {}, {}
    cells = ind["contact_cells"]
    if cells:
        faces = ind["contact_edge_faces"]
        values["contact_fraction"] = (AREA_PER_FACE * faces + AREA_RANDOM * faces**0.5) / cells
        if unresolved_peak(ind):
            reasons["peak_pressure"] = unresolved_reason(ind)
        else:
            weight = PEAK_EDGE_WEIGHT.get(ind["peak_cells_to_edge"], PEAK_WEIGHT)
            values["peak_pressure"] = weight * ind["peak_sharpness"]
    else:
        reasons["contact_fraction"] = reasons["peak_pressure"] = "no contact"
    if ind["dissipation_moment"] is None:
        reasons["friction"] = (
            "friction is zero on every grid (nothing dissipates: elastic material or zero speed)"
            if cells
            else "no contact"
        )
    else:
        weight = FRICTION_WEIGHT[ndim] / (1.0 + ind["interior_roughness"] / FRICTION_ROUGHNESS)
        values["friction"] = weight * ind["dissipation_moment"]
    return ErrorEstimate(values, method="indicators", reasons=reasons, indicators=ind)
