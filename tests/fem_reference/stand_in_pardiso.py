"""A stand-in for ``pypardiso`` that behaves like PARDISO on the FEM's saddle-point systems, so that
the PARDISO paths of :mod:`fem_reference.linsolve` (its own refinement, the probe, deflation,
refinement in extended precision) run in the default test run on a machine without pypardiso.

PARDISO pivots statically: a pivot below ``1e-8 ||A||`` (``iparm[10] = 8``) is replaced by that
size, so its factor is the exact factor of a nearby matrix. The stand-in factors ``A + E`` with
SuperLU, ``E`` a perturbation of ``perturbed`` diagonal entries by ``size * max|A|`` (the zero
pressure block of an incompressible solid is where PARDISO perturbs), refines with ``A`` itself up
to ``iparm[8]`` steps as PARDISO does, and reports the steps taken (``iparm[7]``), the perturbed
pivots (``iparm[14]``) and the factor's entries (``iparm[18]``).
"""

import types

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def module(perturbed=4, size=1e-8, seed=0):
    """A module object to put in ``sys.modules["pypardiso"]``."""

    class PyPardisoSolver:
        def __init__(self):
            self.iparm = {}
            self.libmkl = types.SimpleNamespace(mkl_free_buffers=lambda: None)

        def set_matrix_type(self, mtype):
            self.mtype = mtype

        def set_iparm(self, key, value):
            self.iparm[key] = value

        def get_iparm(self, key):
            return self.iparm.get(key, 0)

        def set_statistical_info_off(self):
            pass

        def free_memory(self, everything=False):
            self._lu = None

        def factorize(self, A):
            A = sp.csc_matrix(A)
            n = A.shape[0]
            # the rows whose diagonal is smallest relative to the row: where static pivoting bites
            diag = np.abs(A.diagonal())
            rows = np.asarray(abs(A).max(axis=1).todense()).ravel()
            rng = np.random.default_rng(seed)
            order = np.lexsort((rng.random(n), diag / np.maximum(rows, 1e-300)))
            hit = order[: min(perturbed, n)]
            E = sp.csc_matrix((np.full(hit.size, size * abs(A).max()), (hit, hit)), shape=A.shape)
            self._lu = spla.splu(A + E, permc_spec="COLAMD")
            self.iparm[14] = int(hit.size)
            self.iparm[18] = int(self._lu.L.nnz + self._lu.U.nnz)

        def solve(self, A, b):
            b = np.asarray(b, dtype=float)
            x = self._lu.solve(b)
            steps = 0
            scale = np.linalg.norm(b)
            for _ in range(int(self.iparm.get(8, 0))):
                r = b - (A @ x).reshape(b.shape)
                if np.linalg.norm(r) <= 1e-14 * scale:
                    break
                x = x + self._lu.solve(r)
                steps += 1
            self.iparm[7] = steps
            return x

    return types.SimpleNamespace(PyPardisoSolver=PyPardisoSolver, __name__="pypardiso")
