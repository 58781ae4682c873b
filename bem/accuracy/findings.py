"""The warnings of a result: one plain sentence per finding, each saying what to change.

A :class:`Finding` is a ``str`` (print it, join it, write it to JSON) that also carries its
``kind`` and the number it is about, so that a sweep can gather the same finding over many
points into one sentence (:func:`gather`). Kinds:

- ``"friction"``, ``"contact_fraction"``, ``"peak_pressure"``: the estimated discretisation error
  of that quantity exceeds :data:`WARN` (5 %);
- ``"peak_unresolved"``: the peak pressure lies in leading-edge layers thinner than a cell, so its
  change on a finer grid does not bound its error (the default estimate is then ``None``;
  docs/theory.md §13.4);
- ``"friction_forms"``: the two friction forms differ by more than :data:`WARN` (eq. 6 is
  then not to be used; docs/theory.md §4.4);
- ``"domain_edge"``: an isolated domain carries more than :data:`EDGE_LOAD` of the load on its
  outermost cells (the domain cuts the contact short);
- ``"not_converged"``: the solve did not reach its tolerance.

Sentences from elsewhere (plain strings, e.g. a material's own warnings) join the same tuple and
are gathered by their text.
"""

import math
import re

from .estimate import unresolved_peak

__all__ = ["EDGE_LOAD", "WARN", "Finding", "findings_of", "gather"]

WARN = 0.05  # an estimated error (or a friction-form gap) above this is a finding
EDGE_LOAD = 0.01  # share of the load on an isolated domain's outermost cells that is a finding
NEGLIGIBLE_FRICTION = 1e-4  # friction coefficients both below this are not compared (both ~ 0)


class Finding(str):
    """A warning sentence (a plain ``str``) with the ``kind`` and ``value`` it is about."""

    def __new__(cls, text, kind="other", value=None):
        obj = super().__new__(cls, text)
        obj.kind = str(kind)
        obj.value = None if value is None else float(value)
        return obj

    def __reduce__(self):
        return (Finding, (str(self), self.kind, self.value))

    def as_dict(self):
        """``{"kind", "value", "text"}`` (JSON-ready)."""
        return {"kind": self.kind, "value": self.value, "text": str(self)}

    @classmethod
    def from_dict(cls, record):
        """The inverse of :meth:`as_dict` (a plain string gives a finding of kind ``"other"``)."""
        if isinstance(record, str):
            return record if isinstance(record, Finding) else cls(record)
        return cls(record["text"], record.get("kind", "other"), record.get("value"))


def _pct(x):
    return f"{100 * x:.2g} %"


def _finer(error):
    """Points-per-side factor (a power of 2) that brings a first-order error under :data:`WARN`."""
    return 2 ** max(1, math.ceil(math.log2(error / WARN)))


def _refine_advice(error, n):
    factor = _finer(error)
    return (
        f"Use about {factor}x the points per side (n = {factor * n}) for the same surface, or measure "
        f"the error with error_estimate = 'refined'."
    )


def _spots(ind):
    ppw = ind.get("points_per_wavelength")
    if ppw is not None and ppw < 4:
        return f"the surface has {ppw:.2g} points per shortest wavelength, so its contact spots span few cells"
    return f"the contact's edges cut {ind['contact_edge_faces'] / ind['contact_cells']:.2g} cell faces per contact cell"


def _uncertain(quantity, value, est, detail, n):
    """The finding that ``quantity`` (of ``value``) has an estimated error above :data:`WARN`."""
    e = est[quantity]
    return Finding(
        f"{quantity} = {value:.4g} is uncertain by about {_pct(e)} (estimated discretisation error): "
        f"{detail}. {_refine_advice(e, n)}",
        quantity,
        e,
    )


def _peak(result, est, ind, n):
    e = est["peak_pressure"]
    peak = float(result.pressure.max())
    layers = ind.get("subcell_layers") or []
    head = f"peak_pressure = {peak:.4g} Pa is uncertain by about {_pct(e)} (estimated discretisation error): "
    to_edge = ind["peak_cells_to_edge"]
    near = "on the contact's edge" if to_edge == 1 else f"{to_edge} cells from the contact's edge"
    mu = est["friction"]
    if to_edge is not None and layers and (mu is None or mu < WARN / 5):
        # the peak is in the layers while friction, which integrates over them, is resolved
        thinnest = min(t[1] for t in layers) * ind["spacing"]
        friction = "" if mu is None else f" Friction does not depend on them (estimated error {mu:.2g})."
        return Finding(
            head + f"it sits {near}, in leading-edge layers thinner than a cell (V tau_k "
            f"down to {thinnest:.2g} m for {len(layers)} Prony term(s), cells of {ind['spacing']:.2g} m), "
            f"which only a grid finer than the layers resolves.{friction} Quote the peak pressure with this "
            f"uncertainty, or measure it with error_estimate = 'refined'.",
            "peak_pressure",
            e,
        )
    where = (
        f"it sits {near}, where the pressure rises from zero within {to_edge} cell(s)"
        if to_edge is not None
        else f"it stands {_pct(ind['peak_sharpness'])} above the mean of its neighbouring cells"
    )
    return Finding(
        head + f"{where}, so the grid does not resolve the pressure's peak. {_refine_advice(e, n)}", "peak_pressure", e
    )


