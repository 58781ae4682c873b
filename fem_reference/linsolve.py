"""Sparse direct factorisation of the (non-symmetric) FEM operators, and the one policy that
picks it.

``scipy.sparse.linalg.splu`` (SuperLU) and ``pypardiso`` (MKL PARDISO, from PyPI, optional)
factor the systems. :func:`solver_path` is the only place that decides which factorisations a
system gets and in what order; :func:`solve_on_path` runs them until the solves meet their
residual limit and reports every step (the ``solver_path`` of each FEM result). See
``viscobem_bench/fem.py`` for timings.
"""

from __future__ import annotations

import contextlib
import logging
import os
import threading
import weakref
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from bem.errors import ConvergenceError, InputError

from .ordering import PIVOT_THRESHOLD, equilibrate, nested_dissection

__all__ = [
    "factorize",
    "SOLVERS",
    "Step",
    "solver_path",
    "solve_on_path",
    "relative_residual",
    "residual_limit",
    "solve_refined",
    "RESIDUAL_LIMIT",
]

RESIDUAL_LIMIT = 1e-8  # largest accepted relative residual of a linear solve (see residual_limit)
# refinement stops at this residual: a hundredth of the limit, so that the force error of an
# accepted solve is far below the discretisation's (>= 1e-5) and round-off in the products cannot
# push it over the limit; going lower costs a solve with every right-hand side and moves nothing
TARGET = RESIDUAL_LIMIT / 100
FLOOR_FACTOR = 10.0  # a solve may sit this far above the round-off floor of its force balance
# iterative refinement stops once a step fails to halve the residual: it contracts by cond * eps per
# step while it works, and at the floor set by the conditioning it only fluctuates (each step costs a
# solve with every right-hand side: the flexibility's hundreds of columns)
STALL = 0.5
# deflation of PARDISO's solve (_Pardiso.deflate): directions where the factor's inverse departs
# from A's by more than DEFLATE_TOL are solved exactly, the rest left to iterative refinement (which
# then contracts by DEFLATE_TOL per step); at most DEFLATE_MAX random probes find them
DEFLATE_TOL = 1e-3
DEFLATE_MAX = 512
# a first solve this far off (relative residual) is deflated at once, before any refinement
DEFLATE_TRIGGER = 100 * 1e-8
# a solve with more right-hand sides than PROBE_COLUMNS is preceded by a probe, its first column
# alone: if PARDISO's own refinement took more than DEFLATE_STEPS steps there, the factor is deflated
# before the rest are solved, and the solve of all columns takes at most DEFLATE_STEPS of them either
# way. Each of those steps costs a solve for every column (the flexibility's tens to hundreds), while
# a deflated solve costs two and converges by DEFLATE_TOL per step
DEFLATE_STEPS = 8
PROBE_COLUMNS = 4

# SuperLU's factor may take this share of the memory the system reports available when it starts
MEMORY_SHARE = 0.9
# SuperLU's factor of a system PARDISO's solves missed on may take this many times PARDISO's entries
# (8 bytes of value and 8 of indices and work each) before the path's next step is taken instead.
# Measured: 2.6 times on a 10-term rubber two decades above its friction peak (87 million entries,
# 19 s), where the carried form took 14 GiB; on broad spectra near their peak the condensed bands
# fill SuperLU's factor to 12 GiB, and the carried form's local couplings do not
CONDENSED_FILL = 8.0

SOLVERS = ("auto", "splu", "pardiso")
log = logging.getLogger(__name__)


def reproducible_mkl():
    """Ask MKL for conditional numerical reproducibility (``MKL_CBWR=AUTO``) unless the user chose.

    MKL's threaded factorisation sums updates in an order that varies from run to run; with the
    saddle-point blocks' perturbed pivots that changes which pivots are perturbed, and so whether a
    hard solve reaches its residual. This mode fixes the order: the same result on the same machine
    with the same number of threads. MKL reads it when it starts, so it is set when this module is
    imported, before PARDISO is.
    """
    os.environ.setdefault("MKL_CBWR", "AUTO")


reproducible_mkl()


def _meminfo(path, key):
    """The ``key`` line of a ``/proc`` status file in bytes, or None where there is none."""
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1]) * 1024  # the kernel reports kB
    except (OSError, ValueError, IndexError):
        return None
    return None


