"""viscobem BEM: steady sliding of rigid (rough) surfaces over linear viscoelastic half-spaces.

Numerics only (numpy + scipy): importing ``bem`` pulls in no plotting, meshing or FEM
package. Units are SI throughout; heights are positive toward the half-space and the
indenter slides in ``+x`` (see :mod:`bem.halfspace.periodic` for the operator's conventions).

Workflow, one subpackage a step:

1. a material (:mod:`bem.materials`: :class:`Material` from a series, a DMA fit or a master
   curve, at any temperature);
2. a rigid surface (:mod:`bem.surfaces`: generated, analytic or measured);
3. one solve (:func:`solve`, :mod:`bem.sliding`) or a friction curve (:func:`friction_curve`,
   :mod:`bem.sweep`): a response operator of :mod:`bem.halfspace` and the complementarity
   solver of :mod:`bem.contact`, along any direction (:mod:`bem.direction`);
4. the result (:class:`SlidingResult`) and what it implies (:mod:`bem.analysis`: anisotropy,
   Persson's theory).

Shared by all: :mod:`bem.errors`, the argument checks of :mod:`bem.checks`, the FFT
convention of :mod:`bem.fft` and the thread setting of :mod:`bem.parallel`.

The package loads lazily: ``import bem`` is cheap, and each public name below imports
its module on first use (PEP 562 module ``__getattr__``), as does every subpackage
(``bem.halfspace``), so a script that needs only the periodic solver never pays for
Persson's theory or the anisotropy tools. ``bem.temperature``, ``bem.anisotropy`` and
``bem.persson`` are the public names of :mod:`bem.materials.temperature`,
:mod:`bem.analysis.anisotropy` and :mod:`bem.analysis.persson` (the same module objects, also
for ``import bem.temperature``).
"""

import importlib
import importlib.abc
import importlib.util
import sys

# public name -> (module, attribute); attribute None: the name is the module itself
_LAZY = {
    "Material": ("bem.materials.material", "Material"),
    "solve": ("bem.sliding", "solve"),
    "friction_curve": ("bem.sweep", "friction_curve"),
    "SlidingResult": ("bem.result", "SlidingResult"),
    "FrictionCurve": ("bem.sweep", "FrictionCurve"),
    "friction_map": ("bem.superposition", "friction_map"),
    "FrictionMap": ("bem.superposition", "FrictionMap"),
    "InputError": ("bem.errors", "InputError"),
    "ConvergenceError": ("bem.errors", "ConvergenceError"),
    "surfaces": ("bem.surfaces", None),
    "errors": ("bem.errors", None),
    "anisotropy": ("bem.analysis.anisotropy", None),
    "persson": ("bem.analysis.persson", None),
    "temperature": ("bem.materials.temperature", None),
    "set_threads": ("bem.parallel", "set_threads"),
    "get_threads": ("bem.parallel", "get_threads"),
    "use_threads": ("bem.parallel", "use_threads"),
    "set_blas_threads": ("bem.parallel", "set_blas_threads"),
    "get_blas_threads": ("bem.parallel", "get_blas_threads"),
}

# public module names that live in a subpackage: ``import bem.temperature`` gives the module itself
_ALIASES = {
    "bem.temperature": "bem.materials.temperature",
    "bem.anisotropy": "bem.analysis.anisotropy",
    "bem.persson": "bem.analysis.persson",
}


class _AliasLoader(importlib.abc.Loader):
    def create_module(self, spec):
        return importlib.import_module(_ALIASES[spec.name])

    def exec_module(self, module):
        pass  # the target module ran when it was imported


class _AliasFinder(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name in _ALIASES:
            return importlib.util.spec_from_loader(name, _AliasLoader())
        return None


if not any(isinstance(f, _AliasFinder) for f in sys.meta_path):
    sys.meta_path.insert(0, _AliasFinder())

__all__ = list(_LAZY)


def __getattr__(name):
    if name in _LAZY:
        module, attribute = _LAZY[name]
    elif not name.startswith("_") and importlib.util.find_spec(f"bem.{name}") is not None:
        module, attribute = f"bem.{name}", None  # any subpackage or module, e.g. bem.halfspace
    else:
        raise AttributeError(f"module 'bem' has no attribute {name!r}")
    value = importlib.import_module(module)
    if attribute is not None:
        value = getattr(value, attribute)
    globals()[name] = value  # later lookups skip this function
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
