"""FEM reference for viscobem (scikit-fem): steady rolling, steady sliding of a periodic profile and
axisymmetric indentation.

An independent check of the BEM: a different discretisation of the same physics. It
shares only the material type (:class:`bem.Material`) and the error classes with ``bem``.
"""

from .indentation import IndentationResult, indentation
from .profile import ProfileResult, sliding_profile
from .rolling import RollingResult, domain_size, rolling_cylinder

__all__ = [
    "rolling_cylinder",
    "RollingResult",
    "domain_size",
    "sliding_profile",
    "ProfileResult",
    "indentation",
    "IndentationResult",
]
