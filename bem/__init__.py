"""viscobem BEM: steady sliding of rigid (rough) surfaces over linear viscoelastic half-spaces.

Numerics only (numpy + scipy): importing ``bem`` pulls in no plotting, meshing or FEM
package. Units are SI throughout; heights are positive toward the half-space and the
indenter slides in ``+x`` (see :mod:`bem.periodic` for the operator's conventions).

The package loads lazily: ``import bem`` is cheap, and each public name below imports
its module on first use (PEP 562 module ``__getattr__``), as does every submodule
(``bem.periodic``), so a script that needs only the periodic solver never pays for
Persson's theory or the anisotropy tools.
"""

import importlib
import importlib.util

# public name -> (module, attribute); attribute None: the name is the module itself
_LAZY = {
    "Material": ("bem.material", "Material"),
    "solve": ("bem.sliding", "solve"),
    "friction_curve": ("bem.sweep", "friction_curve"),
    "SlidingResult": ("bem.sliding", "SlidingResult"),
    "FrictionCurve": ("bem.sweep", "FrictionCurve"),
    "InputError": ("bem.errors", "InputError"),
    "ConvergenceError": ("bem.errors", "ConvergenceError"),
    "surfaces": ("bem.surfaces", None),
    "errors": ("bem.errors", None),
    "anisotropy": ("bem.anisotropy", None),
    "persson": ("bem.persson", None),
    "temperature": ("bem.temperature", None),
    "set_threads": ("bem.parallel", "set_threads"),
    "get_threads": ("bem.parallel", "get_threads"),
    "use_threads": ("bem.parallel", "use_threads"),
}

__all__ = list(_LAZY)


def __getattr__(name):
    if name in _LAZY:
        module, attribute = _LAZY[name]
    elif not name.startswith("_") and importlib.util.find_spec(f"bem.{name}") is not None:
        module, attribute = f"bem.{name}", None  # any submodule, e.g. bem.periodic
    else:
        raise AttributeError(f"module 'bem' has no attribute {name!r}")
    value = importlib.import_module(module)
    if attribute is not None:
        value = getattr(value, attribute)
    globals()[name] = value  # later lookups skip this function
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