def _unresolved(result, est, ind):
    mu = est["friction"]
    friction = "" if mu is None else f" Friction integrates over the layers (its estimated error is {_pct(mu)})."
    layers = ind.get("subcell_layers") or []
    thinnest = min(t[1] for t in layers) * ind["spacing"] if layers else 0.0
    return Finding(
        f"peak_pressure = {float(result.pressure.max()):.4g} Pa is not resolved: the pressure peaks in "
        f"leading-edge layers V tau_k thinner than a cell (down to {thinnest:.2g} m for {len(layers)} Prony "
        f"term(s), cells of {ind['spacing']:.2g} m), about {ind['edge_spike']:.2g} times the grid's peak, and "
        f"grows with every refinement until the cells are as thin as the layers, so its change on a grid "
        f"twice as fine does not bound its error.{friction} Do not quote the peak pressure from this grid.",
        "peak_unresolved",
    )


def _forms(result, est, gap):
    mu = est["friction"]
    known = "" if mu is None else f", whose estimated error is {_pct(mu)}"
    return Finding(
        f"friction_eq6 = {result.friction_eq6:.3g} differs from friction = {result.friction:.3g} by "
        f"{_pct(gap)}: eq. 6 holds only once the grid resolves the contact spots. Use friction (the "
        f"dissipation form{known}); refine the grid until the two agree if eq. 6 is needed.",
        "friction_forms",
        gap,
    )


def findings_of(result, est, ind, n):
    """The findings of one solve: ``result`` (a :class:`~bem.result.SlidingResult`), its estimate,
    the indicators it came from and the points per side ``n``; a tuple of :class:`Finding`."""
    if not result.success:
        return (
            Finding(
                f"the solve did not converge ({result.message}): its fields are not a solution and carry "
                f"no error estimate. Raise maxiter, or see bem.contact.ContactOptions.",
                "not_converged",
            ),
        )
    out = []
    if est["friction"] is not None and est["friction"] > WARN:
        share = _pct(ind["dissipation_moment"])
        detail = f"{_spots(ind)}, and {share} of the dissipation weighs wavelengths of a few cells"
        out.append(_uncertain("friction", result.friction, est, detail, n))
    if est["contact_fraction"] is not None and est["contact_fraction"] > WARN:
        detail = f"{_spots(ind)}, and a cell on an edge counts whole or not at all (coarse grids overstate the area)"
        out.append(_uncertain("contact_fraction", result.contact_fraction, est, detail, n))
    if est["peak_pressure"] is not None and est["peak_pressure"] > WARN:
        out.append(_peak(result, est, ind, n))
    elif unresolved_peak(ind):  # also with a measured (refined) change, which does not bound it
        out.append(_unresolved(result, est, ind))
    gap = ind.get("form_gap", 0.0)
    if gap > WARN and max(abs(result.friction), abs(result.friction_eq6)) >= NEGLIGIBLE_FRICTION:
        out.append(_forms(result, est, gap))
    edge = ind.get("edge_load", 0.0)
    if edge > EDGE_LOAD:
        out.append(
            Finding(
                f"{_pct(edge)} of the load lies on the outermost cells of the isolated domain: the domain "
                f"cuts the contact short. Widen it (an indenter: length, with n in proportion to keep the "
                f"cell size; a measured patch: a boundary treatment that does not load its edges).",
                "domain_edge",
                edge,
            )
        )
    return tuple(out)


def _span(labels):
    if len(labels) <= 4:
        return ", ".join(labels)
    return f"{labels[0]}, {labels[1]}, ..., {labels[-1]}"


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?")


def gather(points, *, noun="points"):
    """One sentence per kind of finding over the labelled points of a sweep.

    ``points`` is a list of ``(label, findings)`` (``label`` a short string such as
    ``"v = 0.001 m/s"``, ``findings`` sentences or :class:`Finding`). A finding seen at one point
    reads ``"at LABEL: TEXT"``; seen at several, ``"at K of N NOUN (LABELS; worst at LABEL): TEXT
    of the worst"``. Returns a list of :class:`Finding` in order of first appearance.
    """
    groups = {}
    for label, found in points:
        for f in found:
            f = Finding.from_dict(f)
            # findings measured by a value group by kind; the others (sentences of one kind that
            # say different things, e.g. a material extrapolated below and above its data) by
            # their words, so that each keeps its own points
            key = f.kind if f.value is not None and f.kind != "other" else (f.kind, _NUMBER.sub("#", str(f)))
            groups.setdefault(key, []).append((label, f))
    total = len(points)
    out = []
    for members in groups.values():
        labels = list(dict.fromkeys(label for label, _ in members))
        valued = [m for m in members if m[1].value is not None]
        worst_label, worst = max(valued, key=lambda m: m[1].value) if valued else members[0]
        if len(labels) == 1:
            text = f"at {labels[0]}: {worst}"
        else:
            text = f"at {len(labels)} of {total} {noun} ({_span(labels)}; worst at {worst_label}): {worst}"
        out.append(Finding(text, worst.kind, worst.value))
    return out
