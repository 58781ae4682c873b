"""The contact solver's options object and public signature (bem.contact)."""

import dataclasses
import inspect
import math

import numpy as np
import pytest

import bem
from bem.contact import ContactOptions, solve_contact
from bem.errors import InputError
from bem.halfspace.periodic import PeriodicHalfSpace

BAD = {bool: [1, None, "yes"], int: [-1, 2.5, True, math.inf], float: [-1.0, math.nan, math.inf, "0.1"]}


def _kind(field):
    value = getattr(ContactOptions(), field.name)
    if field.name == "precondition":
        return None
    return type(value) if type(value) in BAD else None


@pytest.mark.parametrize("field", [f for f in dataclasses.fields(ContactOptions) if _kind(f)], ids=lambda f: f.name)
def test_every_field_is_validated_and_named(field):
    for bad in BAD[_kind(field)]:
        with pytest.raises(InputError, match=rf"options\.{field.name}\b"):
            ContactOptions(**{field.name: bad})


def test_special_fields_are_validated():
    with pytest.raises(InputError, match="options.precondition"):
        ContactOptions(precondition="lines")
    with pytest.raises(dataclasses.FrozenInstanceError):
        ContactOptions().coarsen = False


def test_the_contract_is_small():
    """What a user may set, at most 12 fields; everything else is a named constant of the
    module that uses it (``docs/theory.md`` §4.2 lists both)."""
    assert len(dataclasses.fields(ContactOptions)) <= 12


def test_every_field_has_a_docstring_line():
    """Each tunable says what it trades (the attribute docstring right under it)."""
    source = inspect.getsource(ContactOptions)
    for f in dataclasses.fields(ContactOptions):
        _head, _, rest = source.partition(f"\n    {f.name}:")
        assert rest, f.name
        assert rest.split("\n")[1].strip().startswith('"""'), f"{f.name} has no docstring line"


def test_signature_is_explicit():
    params = inspect.signature(solve_contact).parameters
    assert not any(p.kind in (p.VAR_KEYWORD, p.VAR_POSITIONAL) for p in params.values())
    assert all(params[n].kind == params[n].KEYWORD_ONLY for n in list(params)[2:])


def test_solve_contact_rejects_bad_controls():
    op = PeriodicHalfSpace((16,), 0.01, bem.Material.elastic(1e7), 0.0)
    h = np.cos(np.linspace(0, 2 * np.pi, 16, endpoint=False)) * 1e-6
    with pytest.raises(InputError, match="mean_pressure and approach"):
        solve_contact(op, h)
    with pytest.raises(InputError, match="mean_pressure and approach"):
        solve_contact(op, h, mean_pressure=1e3, approach=1e-7)
    with pytest.raises(InputError, match="options"):
        solve_contact(op, h, mean_pressure=1e3, options={"coarsen": False})


def test_options_reach_the_solver():
    """An option changes the path: the symmetric-part start of a non-symmetric profile (on by
    default) costs products that a plain start does not spend in the same way."""
    s = bem.surfaces.profile(512, 0.01, hurst=0.8, scales=64, rms_slope=0.1, seed=2)
    sls = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)  # phase < 45 deg
    a = bem.solve(s, sls, speed=0.01, load=30.0)
    b = bem.solve(s, sls, speed=0.01, load=30.0, contact_options=ContactOptions(symmetric_start=False))
    assert a.success and b.success
    assert a.matvecs != b.matvecs
    np.testing.assert_allclose(a.pressure, b.pressure, rtol=0, atol=1e-6 * a.pressure.max())
