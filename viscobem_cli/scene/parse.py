"""Scenes: one study described in a TOML file, parsed into validated objects.

Every key with its type, unit, default, valid range and meaning is in the table
:data:`viscobem_cli.scene.schema.KEYS` (the documentation's scenes reference is generated from it).
In short (SI units; unknown keys are an error that lists the valid ones)::

    title = "..."                      # optional
    [material]   nu = 0.5 and one of:  E  |  E0, E_inf, creep_time | relaxation_time
                 |  E0, moduli, times (Prony)  |  E0, compliances, times (creep)
                 |  dma = "file.csv" (columns: frequency, storage E', loss E'' [, temperature];
                    dma_frequency_unit = "rad/s" | "Hz"; dma_modulus_unit = "Pa" | "kPa" | "MPa" | "GPa";
                    dma_temperature_unit = "K" | "C"; dma_terms_per_decade = 3.0; columns named in a
                    header row or by dma_columns: viscobem_cli.scene.dma)
                 shift = { law = "wlf", C1, C2, reference_temperature (K) } | { law = "arrhenius",
                    activation_energy (J/mol), reference_temperature (K) }  (see viscobem_cli.scene.temperatures)
    [surface]    kind = "self_affine" | "sinusoid" | "measured" | "file" | "sphere" | "cylinder", length (m),
                 n, and per kind:
                 self_affine: hurst, scales, rms_height | rms_slope, seed, rolloff,
                              anisotropy, dim (1 or 2), realisations (K: seeds seed..seed+K-1)
                 sinusoid:    amplitude (m), wavelength (m), dim, direction
                 file:        one square periodic cell of plain heights: path (.npy/.txt/.csv, one
                              row per x, relative to the scene file), unit
                 sphere, cylinder: radius (m), exact (default false: paraboloid); an isolated
                              indenter centred in a domain of side length (2-D map / 1-D profile)
                 measured:    a scan of part of a larger surface, any shape and format, periodic or
                              not: path, n, detrend, boundary, window, alpha, patch, unit,
                              scan_size, channel (viscobem_cli.scene.measured)
    [loading]    load (N; N/m for 1-D profiles; a number or a list to sweep) and speeds = [...] (m/s) or
                 xi = {start, stop, num} (log-spaced) or a list (xi = v tau / L; tau = xi_time or the
                 material's longest creep time); temperatures = [...] (K; needs a shift law);
                 direction_deg (sliding direction from +x toward +y, degrees; a list sweeps it:
                 viscobem_cli.scene.directions)
    [solver]     rtol, maxiter, warm_start, workers (processes, default 1), chunk (speeds per
                 task), scheduler ("tcp://host:port" of a dask.distributed cluster), fold_tol,
                 periodic (default false for sphere and cylinder, true otherwise),
                 method ("auto"; periodic: "active-set"; isolated: "uniform" | "adaptive")
    [outputs]    friction_curve, fields, plots, vtk, anisotropy, contact_psd, persson (booleans)
    [analysis]   contact_level (C_chi/C_chi(0) of the contour, 0.476), psd_smoothing (modes, 1.0),
                 plot_xi (xi of the maps, polar and PSD plots; default: the friction peak)
"""

import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bem import Material, surfaces
from bem.contact.options import MAXITER, RTOL
from bem.errors import InputError

from .. import guidance
from ..catalog import SCENE_DIR, builtin_scenes, scene_path
from . import temperatures
from . import values as scene_values

__all__ = [
    "Scene",
    "parse",
    "load",
    "describe_xi",
    "builtin_scenes",
    "SCENE_DIR",
    "DEFAULT_SCENE",
    "SCHEMA",
    "SURFACE_KINDS",
    "INDENTER_KINDS",
]

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

