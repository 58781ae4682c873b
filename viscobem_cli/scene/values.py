"""Checks of single scene values: numbers, loads, the [solver] and [outputs] tables, and
``--set`` overrides. Each raises :class:`~bem.errors.InputError` naming the key, its valid
range and the value received."""

import sys

import numpy as np

from bem.checks import check_positive
from bem.errors import InputError

from .schema import default

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["number", "loads", "solver", "outputs", "override"]


def number(section, key, value):
    """``float(value)`` for a TOML number (not a bool or string), else InputError naming it."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"[{section}] {key} must be a number, got {value!r}")
    return float(value)


def outputs(t, surface):
    """The [outputs] booleans with their defaults, and the fields' precision (keys already checked)."""
    outputs = {
        "friction_curve": True,
        "fields": True,
        "plots": True,
        "vtk": False,
        "anisotropy": False,
        "contact_psd": False,
        "persson": False,
    }
    outputs.update(t)
    precision = outputs.pop("fields_precision", "float32")
    if precision not in ("float32", "float64"):
        raise InputError(f"[outputs] fields_precision must be 'float32' or 'float64', got {precision!r}")
    for key, value in outputs.items():
        if not isinstance(value, bool):
            raise InputError(f"[outputs] {key} must be true or false, got {value!r}")
    for key in ("anisotropy", "contact_psd", "persson"):
        if outputs[key] and surface.ndim != 2:
            raise InputError(f"[outputs] {key} needs a 2-D surface (dim = 2), got a 1-D profile")
    return outputs, precision


def loads(loading, surface):
    """The loads (N; N/m for 1-D profiles; on the scanned patch for a measured surface) of the
    [loading] table: its ``load``, or the forces its ``nominal_pressure`` (Pa) puts on ``surface``."""
    given = [k for k in ("load", "nominal_pressure") if k in loading]
    if len(given) != 1:
        raise InputError(
            "[loading] needs exactly one of load (N for 2-D surfaces, N/m for 1-D profiles; on the scanned "
            "patch for a measured surface) and nominal_pressure (Pa, the mean pressure), got "
            + (" and ".join(given) if given else "neither")
        )
    key = given[0]
    value = loading[key]
    values = value if isinstance(value, list) else [value]
    if not values or not all(
        isinstance(v, (int, float)) and not isinstance(v, bool) and 0 < v < np.inf for v in values
    ):
        unit = "N; N/m for 1-D profiles" if key == "load" else "Pa"
        raise InputError(
            f"[loading] {key} must be a finite number > 0 or a non-empty list of them ({unit}), got {value!r}"
        )
    if key == "nominal_pressure":
        from bem.sliding import load_of_pressure

        return tuple(float(load_of_pressure(surface, p)) for p in values)
    return tuple(float(v) for v in values)


def solver(t):
    """The [solver] table with the schema's defaults (:data:`viscobem_cli.scene.schema.KEYS`)."""

    def get(key):
        return t.get(key, default("solver", key))

    def integer(key, low):
        v = get(key)
        if isinstance(v, bool) or not isinstance(v, int) or v < low:
            raise InputError(f"[solver] {key} must be an integer >= {low}, got {v!r}")
        return v

    rtol = number("solver", "rtol", get("rtol"))
    if not 0 < rtol < 1:
        raise InputError(f"[solver] rtol must be in (0, 1), got {rtol!r}")
    warm = get("warm_start")
    if not isinstance(warm, bool):
        raise InputError(f"[solver] warm_start must be true or false, got {warm!r}")
    fold = get("fold_tol")
    if not (isinstance(fold, (int, float)) and 0 <= fold < 1):
        raise InputError(f"[solver] fold_tol must be in [0, 1) (0: no folding), got {fold!r}")
    scheduler = t.get("scheduler")
    if scheduler is not None and not (isinstance(scheduler, str) and scheduler):
        raise InputError(f"[solver] scheduler must be an address such as 'tcp://host:8786', got {scheduler!r}")
    estimate = t.get("error_estimate", "indicators")
    if estimate not in ("indicators", "refined", "none"):
        raise InputError(
            f"[solver] error_estimate must be 'indicators' (from the solution), 'refined' (a solve on the "
            f"grid twice as fine) or 'none', got {estimate!r}"
        )
    return {
        "rtol": float(rtol),
        "error_estimate": None if estimate == "none" else estimate,
        "maxiter": integer("maxiter", 1),
        "warm_start": warm,
        "workers": integer("workers", 1),
        "chunk": integer("chunk", 0),
        "scheduler": scheduler,
        "fold_tol": float(fold),
    }


def override(raw, item):
    """Apply one ``section.key=value`` override (TOML value; a bare word is a string) to ``raw``."""
    path, sep, value = str(item).partition("=")
    keys = [k.strip() for k in path.split(".")]
    if not sep or not all(keys):
        raise InputError(f"--set needs section.key=value (e.g. surface.n=64), got {item!r}")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    table = raw
    for key in keys[:-1]:
        table = table.setdefault(key, {})
        if not isinstance(table, dict):
            raise InputError(f"--set {item!r}: {key!r} is not a table")
    table[keys[-1]] = parsed


def xi_time(t, material):
    """tau of xi = v tau / l (s) and where it comes from."""
    if "xi_time" in t:
        source = "[loading] xi_time"
        tau = t["xi_time"]
    elif material.is_elastic:
        source, tau = "elastic material: 1 s; set [loading] xi_time to change it", 1.0
    else:
        tau = material.creep_times.max()
        source = "the material's longest creep time; set [loading] xi_time to change it"
    return check_positive("[loading] xi_time (s)", number("loading", "xi_time", tau)), source


def speeds(t, tau, length):
    """Speeds (m/s) and xi of the [loading] table; ``xi = v tau / length``."""
    if ("speeds" in t) == ("xi" in t):
        raise InputError("[loading] give exactly one of speeds = [...] (m/s) or xi = {start, stop, num}")
    if "speeds" in t:
        values = t["speeds"] if isinstance(t["speeds"], list) else [t["speeds"]]
        speeds = np.array([number("loading", "speeds", v) for v in values], dtype=float)
        if speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
            raise InputError(
                f"[loading] speeds must be a non-empty list of finite speeds >= 0 m/s, got {t['speeds']!r}"
            )
        return speeds, speeds * tau / length
    xi = t["xi"]
    if isinstance(xi, list):
        values = np.asarray(xi, dtype=float) if all(isinstance(x, (int, float)) for x in xi) else None
        if values is None or values.size == 0 or not np.all(values > 0):
            raise InputError(f"[loading] xi as a list must hold numbers > 0, got {xi!r}")
        return values * length / tau, values
    if not isinstance(xi, dict) or set(xi) != {"start", "stop", "num"}:
        raise InputError("[loading] xi must be a table {start, stop, num} (log-spaced) or a list of values")
    start, stop = (number("loading", f"xi.{k}", xi[k]) for k in ("start", "stop"))
    num = xi["num"]
    if isinstance(num, bool) or not isinstance(num, int) or num < 1:
        raise InputError(f"[loading] xi.num must be an integer >= 1, got {num!r}")
    if not (0 < start <= stop < np.inf):
        raise InputError(f"[loading] xi needs 0 < start <= stop (finite), got {xi}")
    values = np.logspace(np.log10(start), np.log10(stop), num)
    return values * length / tau, values
