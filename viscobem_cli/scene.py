"""Scenes: one study described in a TOML file, parsed into validated objects.

Schema (SI units; unknown keys are an error that lists the valid ones)::

    title = "..."                      # optional
    [material]   nu = 0.5 and one of:  E  |  E0, E_inf, creep_time | relaxation_time
                 |  E0, moduli, times (Prony)  |  E0, compliances, times (creep)
                 |  dma = "file.csv" (columns: frequency, storage E' (Pa), loss E'' (Pa);
                    dma_frequency_unit = "rad/s" | "Hz"; dma_terms_per_decade = 2.0)
    [surface]    kind = "self_affine" | "sinusoid" | "file" | "sphere" | "cylinder", length (m),
                 n, and per kind:
                 self_affine: hurst, scales, rms_height | rms_slope, seed, rolloff,
                              anisotropy, dim (1 or 2)
                 sinusoid:    amplitude (m), wavelength (m), dim, direction
                 file:        path (.npy/.txt/.csv, relative to the scene file), unit
                 sphere, cylinder: radius (m), exact (default false: paraboloid); an isolated
                              indenter centred in a domain of side length (2-D map / 1-D profile)
    [loading]    load (N; N/m for 1-D profiles) and speeds = [...] (m/s) or
                 xi = {start, stop, num} (log-spaced, xi = v tau / L; tau = xi_time or the
                 material's longest creep time)
    [solver]     rtol, maxiter, warm_start, periodic (default false for sphere and
                 cylinder, true otherwise), method ("auto"; isolated: "uniform" | "adaptive")
    [outputs]    friction_curve, fields, plots, vtk  (booleans)
"""
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bem import Material, surfaces
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
                "rolloff", "anisotropy", "dim", "amplitude", "wavelength", "direction", "path", "unit",
                "radius", "exact"},
    "loading": {"load", "speeds", "xi", "xi_time"},
    "solver": {"rtol", "maxiter", "warm_start", "periodic", "method"},
    "outputs": {"friction_curve", "fields", "plots", "vtk", "anisotropy", "contact_psd"},
}
SURFACE_KINDS = ("self_affine", "sinusoid", "file", "sphere", "cylinder")
INDENTER_KINDS = ("sphere", "cylinder")  # isolated indenters: periodic = false by default
SCENE_DIR = Path(__file__).with_name("scenes")
DEFAULT_SCENE = SCENE_DIR / "seed.toml"


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
    periodic: bool = True
    method: str = "auto"
    outputs: dict = field(default_factory=dict)
    source: str = ""
    raw: dict = field(default_factory=dict, repr=False)


def _check_keys(table, section):
    valid = SCHEMA[section]
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
        raise InputError(f"[surface] kind must be one of {', '.join(SURFACE_KINDS)}, got {kind!r}")
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
    if kind in INDENTER_KINDS:
        if "radius" not in t:
            raise InputError(f"[surface] radius (m) is required for kind = {kind!r}")
        make = surfaces.sphere if kind == "sphere" else surfaces.cylinder
        return make(radius=t["radius"], n=t["n"], length=t["length"], exact=t.get("exact", False))
    if "path" not in t:
        raise InputError("[surface] path is required for kind = 'file'")
    return surfaces.load(base / t["path"], t["length"], unit=t.get("unit", "m"))


def _speeds(t, material, surface):
    _check_keys(t, "loading")
    if "load" not in t:
        raise InputError("[loading] load is required (N for 2-D surfaces, N/m for 1-D profiles)")
    if material.is_elastic:
        tau = float(t.get("xi_time", 1.0))
    else:
        tau = float(t.get("xi_time", material.creep_times.max()))
    if ("speeds" in t) == ("xi" in t):
        raise InputError("[loading] give exactly one of speeds = [...] (m/s) or xi = {start, stop, num}")
    if "speeds" in t:
        speeds = np.atleast_1d(np.asarray(t["speeds"], dtype=float))
        return speeds, speeds * tau / surface.length, tau
    xi = t["xi"]
    if not isinstance(xi, dict) or set(xi) != {"start", "stop", "num"}:
        raise InputError("[loading] xi must be a table {start, stop, num} (log-spaced)")
    if not (xi["start"] > 0 and xi["stop"] >= xi["start"] and int(xi["num"]) >= 1):
        raise InputError(f"[loading] xi needs 0 < start <= stop and num >= 1, got {xi}")
    values = np.logspace(np.log10(xi["start"]), np.log10(xi["stop"]), int(xi["num"]))
    return values * surface.length / tau, values, tau


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
    speeds, xi, tau = _speeds(raw["loading"], material, surface)
    solver = raw.get("solver", {})
    _check_keys(solver, "solver")
    periodic = solver.get("periodic", raw["surface"].get("kind") not in INDENTER_KINDS)
    if not isinstance(periodic, bool):
        raise InputError(f"[solver] periodic must be true or false, got {periodic!r}")
    method = solver.get("method", "auto")
    valid = ("auto", "active-set") if periodic else ("auto", "uniform", "adaptive")
    if method not in valid:
        raise InputError(f"[solver] method must be one of {', '.join(map(repr, valid))} with periodic = "
                         f"{str(periodic).lower()}, got {method!r}")
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
                 load=float(raw["loading"]["load"]), speeds=speeds, xi=xi, xi_time=tau,
                 rtol=float(solver.get("rtol", 1e-8)), maxiter=int(solver.get("maxiter", 400)),
                 warm_start=bool(solver.get("warm_start", True)), periodic=periodic, method=method,
                 outputs=outputs, source=source, raw=raw)


def load(path=None):
    """Read a scene file (the built-in seed study when ``path`` is None); a bare name such as
    ``"sphere"`` that is not a file selects the built-in scene ``scenes/<name>.toml``."""
    path = Path(path) if path is not None else DEFAULT_SCENE
    if not path.exists() and path.suffix == "" and (SCENE_DIR / f"{path.name}.toml").exists():
        path = SCENE_DIR / f"{path.name}.toml"
    try:
        text = path.read_text()
    except OSError as err:
        raise InputError(f"scene: cannot read {str(path)!r}: {err.strerror}") from None
    return parse(text, base=path.parent, source=str(path))
