"""Scenes: one study described in a TOML file, parsed into validated objects.

Schema (SI units; unknown keys are an error that lists the valid ones)::

    title = "..."                      # optional
    [material]   nu = 0.5 and one of:  E  |  E0, E_inf, creep_time | relaxation_time
                 |  E0, moduli, times (Prony)  |  E0, compliances, times (creep)
                 |  dma = "file.csv" (columns: frequency, storage E' (Pa), loss E'' (Pa);
                    dma_frequency_unit = "rad/s" | "Hz"; dma_terms_per_decade = 2.0)
    [surface]    kind = "self_affine" | "sinusoid" | "file", length (m), n, and per kind:
                 self_affine: hurst, scales, rms_height | rms_slope, seed, rolloff,
                              anisotropy, dim (1 or 2)
                 sinusoid:    amplitude (m), wavelength (m), dim, direction
                 file:        path (.npy/.txt/.csv, relative to the scene file), unit
    [loading]    load (N; N/m for 1-D profiles) and speeds = [...] (m/s) or
                 xi = {start, stop, num} (log-spaced, xi = v tau / L; tau = xi_time or the
                 material's longest creep time)
    [solver]     rtol, maxiter, warm_start
    [outputs]    friction_curve, fields, plots, vtk  (booleans)
"""
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bem import Material, surfaces
from bem.checks import check_positive
from bem.errors import InputError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

SCHEMA = {
    "": {"title", "material", "surface", "loading", "solver", "outputs"},
    "material": {"nu", "E", "E0", "E_inf", "creep_time", "relaxation_time", "moduli", "times",
                 "compliances", "dma", "dma_frequency_unit", "dma_terms_per_decade"},
    "surface": {"kind", "length", "n", "hurst", "scales", "rms_height", "rms_slope", "seed",
                "rolloff", "anisotropy", "dim", "amplitude", "wavelength", "direction", "path", "unit"},
    "loading": {"load", "speeds", "xi", "xi_time"},
    "solver": {"rtol", "maxiter", "warm_start"},
    "outputs": {"friction_curve", "fields", "plots", "vtk", "anisotropy", "contact_psd"},
}
SURFACE_KINDS = ("self_affine", "sinusoid", "file")
DEFAULT_SCENE = Path(__file__).with_name("scenes") / "seed.toml"


@dataclass(frozen=True)
class Scene:
    """A parsed, validated study."""

    title: str
    material: Material
    surface: surfaces.Surface
    load: float
    speeds: np.ndarray
    xi: np.ndarray
    xi_time: float
    rtol: float = 1e-8
    maxiter: int = 100
    warm_start: bool = True
    outputs: dict = field(default_factory=dict)
    source: str = ""
    raw: dict = field(default_factory=dict, repr=False)


def _check_keys(table, section):
    valid = SCHEMA[section]
    if not isinstance(table, dict):
        raise InputError(f"[{section}] must be a table of keys ({', '.join(sorted(valid))}), got {table!r}")
    unknown = sorted(set(table) - valid)
    if unknown:
        where = f"[{section}]" if section else "the top level"
        raise InputError(f"unknown key(s) {', '.join(map(repr, unknown))} in {where} of the scene; "
                         f"valid keys: {', '.join(sorted(valid))}")


def _material(t, base):
    _check_keys(t, "material")
    nu = t.get("nu", 0.5)
    markers = {"E": "E", "E_inf": "sls", "moduli": "prony", "compliances": "creep", "dma": "dma"}
    present = [kind for key, kind in markers.items() if key in t]
    if len(present) != 1:
        raise InputError("[material] needs exactly one of: E | E0, E_inf, creep_time or relaxation_time "
                         "| E0, moduli, times | E0, compliances, times | dma (file); got keys "
                         f"{sorted(t)}")
    kind = present[0]
    if kind in ("sls", "prony", "creep") and "E0" not in t:
        raise InputError(f"[material] E0 (relaxed modulus, Pa) is required with {sorted(t)}")
    if kind == "E":
        return Material.elastic(t["E"], nu=nu)
    if kind == "sls":
        return Material.standard_linear_solid(E0=t["E0"], E_inf=t["E_inf"], creep_time=t.get("creep_time"),
                                              relaxation_time=t.get("relaxation_time"), nu=nu)
    if kind == "prony":
        return Material.from_prony(E0=t["E0"], moduli=t["moduli"], times=t.get("times", []), nu=nu)
    if kind == "creep":
        return Material.from_creep(E0=t["E0"], compliances=t["compliances"], times=t.get("times", []), nu=nu)
    if not isinstance(t["dma"], str):
        raise InputError(f"[material] dma must be a file path (string), got {t['dma']!r}")
    path = (base / t["dma"]).resolve()
    try:
        data = np.loadtxt(path, delimiter="," if path.suffix == ".csv" else None, comments="#", ndmin=2)
    except (OSError, ValueError) as err:
        raise InputError(f"[material] dma: cannot read {str(path)!r}: {err}") from None
    if data.shape[1] < 3:
        raise InputError(f"[material] dma: {str(path)!r} needs 3 columns (frequency, storage, loss)")
    unit = t.get("dma_frequency_unit", "rad/s")
    if unit not in ("rad/s", "Hz"):
        raise InputError(f"[material] dma_frequency_unit must be 'rad/s' or 'Hz', got {unit!r}")
    return Material.fit_prony(data[:, 0], data[:, 1], data[:, 2], hz=unit == "Hz",
                              terms_per_decade=t.get("dma_terms_per_decade", 2.0), nu=nu)