# valid key names per section ("" = top level); each has a documented row in viscobem_cli.scene.schema.KEYS
SCHEMA = {
    "": {"title", "material", "surface", "loading", "solver", "outputs", "analysis"},
    "material": {
        "nu",
        "E",
        "E0",
        "E_inf",
        "creep_time",
        "relaxation_time",
        "moduli",
        "times",
        "compliances",
        "dma",
        "dma_frequency_unit",
        "dma_terms_per_decade",
        "dma_modulus_unit",
        "dma_temperature_unit",
        "dma_columns",
        "shift",
    },
    "surface": {
        "kind",
        "length",
        "n",
        "hurst",
        "scales",
        "rms_height",
        "rms_slope",
        "seed",
        "rolloff",
        "anisotropy",
        "dim",
        "amplitude",
        "wavelength",
        "direction",
        "path",
        "unit",
        "realisations",
        "radius",
        "exact",
        "detrend",
        "boundary",
        "window",
        "alpha",
        "scan_size",
        "channel",
        "transpose",
        "patch",
    },  # kind = "measured"
    "loading": {
        "load",
        "nominal_pressure",
        "speeds",
        "xi",
        "xi_time",
        "temperatures",
        "superposition",
        "direction_deg",
    },
    "solver": {
        "rtol",
        "maxiter",
        "warm_start",
        "workers",
        "chunk",
        "scheduler",
        "fold_tol",
        "periodic",
        "method",
        "error_estimate",
    },
    "outputs": {"friction_curve", "fields", "plots", "vtk", "anisotropy", "contact_psd", "persson", "fields_precision"},
    "analysis": {"contact_level", "psd_smoothing", "plot_xi"},
}
SURFACE_KINDS = ("self_affine", "sinusoid", "file", "sphere", "cylinder", "measured")
INDENTER_KINDS = ("sphere", "cylinder")  # isolated indenters: periodic = false by default
DEFAULT_SCENE = scene_path(None)
MIN_POINTS_PER_WAVELENGTH = 4  # fewer: the two friction forms drift apart (a warning)


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
    rtol: float = RTOL
    maxiter: int = MAXITER
    warm_start: bool = True
    periodic: bool = True
    method: str = "auto"
    error_estimate: str = "indicators"  # or "refined", or None (bem.solve's error_estimate)
    outputs: dict = field(default_factory=dict)
    source: str = ""
    raw: dict = field(default_factory=dict, repr=False)
    realisations: tuple = ()
    loads: tuple = ()
    workers: int = 1
    chunk: int = 0
    scheduler: str = None
    fold_tol: float = 1e-6
    contact_level: float = 0.476
    psd_smoothing: float = 1.0
    plot_xi: float = None
    xi_length: float = None  # l in xi = v tau / l (m): the cell length, or a0 for an indenter
    xi_time_source: str = ""
    warnings: tuple = ()  # texts that explain a doubtful setting and what to change
    fields_precision: str = "float32"
    shift: object = None  # time-temperature shift law (bem.materials.temperature), or None
    temperatures: tuple = ()  # K; a sweep per temperature when given
    superposition: bool = False  # the temperatures from one curve over the reduced speeds (bem.friction_map)
    dma: dict = field(default=None, repr=False)  # the DMA table in SI (viscobem_cli.scene.temperatures.read_dma)
    directions: tuple = (0.0,)  # sliding directions (radians), see viscobem_cli.scene.directions

    @property
    def kind(self):
        """The surface kind ("self_affine", "sphere", ...)."""
        return self.raw.get("surface", {}).get("kind", "")

    @property
    def direction(self):
        """The sliding direction of a single-direction study (radians)."""
        return self.directions[0]

    def __post_init__(self):
        if not self.realisations:
            object.__setattr__(self, "realisations", (self.surface,))
        if not self.loads:
            object.__setattr__(self, "loads", (self.load,))

    @property
    def seeds(self):
        """Seed of each realisation (None for surfaces that are not random)."""
        return tuple(s.metadata.get("seed") for s in self.realisations)


def _check_keys(table, section):
    valid = SCHEMA[section]
    if not isinstance(table, dict):
        raise InputError(f"[{section}] must be a table of keys ({', '.join(sorted(valid))}), got {table!r}")
    unknown = sorted(set(table) - valid)
    if unknown:
        where = f"[{section}]" if section else "the top level"
        raise InputError(
            f"unknown key(s) {', '.join(map(repr, unknown))} in {where} of the scene; "
            f"valid keys: {', '.join(sorted(valid))}"
        )