def available_memory():
    """Bytes the kernel reports as available to new allocations (``MemAvailable``), or None where
    the platform does not say."""
    return _meminfo("/proc/meminfo", "MemAvailable")


# The address-space limit is process-wide: factorisations in several threads share one, set by the
# first to start and restored by the last to end (a thread restoring its own saved value while
# another still ran could leave a limit in place for good)
_BUDGET_LOCK = threading.Lock()
_budget_state = {"active": 0, "saved": None}


@contextlib.contextmanager
def _address_space_budget(budget):
    """Let the process's address space grow by at most ``budget`` bytes inside the block.

    SuperLU grows its factor as it fills in; on a broad-spectrum rubber that can outgrow the
    machine (more than 13 GiB), where the kernel would swap or kill the process rather than fail
    an allocation. Under the limit an allocation past the budget fails at once and SuperLU reports
    it (``MemoryError``). Memory the process freed but kept mapped is reused without counting.
    Where resource limits or ``/proc`` are missing, the block runs unbounded.
    """
    try:
        import resource
    except ImportError:  # not a POSIX system
        yield
        return
    with _BUDGET_LOCK:
        if _budget_state["active"] == 0:
            used = _meminfo("/proc/self/status", "VmSize")
            soft, hard = resource.getrlimit(resource.RLIMIT_AS)
            if budget is not None and used is not None:
                limit = used + int(budget)
                unlimited = resource.RLIM_INFINITY
                if (soft == unlimited or soft > limit) and (hard == unlimited or hard >= limit):
                    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
                    _budget_state["saved"] = (soft, hard)
        _budget_state["active"] += 1
    try:
        yield
    finally:
        with _BUDGET_LOCK:
            _budget_state["active"] -= 1
            if _budget_state["active"] == 0 and _budget_state["saved"] is not None:
                resource.setrlimit(resource.RLIMIT_AS, _budget_state["saved"])
                _budget_state["saved"] = None


class _SuperLU:
    name = "splu"

    def __init__(self, A, memory=None):
        avail = available_memory()
        budget = None if avail is None else MEMORY_SHARE * avail
        if memory is not None:
            budget = float(memory) if budget is None else min(budget, float(memory))
        try:
            with _address_space_budget(budget):
                # scaled first (the units of displacements, pressures and transported strains
                # differ by orders): the pivot threshold then compares like with like, and without
                # scaling the condensed rubber systems' residual stalled at 7e-8 instead of 2e-10
                self._row, self._col, scaled = equilibrate(A)
                self._order = nested_dissection(scaled)
                self._lu = spla.splu(
                    sp.csc_matrix(scaled[self._order][:, self._order]),
                    permc_spec="NATURAL",
                    diag_pivot_thresh=PIVOT_THRESHOLD,
                    options={"Equil": False, "SymmetricMode": True},
                )
        except (MemoryError, RuntimeError) as err:
            # SuperLU reports a failed allocation as MemoryError, or as RuntimeError ("SUPERLU_MALLOC
            # fails ...") where it fails in the ordering
            if budget is None or not (isinstance(err, MemoryError) or "MALLOC" in str(err).upper()):
                raise
            raise MemoryError(
                f"SuperLU's factor of {A.shape[0]} unknowns ({A.nnz} entries) needs more than the "
                f"{budget / 2**30:.3g} GiB of memory available"
            ) from None
        self.nnz = int(self._lu.nnz)  # entries SuperLU stores for L and U (read without copying them)

    def solve(self, b):
        b = np.asarray(b, dtype=float)
        row = self._row if b.ndim == 1 else self._row[:, None]
        col = self._col if b.ndim == 1 else self._col[:, None]
        x = np.empty_like(b)
        x[self._order] = self._lu.solve(np.ascontiguousarray((row * b)[self._order]))
        return col * x

    def diagnostics(self):
        return {"solver": self.name, "factor_nonzeros": self.nnz}


