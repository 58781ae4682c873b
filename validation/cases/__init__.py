"""Registry of the validation cases (name -> :class:`Case`).

Every case runs in a quick configuration (coarse grids, few speeds: the CI regression set)
and a full one; each lists only solvers that exist and justifies each tolerance beside its
settings.
"""

from .base import Case, CaseOutput, Check, Profile, Run, Sweep
from .cylinder import CASES as _CYLINDER
from .periodic import CASES as _PERIODIC
from .rough_profile import CASES as _ROUGH_PROFILE
from .rubber import CASES as _RUBBER
from .sphere import CASES as _SPHERE

CASES = {case.name: case for case in (*_CYLINDER, *_RUBBER, *_SPHERE, *_PERIODIC, *_ROUGH_PROFILE)}

__all__ = ["CASES", "Case", "CaseOutput", "Check", "Profile", "Run", "Sweep"]