def _material(t, base):
    _check_keys(t, "material")
    nu = t.get("nu", 0.5)
    markers = {"E": "E", "E_inf": "sls", "moduli": "prony", "compliances": "creep", "dma": "dma"}
    present = [kind for key, kind in markers.items() if key in t]
    if len(present) != 1:
        raise InputError(
            "[material] needs exactly one of: E | E0, E_inf, creep_time or relaxation_time "
            "| E0, moduli, times | E0, compliances, times | dma (file); got keys "
            f"{sorted(t)}"
        )
    kind = present[0]
    if kind in ("sls", "prony", "creep") and "E0" not in t:
        raise InputError(f"[material] E0 (relaxed modulus, Pa) is required with {sorted(t)}")
    if kind == "E":
        return Material.elastic(t["E"], nu=nu)
    if kind == "sls":
        return Material.standard_linear_solid(
            E0=t["E0"],
            E_inf=t["E_inf"],
            creep_time=t.get("creep_time"),
            relaxation_time=t.get("relaxation_time"),
            nu=nu,
        )
    if kind == "prony":
        return Material.from_prony(E0=t["E0"], moduli=t["moduli"], times=t.get("times", []), nu=nu)
    if kind == "creep":
        return Material.from_creep(E0=t["E0"], compliances=t["compliances"], times=t.get("times", []), nu=nu)
    return temperatures.dma_material(t, base, nu)  # 3 columns: a Prony fit; 4: a master curve


def _surface(t, base):
    _check_keys(t, "surface")
    kind = t.get("kind")
    if kind not in SURFACE_KINDS:
        raise InputError(f"[surface] kind must be one of {', '.join(SURFACE_KINDS)}, got {kind!r}")
    if kind == "measured":  # a scan of part of a larger surface: viscobem_cli.scene.measured
        from . import measured

        return measured.surfaces(t, base)
    for key in ("length",) + (("n",) if kind != "file" else ()):
        if key not in t:
            raise InputError(f"[surface] {key} is required for kind = {kind!r}")
    count = t.get("realisations", 1)
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise InputError(f"[surface] realisations must be an integer >= 1, got {count!r}")
    if kind == "self_affine":
        allowed = {"hurst", "scales", "rms_height", "rms_slope", "rolloff", "anisotropy", "dim"}
        args = {k: t[k] for k in allowed if k in t}
        seed = t.get("seed", 0)
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise InputError(f"[surface] seed must be an integer >= 0, got {seed!r}")
        return tuple(surfaces.self_affine(t["n"], t["length"], seed=seed + k, **args) for k in range(count))
    if count != 1:
        raise InputError(f"[surface] realisations must be 1 for kind = {kind!r} (not random), got {count!r}")
    if kind == "sinusoid":
        args = {k: t[k] for k in ("amplitude", "wavelength", "dim", "direction") if k in t}
        return (surfaces.sinusoid(t["n"], t["length"], **args),)
    if kind in INDENTER_KINDS:
        if "radius" not in t:
            raise InputError(f"[surface] radius (m) is required for kind = {kind!r}")
        make = surfaces.sphere if kind == "sphere" else surfaces.cylinder
        return (make(radius=t["radius"], n=t["n"], length=t["length"], exact=t.get("exact", False)),)
    if not isinstance(t.get("path"), str):
        raise InputError(f"[surface] path (a file path string) is required for kind = 'file', got {t.get('path')!r}")
    return (surfaces.load(base / t["path"], t["length"], unit=t.get("unit", "m")),)


