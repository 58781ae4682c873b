"""The result of :func:`fem_reference.rolling_cylinder` (SI units)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["RollingResult"]


@dataclass(frozen=True)
class RollingResult:
    """Result of :func:`rolling_cylinder` (SI units; lengths in m, per unit length in z).

    Attributes
    ----------
    x : ndarray
        Top-surface node coordinates in the candidate contact band (m).
    pressure : ndarray
        Contact pressure at ``x`` (Pa): nodal force over ``int phi_i ds``.
    displacement : ndarray
        Depression (vertical displacement into the solid) at ``x`` (m).
    forces : ndarray
        Nodal contact forces at ``x`` (N/m); they sum to ``load``.
    leading_edge, trailing_edge : float
        Contact edges (m), leading at ``+x``.
    friction : float
        ``mu = x_bar / R`` from the moment of the nodal forces (the seed paper's eq. 6, docs/theory.md §4.3).
    friction_dissipation : float
        Viscous dissipation integrated over the block, over ``P V`` (0 at ``V = 0``). The
        two forms converge together; against Hunter's exact solution at 3 elements per
        glassy half-width the moment form is the better one at low speed (0.6 % vs
        1.8 % at ``V lambda = 0.3 a0``) and the dissipation form at high speed (0.05 %
        vs 4.6 % at ``V lambda = 100 a0``, where the pressure centroid moves by a
        hundredth of a node spacing).
    dissipated_power : float
        Viscous dissipation integrated over the block (W/m), from the internal variables;
        it matches ``friction * load * speed`` (the moment form) to the discretisation error.
    peak_pressure, load, speed, radius, approach : float
        Pa, N/m, m/s, m, m (the approach depends on the truncation depth in 2-D).
    element_size, domain_width, domain_depth, grading : float
        Core element size ``h``, half-width ``L`` and depth ``H`` of the block (m), and
        the element growth ratio outside the core.
    n_elements, n_unknowns, iterations : int
    residual : float
        Complementarity residual of the solution (:func:`~fem_reference.contact.complementarity_residual`):
        the gaps of the displaced surface from the final field solve, in the active set and out of it,
        and the signs of the nodal forces.
    material : bem.Material
        The material actually used (after folding inactive Prony terms).
    input_material : bem.Material
        The material as given (before folding).
    success, message : bool, str
        ``success`` is True only if every linear solve is within its limit (``linear_residual <=
        linear_residual_limit``) and the complementarity ``residual`` is within
        :func:`~fem_reference.contact.complementarity_limit` of that limit.
    timings : dict
        Wall times (s) of the last mesh: ``assemble``, ``factor`` (their sum
        ``assemble_factor``), ``flexibility``, ``contact``, ``fields``; ``total`` over all
        passes.
    fields : dict
        Quadrature-point fields (only with ``keep_fields=True``): ``points``, ``strain``,
        ``stress``, ``alpha`` (list, one per term of ``material``), ``taus`` (their
        ``tau_k``, s), ``pressure`` (Pa), ``dissipation``, ``weights``, and ``u``,
        ``mesh``, ``basis``, ``ops`` (:class:`~fem_reference.kinematics.QuadratureOperators`).
    linear_residual : float
        Relative residual of the linear solve (flexibility and fields) closest to its limit:
        ``||K u - f|| / ||f||`` on the force balance, the constraint rows against their own terms
        (:func:`~fem_reference.linsolve.relative_residual`).
    linear_residual_limit : float
        Its limit: 1e-8, or ten times the round-off floor of the force balance where that is
        higher (:func:`~fem_reference.linsolve.residual_limit`).
    solver : str
        Linear solver of the result (``splu`` or ``pardiso``).
    solver_path : tuple of dict
        Every factorisation tried on the last mesh, in order
        (:func:`~fem_reference.linsolve.solve_on_path`): ``solver``, ``form`` (``"as asked"`` or
        ``"carried"``), the factor's diagnostics (``factor_nonzeros``; PARDISO's
        ``perturbed_pivots`` and ``deflated_directions``), the worst ``residual`` against its
        ``limit``, and the ``outcome``.
    mesh : str
        ``uniform`` or ``graded``.
    passes : int
        Meshes solved (the graded mesh follows the contact edges until they settle).
    terms : dict
        ``kept``, ``relaxed`` and ``glassy`` relaxation times ``tau_k`` (s).
    condensed : tuple of bool
        Per kept term: viscous strains eliminated (True) or unknowns (False).
    peak_memory : float
        Peak resident memory of the process so far (MiB).
    n_nonzeros, factor_nonzeros : int
        Entries of the assembled system and of its factors (fill-in included; -1 when the solver does
        not report it), last mesh.
    thinnest_layer : float
        The thinnest leading-edge layer ``V min(tau_k)`` over the terms kept (m; ``inf`` for an
        elastic solid or at rest).
    smallest_element : float
        The smallest element along the flow (m).
    peak_resolved : bool
        The pressure's leading-edge layer ``thinnest_layer`` spans at least one ``smallest_element``
        (uniform mesh) or :data:`~fem_reference.graded.LAYER_ELEMENTS` of them (graded mesh, which
        puts that many across a layer it resolves). Where it does not, the peak pressure is a value
        at an unresolved jump (``warnings`` says so) and should not be judged pointwise.
    warnings : tuple of str
        What the result cannot be trusted for (an unresolved leading-edge layer, a graded mesh that did
        not settle on the contact edges within ``passes``, the two forms of the friction more than
        :data:`~fem_reference.rolling.FORM_GAP` apart, an error estimate above
        :data:`~fem_reference.rolling.ESTIMATE_LIMIT`).
    error_estimate : dict
        Estimates of relative discretisation errors (:func:`~fem_reference.rolling_cylinder`,
        ``estimate``): ``friction`` and ``friction_dissipation``, from the mesh's coarse twin and
        the gap between the two forms; ``peak_pressure`` from the twin, where ``peak_resolved``.
        Empty when not asked for, when the twin's solve failed (``warnings`` says why) and for a
        solid that does not dissipate.
    """

    x: np.ndarray
    pressure: np.ndarray
    displacement: np.ndarray
    forces: np.ndarray
    leading_edge: float
    trailing_edge: float
    friction: float
    friction_dissipation: float
    dissipated_power: float
    peak_pressure: float
    load: float
    speed: float
    radius: float
    approach: float
    element_size: float
    domain_width: float
    domain_depth: float
    grading: float
    n_elements: int
    n_unknowns: int
    iterations: int
    residual: float
    material: object = None
    success: bool = False
    message: str = ""
    timings: dict = field(default_factory=dict)
    fields: dict = field(default_factory=dict, repr=False)
    linear_residual: float = float("nan")
    linear_residual_limit: float = float("nan")
    solver: str = ""
    solver_path: tuple = ()
    mesh: str = "uniform"
    passes: int = 1
    terms: dict = field(default_factory=dict)
    condensed: tuple = ()
    peak_memory: float = float("nan")
    input_material: object = None
    n_nonzeros: int = 0
    factor_nonzeros: int = 0
    thinnest_layer: float = float("inf")
    smallest_element: float = float("nan")
    peak_resolved: bool = True
    warnings: tuple = ()
    error_estimate: dict = field(default_factory=dict)
