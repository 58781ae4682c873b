"""Bad input raises bem.errors.InputError (a ValueError) whose message names the parameter."""
import numpy as np
import pytest

import bem
from bem import Material, surfaces
from bem.errors import InputError

NAN = float("nan")
SLS = dict(E0=1e6, E_inf=1e7)


@pytest.mark.parametrize("build, name", [
    (lambda: Material.elastic(0.0), "E"),
    (lambda: Material.elastic(-1e6), "E"),
    (lambda: Material.elastic(NAN), "E"),
    (lambda: Material.elastic(np.inf), "E"),
    (lambda: Material.elastic("stiff"), "E"),
    (lambda: Material.elastic(1e6, nu=0.6), "nu"),
    (lambda: Material.elastic(1e6, nu=-0.1), "nu"),
    (lambda: Material.elastic(1e6, nu=NAN), "nu"),
    (lambda: Material.standard_linear_solid(E0=1e7, E_inf=1e7, creep_time=1.0), "E_inf"),
    (lambda: Material.standard_linear_solid(E0=1e7, E_inf=1e6, creep_time=1.0), "E_inf"),
    (lambda: Material.standard_linear_solid(E0=0.0, E_inf=1e6, creep_time=1.0), "E0"),
    (lambda: Material.standard_linear_solid(E0=NAN, E_inf=1e6, creep_time=1.0), "E0"),
    (lambda: Material.standard_linear_solid(**SLS), "relaxation_time or creep_time"),
    (lambda: Material.standard_linear_solid(**SLS, creep_time=1.0, relaxation_time=0.1),
     "relaxation_time or creep_time"),
    (lambda: Material.standard_linear_solid(**SLS, creep_time=0.0), "creep_time"),
    (lambda: Material.standard_linear_solid(**SLS, relaxation_time=-1.0), "relaxation_time"),
    (lambda: Material.standard_linear_solid(**SLS, relaxation_time=NAN), "relaxation_time"),
    (lambda: Material.standard_linear_solid(**SLS, creep_time=1.0, nu=0.7), "nu"),
    (lambda: Material.from_prony(E0=1e6, moduli=[1e6, 2e6], times=[1.0]), "moduli and times"),
    (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[0.0]), "times"),
    (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[-1.0]), "times"),
    (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[NAN]), "times"),
    (lambda: Material.from_prony(E0=1e6, moduli=[-1e6], times=[1.0]), "moduli"),
    (lambda: Material.from_prony(E0=1e6, moduli=[NAN], times=[1.0]), "moduli"),
    (lambda: Material.from_prony(E0=1e6, moduli=[1e6, 1e6], times=[1.0, 1.0]), "times"),
    (lambda: Material.from_prony(E0=-1e6, moduli=[1e6], times=[1.0]), "E0"),
    (lambda: Material.from_prony(E0=1e6, moduli=[[1e6]], times=[[1.0]]), "moduli"),
    (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[1.0], nu=0.51), "nu"),
    (lambda: Material.from_creep(E0=1e6, compliances=[1e-7, 1e-7], times=[1.0]), "compliances and times"),
    (lambda: Material.from_creep(E0=1e6, compliances=[-1e-7], times=[1.0]), "compliances"),
    (lambda: Material.from_creep(E0=1e6, compliances=[1e-6], times=[1.0]), "compliances"),  # E_inf = inf
    (lambda: Material.from_creep(E0=1e6, compliances=[1e-7], times=[0.0]), "times"),
    (lambda: Material.from_creep(E0=1e6, compliances=[NAN], times=[1.0]), "compliances"),
    (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5]), "frequencies, storage and loss"),
    (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5, -1e5]), "loss"),
    (lambda: Material.fit_prony([0.0, 2.0], [1e6, 1e6], [1e5, 1e5]), "frequencies"),
    (lambda: Material.fit_prony([1.0, 2.0], [1e6, NAN], [1e5, 1e5]), "storage"),
    (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5, 1e5], times=[-1.0]), "times"),
    (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5, 1e5], terms_per_decade=0), "terms_per_decade"),
    (lambda: Material.elastic(1e6).folded(-1.0, 1.0), "w_min"),
    (lambda: Material.elastic(1e6).folded(1.0, 0.0), "w_max"),
])
def test_material_rejects(build, name):
    with pytest.raises(InputError, match=name):
        build()


