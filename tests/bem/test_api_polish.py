"""The public API's manners: mistyped keywords are named, numbers are required where numbers
are meant, messages show plain numbers, results print in one short line."""

import numpy as np
import pytest

import bem
from bem import surfaces
from bem.adaptive import solve_adaptive
from bem.checks import check_int, check_positive, check_range, show
from bem.errors import InputError
from bem.sliding import ADAPTIVE_OPTIONS

ELASTIC = bem.Material.elastic(1e7)
S = surfaces.sinusoid(32, 1e-3, amplitude=1e-6)


def test_a_mistyped_keyword_is_named_with_the_closest_valid_one():
    with pytest.raises(InputError, match=r"unknown keyword argument 'lod' \(did you mean 'load'\?\)"):
        bem.solve(S, ELASTIC, speed=0.0, lod=0.3)
    with pytest.raises(InputError, match=r"'rtl' \(did you mean 'rtol'\?\)"):
        bem.solve(S, ELASTIC, speed=0.0, load=0.3, rtl=1e-6)
    with pytest.raises(InputError, match=r"'level' \(did you mean 'levels'\?\)"):
        bem.solve(
            surfaces.sphere(radius=1e-2, n=32, length=2e-3),
            ELASTIC,
            speed=0.0,
            load=1.0,
            periodic=False,
            method="adaptive",
            level=2,
        )


def test_an_adaptive_option_without_the_adaptive_method_says_so():
    with pytest.raises(InputError, match=r"'levels' is an option of method='adaptive'.*got method='auto'"):
        bem.solve(S, ELASTIC, speed=0.0, load=0.3, levels=2)


def test_solve_passes_on_exactly_the_adaptive_solvers_own_options():
    import inspect

    own = set(inspect.signature(solve_adaptive).parameters) - {
        "surface",
        "material",
        "speed",
        "load",
        "rtol",
        "maxiter",
        "raise_on_failure",
    }
    assert own == set(ADAPTIVE_OPTIONS)


@pytest.mark.parametrize(
    "name, value", [("speed", "0.01"), ("load", "1"), ("rtol", "1e-8"), ("speed", True), ("load", b"1"), ("speed", 1j)]
)
def test_numbers_are_required_where_numbers_are_meant(name, value):
    kw = {"speed": 0.0, "load": 1.0} | {name: value}
    with pytest.raises(InputError, match=rf"^{name} must be a real number.*got {value!r}"):
        bem.solve(S, ELASTIC, **kw)


def test_approach_as_a_string_is_refused():
    with pytest.raises(InputError, match=r"approach must be a real number \(not a string\), got '1e-7'"):
        bem.solve(S, ELASTIC, speed=0.0, approach="1e-7")


def test_messages_show_plain_numbers():
    for call in (
        lambda: bem.solve(S, ELASTIC, speed=0.0, load=np.float64(-1.0)),
        lambda: bem.solve(S, ELASTIC, speed=np.float32(-2.0), load=1.0),
        lambda: bem.solve(S, ELASTIC, speed=0.0, load=1.0, rtol=np.float64(2.0)),
        lambda: check_range("hurst", np.float64(1.5), np.float64(0.0), np.float64(1.0)),
        lambda: surfaces.sinusoid(np.int64(1), 1e-3, amplitude=1e-6),
    ):
        with pytest.raises(InputError) as err:
            call()
        assert "np." not in str(err.value) and "float64" not in str(err.value)
    with pytest.raises(InputError, match=r"got -1\.0$"):
        bem.solve(S, ELASTIC, speed=0.0, load=np.float64(-1.0))
    assert show(np.float64(0.5)) == "0.5" and show(np.int64(3)) == "3" and show(np.array(2.0)) == "2.0"


def test_integer_messages_read_properly():
    with pytest.raises(InputError, match=r"^n must be an integer >= 2, got 1$"):
        check_int("n", 1, 2)
    with pytest.raises(InputError, match=r"^dim must be an integer in \[1, 2\], got 3$"):
        check_int("dim", 3, 1, 2)
    with pytest.raises(InputError, match=r"^n must be an integer >= 2, got 2\.0$"):
        check_int("n", 2.0, 2)
    assert check_positive("x", np.float32(0.5)) == 0.5


def test_results_print_one_short_line():
    res = bem.solve(S, ELASTIC, speed=0.0, load=0.3)
    text = repr(res)
    assert text.startswith("SlidingResult(converged, shape=(32,), speed=0 m/s, load=0.3,")
    assert "\n" not in text and "array" not in text and len(text) < 300
    sphere = surfaces.sphere(radius=1e-2, n=32, length=2e-3)
    adaptive = bem.solve(sphere, ELASTIC, speed=0.0, load=1.0, periodic=False, method="adaptive", levels=1)
    assert repr(adaptive).startswith("AdaptiveResult(converged, shape=(32, 32),") and len(repr(adaptive)) < 300
    curve = bem.friction_curve(
        S, bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01), speeds=[1e-3, 1e-2], load=0.3
    )
    assert repr(curve).startswith(
        "FrictionCurve(load=0.3, 2 speeds from 0.001 to 0.01 m/s, 2 converged, peak friction "
    )
    assert len(repr(curve)) < 200
