"""viscobem BEM: steady sliding of rigid (rough) surfaces over linear viscoelastic half-spaces.

Numerics only (numpy + scipy): importing ``bem`` pulls in no plotting, meshing or FEM
package. Units are SI throughout; heights are positive toward the half-space and the
indenter slides in ``+x`` (see :mod:`bem.periodic` for the operator's conventions).
"""
from . import anisotropy, errors, persson, surfaces
from .errors import ConvergenceError, InputError
from .material import Material
from .parallel import get_threads, set_threads, use_threads
from .sliding import FrictionCurve, SlidingResult, friction_curve, solve

__all__ = ["Material", "surfaces", "errors", "anisotropy", "persson", "solve", "friction_curve",
           "SlidingResult", "FrictionCurve", "InputError", "ConvergenceError",
           "set_threads", "get_threads", "use_threads"]