SURFACE = surfaces.sinusoid(64, 1e-3, amplitude=1e-6)
MAT = Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)


@pytest.mark.parametrize("kwargs, name", [
    (dict(speed=0.1, load=0.0), "load"),
    (dict(speed=0.1, load=-1.0), "load"),
    (dict(speed=0.1, load=NAN), "load"),
    (dict(speed=0.1, load=np.inf), "load"),
    (dict(speed=0.1), "load"),  # neither load nor approach
    (dict(speed=0.1, load=1.0, approach=1e-7), "load"),  # both
    (dict(speed=0.1, approach=-1e-7), "approach"),
    (dict(speed=0.1, approach=NAN), "approach"),
    (dict(speed=-0.1, load=1.0), "speed"),
    (dict(speed=NAN, load=1.0), "speed"),
    (dict(speed=np.inf, load=1.0), "speed"),
    (dict(speed="fast", load=1.0), "speed"),
    (dict(speed=0.1, load=1.0, rtol=0.0), "rtol"),
    (dict(speed=0.1, load=1.0, rtol=-1e-8), "rtol"),
    (dict(speed=0.1, load=1.0, rtol=1.0), "rtol"),
    (dict(speed=0.1, load=1.0, rtol=NAN), "rtol"),
    (dict(speed=0.1, load=1.0, initial=np.ones(63)), "initial"),
    (dict(speed=0.1, load=1.0, initial=np.ones((64, 64))), "initial"),
    (dict(speed=0.1, load=1.0, periodic="no"), "periodic"),  # False is valid: isolated contact
    (dict(speed=0.1, load=1.0, method="lemke"), "method"),
])
def test_solve_rejects(kwargs, name):
    with pytest.raises(InputError, match=name):
        bem.solve(SURFACE, MAT, **kwargs)


@pytest.mark.parametrize("surface, material, name", [
    (np.zeros(64), MAT, "surface"),
    ("rough.npy", MAT, "surface"),
    (SURFACE, "rubber", "material"),
    (SURFACE, None, "material"),
])
def test_solve_rejects_wrong_types(surface, material, name):
    with pytest.raises(InputError, match=name):
        bem.solve(surface, material, speed=0.1, load=1.0)


@pytest.mark.parametrize("speeds", [[], [-1.0], [0.1, -0.1], [NAN], [np.inf], [[0.1, 0.2]]])
def test_friction_curve_rejects_speeds(speeds):
    with pytest.raises(InputError, match="speeds"):
        bem.friction_curve(SURFACE, MAT, speeds=speeds, load=1.0)


def test_friction_curve_rejects_load():
    with pytest.raises(InputError, match="load"):
        bem.friction_curve(SURFACE, MAT, speeds=[0.1], load=-1.0)


def test_input_error_is_a_value_error():
    assert issubclass(InputError, ValueError)


# ------------------------------------------------------------ gaps found in 25c6e16, fixed in 2c4d878
@pytest.mark.parametrize("maxiter", [0, -1, 2.5, True])
def test_solve_rejects_maxiter(maxiter):
    with pytest.raises(InputError, match="maxiter"):
        bem.solve(SURFACE, MAT, speed=0.1, load=1.0, maxiter=maxiter)


def test_solve_rejects_nan_initial():
    initial = np.ones(64)
    initial[3] = NAN
    with pytest.raises(InputError, match="initial"):
        bem.solve(SURFACE, MAT, speed=0.1, load=1.0, initial=initial)


def test_friction_curve_rejects_non_numeric_speeds():
    with pytest.raises(InputError, match="speeds"):
        bem.friction_curve(SURFACE, MAT, speeds="fast", load=1.0)


def test_folded_rejects_reversed_band():
    with pytest.raises(InputError, match="w_min"):
        Material.elastic(1e6).folded(10.0, 1.0)


@pytest.mark.parametrize("factor", [1.0, 1.5])
def test_solve_rejects_approach_at_or_beyond_full_contact(factor):
    """At ``max h - mean h`` the zero-mean displacement closes the whole gap: the load is
    unbounded, and beyond it there is no solution (it used to run maxiter iterations)."""
    full = SURFACE.heights.max() - SURFACE.heights.mean()  # 1e-6 m for this sinusoid
    with pytest.raises(InputError, match="approach"):
        bem.solve(SURFACE, MAT, speed=0.1, approach=factor * full, maxiter=10)