def _surface(t, base):
    _check_keys(t, "surface")
    kind = t.get("kind")
    if kind not in SURFACE_KINDS:
        raise InputError(f"[surface] kind must be one of {', '.join(SURFACE_KINDS)} (periodic cells), "
                         f"got {kind!r}")
    for key in ("length",) + (("n",) if kind != "file" else ()):
        if key not in t:
            raise InputError(f"[surface] {key} is required for kind = {kind!r}")
    if kind == "self_affine":
        allowed = {"hurst", "scales", "rms_height", "rms_slope", "seed", "rolloff", "anisotropy", "dim"}
        args = {k: t[k] for k in allowed if k in t}
        return surfaces.self_affine(t["n"], t["length"], **args)
    if kind == "sinusoid":
        args = {k: t[k] for k in ("amplitude", "wavelength", "dim", "direction") if k in t}
        return surfaces.sinusoid(t["n"], t["length"], **args)
    if not isinstance(t.get("path"), str):
        raise InputError(f"[surface] path (a file path string) is required for kind = 'file', got "
                         f"{t.get('path')!r}")
    return surfaces.load(base / t["path"], t["length"], unit=t.get("unit", "m"))


def _number(section, key, value):
    """``float(value)`` for a TOML number (not a bool or string), else InputError naming it."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"[{section}] {key} must be a number, got {value!r}")
    return float(value)


def _speeds(t, material, surface):
    _check_keys(t, "loading")
    if "load" not in t:
        raise InputError("[loading] load is required (N for 2-D surfaces, N/m for 1-D profiles)")
    load = check_positive("[loading] load (N, or N/m for 1-D profiles)", _number("loading", "load", t["load"]))
    if material.is_elastic:
        tau = t.get("xi_time", 1.0)
    else:
        tau = t.get("xi_time", material.creep_times.max())
    tau = check_positive("[loading] xi_time (s)", _number("loading", "xi_time", tau))
    if ("speeds" in t) == ("xi" in t):
        raise InputError("[loading] give exactly one of speeds = [...] (m/s) or xi = {start, stop, num}")
    if "speeds" in t:
        values = t["speeds"] if isinstance(t["speeds"], list) else [t["speeds"]]
        speeds = np.array([_number("loading", "speeds", v) for v in values], dtype=float)
        if speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
            raise InputError(f"[loading] speeds must be a non-empty list of finite speeds >= 0 m/s, "
                             f"got {t['speeds']!r}")
        return load, speeds, speeds * tau / surface.length, tau
    xi = t["xi"]
    if not isinstance(xi, dict) or set(xi) != {"start", "stop", "num"}:
        raise InputError("[loading] xi must be a table {start, stop, num} (log-spaced)")
    start, stop = (_number("loading", f"xi.{k}", xi[k]) for k in ("start", "stop"))
    num = xi["num"]
    if isinstance(num, bool) or not isinstance(num, int) or num < 1:
        raise InputError(f"[loading] xi.num must be an integer >= 1, got {num!r}")
    if not (0 < start <= stop < np.inf):
        raise InputError(f"[loading] xi needs 0 < start <= stop (finite), got {xi}")
    values = np.logspace(np.log10(start), np.log10(stop), num)
    return load, values * surface.length / tau, values, tau


def _solver(t):
    _check_keys(t, "solver")
    rtol = _number("solver", "rtol", t.get("rtol", 1e-8))
    if not 0 < rtol < 1:
        raise InputError(f"[solver] rtol must be in (0, 1), got {rtol!r}")
    maxiter = t.get("maxiter", 400)
    if isinstance(maxiter, bool) or not isinstance(maxiter, int) or maxiter < 1:
        raise InputError(f"[solver] maxiter must be an integer >= 1, got {maxiter!r}")
    warm = t.get("warm_start", True)
    if not isinstance(warm, bool):
        raise InputError(f"[solver] warm_start must be true or false, got {warm!r}")
    return rtol, maxiter, warm


def parse(text, *, base=Path("."), source="<string>"):
    """Parse scene TOML ``text``; relative paths resolve against ``base``."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"scene {source}: not valid TOML: {err}") from None
    _check_keys(raw, "")
    for section in ("material", "surface", "loading"):
        if section not in raw:
            raise InputError(f"scene {source}: section [{section}] is required")
    material = _material(raw["material"], base)
    surface = _surface(raw["surface"], base)
    load, speeds, xi, tau = _speeds(raw["loading"], material, surface)
    rtol, maxiter, warm_start = _solver(raw.get("solver", {}))
    outputs = {"friction_curve": True, "fields": True, "plots": True, "vtk": False,
               "anisotropy": False, "contact_psd": False}
    _check_keys(raw.get("outputs", {}), "outputs")
    outputs.update(raw.get("outputs", {}))
    for key, value in outputs.items():
        if not isinstance(value, bool):
            raise InputError(f"[outputs] {key} must be true or false, got {value!r}")
    for key in ("anisotropy", "contact_psd"):
        if outputs[key]:
            raise InputError(f"[outputs] {key} = true is not available in this version of viscobem")
    return Scene(title=str(raw.get("title", Path(source).stem)), material=material, surface=surface,
                 load=load, speeds=speeds, xi=xi, xi_time=tau, rtol=rtol, maxiter=maxiter,
                 warm_start=warm_start, outputs=outputs, source=source, raw=raw)


def load(path=None):
    """Read a scene file (the built-in seed study when ``path`` is None)."""
    path = Path(path) if path is not None else DEFAULT_SCENE
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise InputError(f"scene: cannot read {str(path)!r}: {err.strerror}") from None
    except UnicodeDecodeError:
        raise InputError(f"scene: cannot read {str(path)!r}: not a UTF-8 text (TOML) file") from None
    return parse(text, base=path.parent, source=str(path))