class _Pardiso:
    """MKL PARDISO (METIS ordering, weighted matching and scaling). The saddle-point
    blocks (zero pressure block for ``nu = 0.5``) make it perturb a few pivots, so up to
    20 steps of its iterative refinement are enabled; the residual then matches
    SuperLU's (measured 1e-7 relative, max norm, for random right-hand sides on both). Where
    that is not enough (broad-spectrum rubbers at high speed, some standard solids), the solve
    is deflated (:meth:`deflate`)."""

    name = "pardiso"

    def __init__(self, A):
        import pypardiso

        self._solver = pypardiso.PyPardisoSolver()
        self._solver.set_matrix_type(11)  # real non-symmetric
        self._steps = 20  # PARDISO's own refinement steps at most (iparm 8); none once deflated
        for key, value in {1: 1, 2: 2, 8: self._steps, 10: 8, 11: 1, 13: 1, 18: -1}.items():
            self._solver.set_iparm(key, value)  # 1-based iparm: METIS, refinement, matching, report fill
        self._solver.set_statistical_info_off()
        self._A = sp.csr_matrix(A)
        self._A.sort_indices()
        self._solver.factorize(self._A)
        self.nnz = int(self._solver.get_iparm(18))  # entries of the factors, as PARDISO reports them
        self._Q = self._Qw = self._Rw = None
        self.deflated = 0
        self.refinement_steps = 0  # PARDISO's own, in the last solve
        self.extended = None  # A in extended precision, for refinement of the deflated solve

    def _plain(self, b):
        b = np.ascontiguousarray(np.asarray(b, dtype=float))
        steps = self._steps
        if b.ndim == 2 and b.shape[1] > PROBE_COLUMNS:
            # each of PARDISO's refinement steps solves every column: a solve of many columns pays for
            # at most DEFLATE_STEPS of them, whatever one probe column took (the columns of one
            # flexibility need different numbers of steps); one left off is deflated by solve_refined
            self._solver.set_iparm(8, min(steps, DEFLATE_STEPS))
        try:
            x = self._solver.solve(self._A, b)
        finally:
            self._solver.set_iparm(8, steps)
        self.refinement_steps = int(self._solver.get_iparm(7))
        return x

    def diagnostics(self):
        return {
            "solver": self.name,
            "factor_nonzeros": self.nnz,
            "perturbed_pivots": int(self._solver.get_iparm(14)),
            "deflated_directions": self.deflated,
        }

    def slow_to_refine(self, b):
        """True if PARDISO's own refinement of the solve with ``b`` (one column) took more than
        :data:`DEFLATE_STEPS` steps; always False once deflated (its refinement is then off)."""
        if self._Q is not None:
            return False
        self._plain(b)
        return self.refinement_steps > DEFLATE_STEPS

    def solve(self, b):
        if self._Q is None or self.deflated == 0:
            return self._plain(b)
        # x = y + Q z with y = M^-1 b: the error of y lies in the range of P (M = A + E, so
        # (A^-1 - M^-1) b = A^-1 E M^-1 b, and M^-1 E = A^-1 E (I + ...)^-1 spans the same), and z
        # minimises the true residual ||b - A y - A Q z|| through the QR factors of A Q. Products
        # with A are exact where M^-1 is not: on the directions a perturbed pivot dominates,
        # M^-1 A Q is nearly zero and carries nothing but the factor's round-off
        y = self._plain(b)
        y2 = y.reshape(y.shape[0], -1)
        r = np.asarray(b, dtype=float).reshape(y2.shape) - self._A @ y2
        z = np.linalg.solve(self._Rw, self._Qw.T @ r)
        return (y2 + self._Q @ z).reshape(y.shape)

    def deflate(self, seed=0):
        """Make the solve exact on the directions where the factor is far from ``A``.

        Static pivoting (perturbed pivots, and the growth it lets through) leaves ``M^-1 A = I -
        P`` with ``P`` of fast-decaying singular values: iterative refinement contracts by the
        largest, and stalls or diverges once that is near or above 1. A randomized range finder
        (``k`` Gaussian probes ``X``, ``P X = X - M^-1 A X``) finds the directions where ``P``
        exceeds :data:`DEFLATE_TOL`; ``k`` doubles until the smallest found is below it (at
        most :data:`DEFLATE_MAX` probes). Every later solve is exact on them (a solve with the
        factor, a product with ``A`` and a least-squares correction on their span, :meth:`solve`)
        and refinement contracts by ``DEFLATE_TOL`` per step. PARDISO's own refinement is
        switched off, so that ``M^-1`` is a fixed linear operator. Returns False if this factor
        was deflated already.
        """
        if self._Q is not None:
            return False
        self._steps = 0
        self._solver.set_iparm(8, 0)
        n = self._A.shape[0]
        rng = np.random.default_rng(seed)
        k = min(max(2 * int(self._solver.get_iparm(14)) + 16, 32), DEFLATE_MAX, n)
        while True:
            X = rng.standard_normal((n, k))
            U, sig, _ = np.linalg.svd(X - self._plain(self._A @ X), full_matrices=False)
            est = sig / np.sqrt(k)  # singular values of P: a Gaussian probe has sqrt(k) of each
            if est[-1] < DEFLATE_TOL or k >= min(DEFLATE_MAX, n):
                break
            k = min(2 * k, DEFLATE_MAX, n)
        keep = est > DEFLATE_TOL
        self._Q = np.ascontiguousarray(U[:, keep])
        self.deflated = int(keep.sum())
        if self.deflated:  # none is possible: a factor only slow to refine may be close to A
            self._Qw, self._Rw = np.linalg.qr(self._A @ self._Q)
        if np.finfo(np.longdouble).eps < np.finfo(float).eps:  # x86: 64-bit mantissa
            self.extended = self._A.astype(np.longdouble)
        log.debug(
            "PARDISO: %d perturbed pivots; solve deflated on %d of %d probed directions (next %.1e)",
            int(self._solver.get_iparm(14)),
            self.deflated,
            k,
            est[-1],
        )
        return True

    def __del__(self):
        # MKL keeps the factor in its own memory until told to release it: without this every
        # factorisation of a run would stay resident after its operator is gone
        solver = getattr(self, "_solver", None)
        if solver is not None:
            try:
                solver.free_memory(everything=True)
                solver.libmkl.mkl_free_buffers()  # and MKL's allocator hands the memory back
            except Exception:  # interpreter shutdown: the library may already be unloaded
                pass