def parse(text, *, base=Path("."), source="<string>", overrides=()):
    """Parse scene TOML ``text``; relative paths resolve against ``base``.

    ``overrides``: ``"section.key=value"`` strings (``value`` in TOML syntax, e.g.
    ``"surface.n=64"``, ``"loading.xi.num=3"``) applied on top of the text, as
    ``viscobem run --set`` does.
    """
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"scene {source}: not valid TOML: {err}") from None
    for item in overrides:
        scene_values.override(raw, item)
    _check_keys(raw, "")
    for section in ("material", "surface", "loading"):
        if section not in raw:
            raise InputError(f"scene {source}: section [{section}] is required")
    material = _material(raw["material"], base)
    realisations = _surface(raw["surface"], base)
    surface = realisations[0]
    _check_keys(raw["loading"], "loading")
    loads = scene_values.loads(raw["loading"], surface)
    tau, tau_source = scene_values.xi_time(raw["loading"], material)
    kind = raw["surface"]["kind"]
    xi_length = (
        surface.length
        if kind not in INDENTER_KINDS
        else guidance.hertz_radius(
            kind, modulus=material.E0, nu=material.nu, radius=raw["surface"]["radius"], load=loads[0]
        )
    )
    speeds, xi = scene_values.speeds(raw["loading"], tau, xi_length)
    solver = raw.get("solver", {})
    _check_keys(solver, "solver")
    run = scene_values.solver(solver)
    run["periodic"] = solver.get("periodic", raw["surface"].get("kind") not in INDENTER_KINDS)
    if raw["surface"].get("kind") == "measured":  # the boundary chosen for the measured patch
        from . import measured

        run["periodic"] = measured.periodic(raw["surface"], solver)
    if not isinstance(run["periodic"], bool):
        raise InputError(f"[solver] periodic must be true or false, got {run['periodic']!r}")
    run["method"] = solver.get("method", "auto")
    valid = ("auto", "active-set") if run["periodic"] else ("auto", "uniform", "adaptive")
    if run["method"] not in valid:
        raise InputError(
            f"[solver] method must be one of {', '.join(map(repr, valid))} with periodic = "
            f"{str(run['periodic']).lower()}, got {run['method']!r}"
        )
    warnings = guidance.resolution_warnings(surface, kind, run["periodic"], MIN_POINTS_PER_WAVELENGTH)
    if kind == "measured":  # warnings on the scan's boundary and cropping
        from . import measured

        warnings += measured.warnings_of(realisations)
    analysis = raw.get("analysis", {})
    _check_keys(analysis, "analysis")
    _check_keys(raw.get("outputs", {}), "outputs")
    outputs, precision = scene_values.outputs(raw.get("outputs", {}), surface)
    level = analysis.get("contact_level", 0.476)
    if not (isinstance(level, (int, float)) and 0 < level < 1):
        raise InputError(f"[analysis] contact_level must be in (0, 1), got {level!r}")
    smoothing = analysis.get("psd_smoothing", 1.0)
    if not (isinstance(smoothing, (int, float)) and 0.25 <= smoothing <= surface.n / 4):
        raise InputError(f"[analysis] psd_smoothing must be in [0.25, n / 4] grid modes, got {smoothing!r}")
    plot_xi = analysis.get("plot_xi")
    if plot_xi is not None and not (isinstance(plot_xi, (int, float)) and plot_xi > 0):
        raise InputError(f"[analysis] plot_xi must be a number > 0, got {plot_xi!r}")
    from .directions import parse as parse_directions

    run["directions"] = parse_directions(raw["loading"], surface, run["periodic"], run["method"])
    dma = temperatures.read_dma(raw["material"], base) if "dma" in raw["material"] else None
    scene = Scene(
        title=str(raw.get("title", Path(source).stem)),
        material=material,
        surface=surface,
        load=loads[0],
        speeds=speeds,
        xi=xi,
        xi_time=tau,
        outputs=outputs,
        source=source,
        raw=raw,
        realisations=realisations,
        loads=loads,
        contact_level=float(level),
        psd_smoothing=float(smoothing),
        plot_xi=None if plot_xi is None else float(plot_xi),
        xi_length=float(xi_length),
        xi_time_source=tau_source,
        warnings=tuple(warnings) + tuple(dma["warnings"] if dma else ()),  # units a DMA table does not name
        fields_precision=precision,
        **run,
        **temperatures.scene_fields(raw, material),
        dma=dma,
    )
    return temperatures.with_material_warnings(scene)  # what the DMA data do not cover


def load(path=None, *, overrides=()):
    """Read a scene: a file, a built-in scene by name, or the default study when ``path`` is
    None; ``overrides`` as in :func:`parse`."""
    path = scene_path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise InputError(f"scene: cannot read {str(path)!r}: {err.strerror}") from None
    except UnicodeDecodeError:
        raise InputError(f"scene: cannot read {str(path)!r}: not a UTF-8 text (TOML) file") from None
    return parse(text, base=path.parent, source=str(path), overrides=overrides)


def describe_xi(scene):
    """Console lines: tau and its origin, the length in xi and the speed range (m/s)."""
    return guidance.describe_xi(scene)
