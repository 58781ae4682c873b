"""The public names of ``bem`` (docs/python.md and the API reference) stay importable where users
import them from, whatever the package's inner layout: the top-level names, the public modules
``bem.surfaces``, ``bem.contact``, ``bem.errors``, ``bem.temperature``, ``bem.anisotropy`` and
``bem.persson`` by attribute, by ``import`` and by ``from ... import``."""

import importlib
import subprocess
import sys

import pytest

TOP_LEVEL = [
    "Material",
    "solve",
    "friction_curve",
    "SlidingResult",
    "FrictionCurve",
    "friction_map",
    "FrictionMap",
    "InputError",
    "ConvergenceError",
    "surfaces",
    "errors",
    "anisotropy",
    "persson",
    "temperature",
    "set_threads",
    "get_threads",
    "use_threads",
]
MODULE_NAMES = {
    "bem.surfaces": ["Surface", "from_heights", "self_affine", "profile", "sinusoid", "sphere", "cylinder", "load"],
    "bem.contact": ["ContactOptions", "solve_contact"],
    "bem.errors": ["InputError", "ConvergenceError", "ViscobemError"],
    "bem.temperature": ["WLF", "Arrhenius"],
    "bem.anisotropy": ["spectral_moments", "contact_psd", "psd_contour"],
    "bem.persson": ["friction", "friction_for_surface"],
}


@pytest.mark.parametrize("name", TOP_LEVEL)
def test_top_level_name(name):
    import bem

    assert getattr(bem, name) is not None
    assert name in dir(bem)


@pytest.mark.parametrize("module", sorted(MODULE_NAMES))
def test_public_module_by_import_and_attribute(module):
    import bem

    imported = importlib.import_module(module)
    assert getattr(bem, module.split(".")[1]) is imported  # bem.temperature is the same object
    for name in MODULE_NAMES[module]:
        assert getattr(imported, name) is not None, f"{module}.{name}"


def test_aliases_are_the_modules_that_define_them():
    """``bem.temperature`` is :mod:`bem.materials.temperature` itself (one module object, so
    ``isinstance`` checks and module state agree), in a fresh interpreter where nothing else
    imported it first; ``from bem.anisotropy import ...`` works there too."""
    code = (
        "import sys; from bem.temperature import WLF; from bem.anisotropy import spectral_moments; "
        "import bem.persson; import bem; "
        "assert sys.modules['bem.temperature'] is sys.modules['bem.materials.temperature']; "
        "assert bem.anisotropy is sys.modules['bem.analysis.anisotropy']; "
        "assert WLF.__module__ == 'bem.materials.temperature'; print('ok')"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def test_an_unknown_name_is_an_attribute_error():
    import bem

    with pytest.raises(AttributeError, match="no attribute 'solver'"):
        bem.solver  # noqa: B018
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("bem.temperatures")