def pardiso_available():
    """True if the optional PARDISO solver (``pypardiso``, the ``fem`` extra) is importable."""
    try:
        import pypardiso  # noqa: F401
    except ImportError:
        return False
    return True


def factorize(A, solver="auto", memory=None):
    """Factor the square sparse matrix ``A``; returns an object with ``solve(b)``, ``name`` and
    ``nnz`` (the entries of the factors, fill-in included).

    Parameters
    ----------
    A : scipy.sparse matrix
    solver : {"auto", "splu", "pardiso"}
        ``"auto"``: the first step of :func:`solver_path` (PARDISO if ``pypardiso`` is importable,
        else SuperLU).
    memory : float, optional
        Most bytes SuperLU's factorisation may add to the process (``MemoryError`` beyond); at
        most :data:`MEMORY_SHARE` of the memory available in any case.
    """
    if solver not in SOLVERS:
        raise InputError(f"solver must be one of {SOLVERS}, got {solver!r}")
    if solver == "pardiso" and not pardiso_available():
        raise InputError("solver='pardiso' needs the optional package pypardiso (pip install pypardiso)")
    fac = _Pardiso(A) if solver_path(solver)[0].solver == "pardiso" else _SuperLU(A, memory=memory)
    log.debug("factorised %d unknowns with %s", A.shape[0], fac.name)
    return fac


@dataclass(frozen=True)
class Step:
    """One factorisation of a path: ``solver`` (``"pardiso"`` or ``"splu"``) on the system as asked,
    or with every viscous term carried by its outflow values (``carried``); ``fill``: SuperLU's
    factor may take at most this many times the previous step's factor entries."""

    solver: str
    carried: bool = False
    fill: float | None = None

    def __str__(self):
        name = {"splu": "SuperLU", "pardiso": "PARDISO"}[self.solver]
        return name + (", carrying every term by its outflow values" if self.carried else "")


def solver_path(solver="auto", *, carries=False, condenses=False, squares=False, closed=False):
    """The factorisations a FEM system gets, in order: the one place that picks its linear algebra.

    ``"splu"`` or ``"pardiso"`` gets that factorisation alone, and a solve that misses its limit
    is reported, not replaced. ``"auto"`` gets SuperLU where ``pypardiso`` is not importable or
    the system carries a term (PARDISO's static pivoting leaves the carried form's solve off:
    first residual 1 on a 10-term rubber, 2 on the quick validation's solids, where SuperLU's
    partial pivoting reaches 1e-9 and, on a 3-term rubber, factors faster than the condensed
    form). Otherwise it gets PARDISO; where its solves miss their limit even deflated, SuperLU on
    the same system within :data:`CONDENSED_FILL` times PARDISO's entries; and beyond that,
    SuperLU on the form that carries every term (whose couplings stay local). On a mesh of squares
    (:mod:`fem_reference.quadtree`) PARDISO solves the carried form too (residual 7e-11 against a
    limit of 1e-8 on a 20-term rubber at its friction peak, 600,000 unknowns), so there ``"auto"``
    gets PARDISO, then SuperLU on the same system where its solves miss. Where the streamlines close
    on themselves (a periodic cell, :mod:`fem_reference.periodic`), ``"auto"`` gets SuperLU: there
    PARDISO's first residual was 3.8 on a 4-term rubber's 24,064 unknowns, and its refinement took
    35 s before SuperLU's 1.2 s factor met the limit (2.5e-13).

    Parameters
    ----------
    solver : {"auto", "splu", "pardiso"}
        What the caller asked for.
    carries : bool
        The system as asked carries some term by its outflow values.
    condenses : bool
        The system as asked condenses some term (so a form carrying every term exists).
    squares : bool
        The mesh's elements are squares (no needles for PARDISO's static pivoting).
    closed : bool
        The memory's streamlines are closed (a periodic cell).

    Returns
    -------
    tuple of Step
    """
    if solver not in SOLVERS:
        raise InputError(f"solver must be one of {SOLVERS}, got {solver!r}")
    if solver != "auto":
        return (Step(solver),)
    if closed or not pardiso_available():
        return (Step("splu"),)
    if squares:
        return (Step("pardiso"), Step("splu"))
    if carries:
        return (Step("splu"),)
    path = (Step("pardiso"), Step("splu", fill=CONDENSED_FILL))
    return path + (Step("splu", carried=True),) if condenses else path


def _diagnostics(factor):
    """The factor's own report (an empty one from a factor that gives none). No reference to the
    factor outlives the call: a missed factor must be freed before the next one is made."""
    return factor.diagnostics() if hasattr(factor, "diagnostics") else {}


class _Missed(Exception):
    """The step's solves missed their limit and a later step will take over."""


def solve_on_path(path, build, work):
    """Run ``work`` on the operator of each step of ``path`` until its solves meet their limit.

    The last step's result is returned even if it missed (the caller reports that). A fallback
    that cannot be factored raises ``ConvergenceError`` naming the miss it was to mend; a first
    step that cannot be factored raises as it did.

    Parameters
    ----------
    path : sequence of Step
        From :func:`solver_path`.
    build : callable
        ``build(step, memory)`` returns an operator with ``factor`` and the ``residual`` and
        ``residual_limit`` of its solves so far; ``memory`` (bytes, or None) bounds SuperLU's factor.
    work : callable
        ``work(op, checkpoint)`` solves with ``op`` and returns its result; it calls
        ``checkpoint()`` after its costliest solves, so that a step that missed is left before the
        rest of its work is done.

    Returns
    -------
    result : object
        What ``work`` returned on the last step run.
    report : list of dict
        Every step tried: ``solver``, ``form``, its factor's diagnostics, its worst ``residual``
        against its ``limit``, and its ``outcome`` ("met", "missed", or why it could not run).
    """
    report, missed, nnz = [], None, -1
    for i, step in enumerate(path):
        last = i == len(path) - 1
        entry = {"solver": step.solver, "form": "carried" if step.carried else "as asked"}
        report.append(entry)
        memory = None
        if step.fill is not None:
            if nnz <= 0:  # the previous factor did not say its size: no budget to give
                entry["outcome"] = "skipped: the factor before it did not report its size"
                continue
            memory = step.fill * 16.0 * nnz
        try:
            op = build(step, memory)
        except MemoryError as err:
            if missed is None:
                raise
            entry["outcome"] = f"memory: {err}"
            if last:
                raise ConvergenceError(f"{missed}, and the fallback to SuperLU failed: {err}") from err
            log.warning("%s; factoring with %s", err, path[i + 1])
            continue

        def checkpoint(op=op, last=last):
            if not last and op.residual > op.residual_limit:
                raise _Missed

        try:
            result = work(op, checkpoint)
            checkpoint()
        except _Missed:
            result = None
        entry.update(_diagnostics(op.factor), residual=float(op.residual), limit=float(op.residual_limit))
        if result is not None:
            entry["outcome"] = "met" if op.residual <= op.residual_limit else "missed"
            return result, report
        entry["outcome"] = "missed"
        missed = f"{op.factor.name} solve residual {op.residual:.2e} > {op.residual_limit:.1e}"
        log.warning("%s: factoring with %s", missed, path[i + 1])
        nnz = int(getattr(op.factor, "nnz", -1))
        op = checkpoint = None  # the missed factor (and its deflation) goes before the next one's fill comes
    raise ConvergenceError(f"{missed}, and no fallback could run")  # every later step was skipped


_MAGNITUDES = {}


def _magnitude(A):
    """``|A|`` (entrywise), kept while ``A`` lives: every residual of a system's solves and
    refinement steps scales by it, and forming it costs a pass over the matrix."""
    key = id(A)
    hit = _MAGNITUDES.get(key)
    if hit is None or hit[0]() is not A:
        hit = (weakref.ref(A), abs(A))
        _MAGNITUDES[key] = hit
        weakref.finalize(A, _MAGNITUDES.pop, key, None)
    return hit[1]


def relative_residual(A, x, b, n_equilibrium=None):
    """Relative residual of ``A x = b``, the worst over the columns of ``b``.

    Without ``n_equilibrium`` it is ``||A x - b|| / ||b||`` (Euclidean norms). The FEM's
    systems stack equations of different units: the first ``n_equilibrium`` rows are the
    force balance ``K u - f`` (the applied loads live there), the rest are constraints
    (incompressibility, the viscous strains' transport) whose right-hand side is usually
    zero. One norm over all rows would measure the constraints against the load, in other
    units, and report the round-off of their own large terms (``eps |A| |x|``, up to 1e-7
    of ``||b||``) as an error of the solve. So the force balance is measured against the
    load, ``||K u - f|| / ||f||``, and the constraint rows against the size of their own
    terms, ``||r_c|| / || |A_c| |x| + |b_c| ||`` (the Oettli-Prager scale); the larger of
    the two is returned. A force block without load is measured like a constraint block.
    """
    b2 = b.reshape(b.shape[0], -1)
    r = A @ x.reshape(x.shape[0], -1) - b2
    norm = np.linalg.norm
    if n_equilibrium is None:
        return _worst_ratio(norm(r, axis=0), norm(b2, axis=0))
    n = int(n_equilibrium)
    scale = _magnitude(A) @ np.abs(x.reshape(x.shape[0], -1)) + np.abs(b2)
    load = norm(b2[:n], axis=0)
    worst = _worst_ratio(norm(r[:n], axis=0), np.where(load > 0, load, norm(scale[:n], axis=0)))
    if n < A.shape[0]:
        worst = max(worst, _worst_ratio(norm(r[n:], axis=0), norm(scale[n:], axis=0)))
    return worst


def residual_limit(A, x, b, n_equilibrium):
    """The largest acceptable :func:`relative_residual` of the solve ``x`` of ``A x = b``.

    It is :data:`RESIDUAL_LIMIT`, unless the round-off floor of the force balance is higher: a
    backward-stable solve leaves residuals of order ``eps (|A| |x|)_i`` in each row, so
    ``||K u - f|| / ||f||`` cannot fall below ``eps || (|A| |x|)_eq || / ||f||``. For rubbers of a
    large modulus ratio the balance's terms exceed the load by ~1e8 (near the contact the glassy
    and the viscous stresses almost cancel), which puts the floor near 2e-8; there the limit is
    ``FLOOR_FACTOR`` times the floor. A wrong solve still fails: its residual is set by its error,
    not by round-off.
    """
    n = int(n_equilibrium)
    b2 = b.reshape(b.shape[0], -1)[:n]
    terms = (_magnitude(A) @ np.abs(x.reshape(x.shape[0], -1)))[:n]
    load = np.linalg.norm(b2, axis=0)
    ok = load > 0
    if not np.any(ok):
        return RESIDUAL_LIMIT
    floor = np.finfo(float).eps * np.max(np.linalg.norm(terms, axis=0)[ok] / load[ok])
    return max(RESIDUAL_LIMIT, FLOOR_FACTOR * float(floor))


def _worst_ratio(num, den):
    """``max_j num_j / den_j`` over the columns with ``den_j > 0`` (``max num`` when there are none)."""
    ok = den > 0
    return float(np.max(num[ok] / den[ok])) if np.any(ok) else float(np.max(num, initial=0.0))


def solve_refined(A, factor, b, *, n_equilibrium=None, target=TARGET, steps=8):
    """``x`` with ``factor.solve`` plus up to ``steps`` of iterative refinement.

    Refinement stops once the relative residual (:func:`relative_residual`, with
    ``n_equilibrium`` force-balance rows) is below ``target``, or once a step fails to halve it
    (:data:`STALL`: near the floor set by the conditioning it only fluctuates); the best iterate
    is kept. A factor that can be deflated (PARDISO: :meth:`_Pardiso.deflate`) is deflated when
    its own refinement is slow on a probe column (:data:`DEFLATE_STEPS`), when its first solve is
    off by more than :data:`DEFLATE_TRIGGER`, or when refinement ends above the limit. Returns
    ``(x, residual, limit)``: the residual of the returned ``x`` and the largest acceptable one
    (:func:`residual_limit`; :data:`RESIDUAL_LIMIT` without ``n_equilibrium``).
    """
    deflate = getattr(factor, "deflate", None)
    if deflate is not None and b.ndim == 2 and b.shape[1] > PROBE_COLUMNS and factor.slow_to_refine(b[:, 0]):
        deflate()
    x = factor.solve(b)
    res = relative_residual(A, x, b, n_equilibrium)
    if deflate is not None and res > DEFLATE_TRIGGER and deflate():
        # the factor's own refinement left the solve far off: refinement from there would cost
        # many solves, each with PARDISO's refinement steps, and may not converge at all
        x, res = factor.solve(b), None
    best, best_res, limit = _refine_to_limit(A, factor, b, x, n_equilibrium, target, steps, res)
    if best_res > limit and deflate is not None and deflate():
        # refinement stalled or diverged: the factor is far from A on a few directions; solve
        # those exactly and start again (the first deflated solve can be the worse one)
        x, res, lim = _refine_to_limit(A, factor, b, factor.solve(b), n_equilibrium, target, steps)
        if res < best_res:
            best, best_res, limit = x, res, lim
    return best, best_res, limit


def _refine_to_limit(A, factor, b, x, n_equilibrium, target, steps, res=None):
    """:func:`_refine` in double precision, continued in extended precision where that ends above
    the limit and the factor keeps ``A`` in it (a deflated PARDISO factor): ``(x, residual, limit)``.
    The extended products cost several times the double ones, so they are spent only where needed."""
    best, best_res = _refine(A, factor, b, x, n_equilibrium, target, steps, None, res)
    limit = _limit(A, best, b, best_res, n_equilibrium)
    extended = getattr(factor, "extended", None)
    if best_res > limit and extended is not None:
        x, res = _refine(A, factor, b, best, n_equilibrium, target, steps, extended, best_res)
        if res < best_res:
            best, best_res = x, res
            limit = _limit(A, best, b, best_res, n_equilibrium)
    return best, best_res, limit


def _limit(A, x, b, res, n_equilibrium):
    if n_equilibrium is not None and res > RESIDUAL_LIMIT:  # only then can the floor matter
        return residual_limit(A, x, b, n_equilibrium)
    return RESIDUAL_LIMIT


def _refine(A, factor, b, x, n_equilibrium, target, steps, extended=None, res=None):
    """Iterative refinement from ``x`` (whose residual is ``res``, if known): the best iterate
    and its residual.

    With ``extended`` (``A`` in extended precision) the iterate and its residual are kept in that
    precision: the balance's terms exceed the load by up to ~1e8, so a residual rounded to double
    is off by about the floor of :func:`residual_limit`, and a solve that is not backward stable
    to that level (the deflated one) stalls above it; in extended precision it reaches it.
    """
    if res is None:
        res = relative_residual(A, x, b, n_equilibrium)
    best, best_res = x, res
    xe = be = None
    if extended is not None:
        xe, be = x.astype(extended.dtype), b.astype(extended.dtype)
    for _ in range(steps):
        if best_res <= target:
            break
        if extended is None:
            x = x + factor.solve(b - (A @ x).reshape(b.shape))
        else:
            r = (be - (extended @ xe).reshape(b.shape)).astype(float)
            xe = xe + factor.solve(r).astype(extended.dtype)
            x = xe.astype(float)
        res = relative_residual(A, x, b, n_equilibrium)
        stalled = res > STALL * best_res  # at the round-off floor: more steps only fluctuate
        if res < best_res:
            best, best_res = x, res
        if stalled:
            break
    return best, best_res
