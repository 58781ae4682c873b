"""Every scene key: section, name, type, unit, default, valid range and meaning.

:data:`KEYS` is the single table of the scene format. The parser rejects a key that is
not in it (listing the valid ones), and the documentation's scenes reference is generated
from it. To add a key, append a :class:`Key` to :data:`KEYS` (in the module that parses
it, ``KEYS.append(Key(...))`` at import time works too) and read it in the parser.

``default`` is the value used when the key is absent (``None``: no default, see ``help``);
``valid`` is a human-readable range or list of choices.
"""

from dataclasses import dataclass

from bem.contact.options import MAXITER, RTOL

__all__ = ["Key", "KEYS", "SECTIONS", "default", "keys_of", "names_of"]


@dataclass(frozen=True)
class Key:
    """One scene key (a row of the scenes reference)."""

    section: str  # "" for top-level keys
    name: str
    type: str  # "number", "integer", "boolean", "string", "list", "table", "number or list"
    unit: str  # SI unit, "" for dimensionless
    default: object
    valid: str
    help: str


SECTIONS = ("material", "surface", "loading", "solver", "outputs", "analysis")

KEYS = [
    Key("", "title", "string", "", "the file name", "any text", "Title of the study (plots, results.json)."),
    # [material]: nu and one of E | E0, E_inf, creep_time | relaxation_time | E0, moduli, times |
    # E0, compliances, times | dma
    Key("material", "nu", "number", "", 0.5, "(-1, 0.5]", "Poisson's ratio."),
    Key("material", "E", "number", "Pa", None, "> 0", "Young's modulus of an elastic solid."),
    Key("material", "E0", "number", "Pa", None, "> 0", "Relaxed (long-time, low-frequency) modulus."),
    Key(
        "material",
        "E_inf",
        "number",
        "Pa",
        None,
        "> E0",
        "Glassy (short-time, high-frequency) modulus of a standard linear solid.",
    ),
    Key(
        "material",
        "creep_time",
        "number",
        "s",
        None,
        "> 0",
        "Creep (retardation) time of a standard linear solid; give this or relaxation_time.",
    ),
    Key(
        "material",
        "relaxation_time",
        "number",
        "s",
        None,
        "> 0",
        "Relaxation time of a standard linear solid; give this or creep_time.",
    ),
    Key("material", "moduli", "list", "Pa", None, "numbers > 0", "Prony series moduli E_k (with E0, times)."),
    Key(
        "material",
        "times",
        "list",
        "s",
        None,
        "numbers > 0",
        "Prony relaxation times (with moduli) or creep times (with compliances).",
    ),
    Key(
        "material",
        "compliances",
        "list",
        "1/Pa",
        None,
        "numbers > 0",
        "Creep-compliance series terms (with E0, times).",
    ),
    Key(
        "material",
        "dma",
        "string",
        "",
        None,
        "a file path",
        "DMA table (columns: frequency, storage E', loss E'', and optionally temperature) fitted by a Prony "
        "series; with a temperature column, a master curve and its shift law (see shift); relative to the "
        "scene file.",
    ),
    Key(
        "material",
        "dma_frequency_unit",
        "string",
        "",
        "rad/s",
        "rad/s | Hz",
        "Unit of the DMA frequencies (or in the header).",
    ),
    Key("material", "dma_terms_per_decade", "number", "", 3.0, "> 0", "Prony terms per decade of the DMA fit."),
    # [surface]
    Key(
        "surface",
        "kind",
        "string",
        "",
        None,
        "self_affine | sinusoid | measured | file | sphere | cylinder",
        "Rigid surface type (required): measured is a scan of part of a larger surface (any shape and format, "
        "periodic or not); file is one square periodic cell of plain heights.",
    ),
    Key(
        "surface",
        "length",
        "number",
        "m",
        None,
        "> 0",
        "Side of the periodic cell, or of the isolated indenter's domain (required; measured: from the file).",
    ),
    Key(
        "surface",
        "n",
        "integer",
        "",
        None,
        ">= 2 (measured: >= 4)",
        "Grid points per side (required except for kind = file; measured: per side of the solved patch, "
        "default its own pixels, a mirrored cell has 2 n).",
    ),
    Key("surface", "hurst", "number", "", None, "(0, 1]", "self_affine: Hurst exponent H."),
    Key(
        "surface",
        "scales",
        "integer",
        "",
        64,
        "scales * max(s, 1/s) <= n / 2",
        "self_affine: number of scales q_1 / q_L; keep n / scales >= 4 grid points per shortest wavelength.",
    ),
    Key("surface", "rms_height", "number", "m", None, "> 0", "self_affine: rms height (or rms_slope)."),
    Key("surface", "rms_slope", "number", "", None, "> 0", "self_affine: rms slope (or rms_height)."),
    Key("surface", "seed", "integer", "", 0, ">= 0", "self_affine: random seed of the first realisation."),
    Key("surface", "rolloff", "number", "", 1.0, ">= 1", "self_affine: roll-off q_r / q_L."),
    Key("surface", "anisotropy", "number", "", 1.0, "> 0", "self_affine: PSD stretch s along x."),
    Key(
        "surface",
        "dim",
        "integer",
        "",
        "2 (self_affine), 1 (sinusoid)",
        "1 | 2",
        "self_affine, sinusoid: 2-D map or 1-D profile.",
    ),
    Key(
        "surface",
        "realisations",
        "integer",
        "",
        1,
        ">= 1",
        "self_affine: K realisations (seeds seed .. seed + K - 1), reported as mean and standard error.",
    ),
    Key("surface", "amplitude", "number", "m", None, "> 0", "sinusoid: amplitude."),
    Key("surface", "wavelength", "number", "m", "length", "(0, length]", "sinusoid: wavelength."),
    Key("surface", "direction", "string", "", "x", "x | y | xy", "sinusoid: orientation of the crests' normal."),
    Key(
        "surface",
        "path",
        "string",
        "",
        None,
        "file: .npy | .txt | .csv; measured: any SurfaceTopography format",
        "file: square height map; measured: the scan (a bare matrix, .npy or text, is h[ix, iy]: one text row per "
        "x); relative to the scene file.",
    ),
    Key(
        "surface",
        "unit",
        "string",
        "",
        "file: m",
        "m | mm | um (µm, micron) | nm | pm | A",
        "file: unit of the heights; measured: unit of heights and scan_size, only if the file has none.",
    ),
    Key("surface", "radius", "number", "m", None, "> 0", "sphere, cylinder: radius (required)."),
    Key(
        "surface",
        "exact",
        "boolean",
        "",
        False,
        "true | false",
        "sphere, cylinder: the exact cap instead of the paraboloid.",
    ),
    # [loading]
    Key(
        "loading",
        "load",
        "number or list",
        "N (N/m for 1-D)",
        None,
        "> 0",
        "Normal force; a list sweeps loads (this or nominal_pressure; measured: on the scanned patch).",
    ),
    Key(
        "loading",
        "nominal_pressure",
        "number or list",
        "Pa",
        None,
        "> 0",
        "Mean pressure instead of load: the force it puts on the cell (on the scanned patch, if measured).",
    ),
    Key("loading", "speeds", "list", "m/s", None, ">= 0", "Sliding speeds (or xi)."),
    Key(
        "loading",
        "xi",
        "table or list",
        "",
        None,
        "{start, stop, num} with 0 < start <= stop, or numbers > 0",
        "Dimensionless speeds xi = v tau / l (log-spaced from a table); l is the cell length, or the relaxed "
        "Hertz contact radius a0 for sphere and cylinder.",
    ),
    Key(
        "loading", "xi_time", "number", "s", "the longest creep time (1 s if elastic)", "> 0", "tau in xi = v tau / l."
    ),
    # [solver]
    Key("solver", "rtol", "number", "", RTOL, "(0, 1)", "Tolerance of the contact solver."),
    Key("solver", "maxiter", "integer", "", MAXITER, ">= 1", "Maximum active-set iterations per point."),
    Key("solver", "warm_start", "boolean", "", True, "true | false", "Start each speed from its neighbour."),
    Key("solver", "workers", "integer", "", 1, ">= 1", "Processes solving chunks of speeds in parallel."),
    Key("solver", "chunk", "integer", "", 0, ">= 0", "Speeds per task (0: split evenly over the workers)."),
    Key(
        "solver",
        "scheduler",
        "string",
        "",
        None,
        "tcp://host:port",
        'Address of a dask.distributed scheduler (needs pip install "viscobem[dask]").',
    ),
    Key(
        "solver",
        "fold_tol",
        "number",
        "",
        1e-6,
        "[0, 1)",
        "Fold Prony terms inactive over the sweep's frequency band (0: never).",
    ),
    Key(
        "solver",
        "periodic",
        "boolean",
        "",
        "false for sphere and cylinder, else true",
        "true | false",
        "Periodic cell or isolated contact.",
    ),
    Key(
        "solver",
        "method",
        "string",
        "",
        "auto",
        "auto | active-set (periodic); auto | uniform | adaptive",
        "Solver variant.",
    ),
    Key(
        "solver",
        "error_estimate",
        "string",
        "",
        "indicators",
        "indicators | refined | none",
        "How each point's discretisation error is estimated: from the solution itself, by a solve on the "
        "grid twice as fine (the cost of that solve), or not at all.",
    ),
    # [outputs]
    Key("outputs", "friction_curve", "boolean", "", True, "true | false", "Friction and contact against xi."),
    Key("outputs", "fields", "boolean", "", True, "true | false", "fields.npz: pressure and displacement maps."),
    Key(
        "outputs",
        "fields_precision",
        "string",
        "",
        "float32",
        "float32 | float64",
        "Floating-point type of the stored fields.",
    ),
    Key("outputs", "plots", "boolean", "", True, "true | false", "PNG plots."),
    Key(
        "outputs",
        "vtk",
        "boolean",
        "",
        False,
        "true | false",
        'VTK files for ParaView (needs pip install "viscobem[vtk]").',
    ),
    Key("outputs", "anisotropy", "boolean", "", False, "true | false", "Anisotropy of the deformed surface (2-D)."),
    Key("outputs", "contact_psd", "boolean", "", False, "true | false", "PSD of the contact indicator (2-D)."),
    Key("outputs", "persson", "boolean", "", False, "true | false", "Persson's theory overlaid (2-D)."),
    # [analysis]
    Key("analysis", "contact_level", "number", "", 0.476, "(0, 1)", "C_chi / C_chi(0) of the contact-PSD contour."),
    Key("analysis", "psd_smoothing", "number", "grid modes", 1.0, "[0.25, n / 4]", "Smoothing of the contact PSD."),
    Key("analysis", "plot_xi", "number", "", "the friction peak", "> 0", "xi of the maps (nearest sweep point)."),
]

# Keys parsed by viscobem_cli.scene.temperatures (temperature and master curves), viscobem_cli.scene.directions
# (sliding direction) and viscobem_cli.scene.measured (measured topographies).
KEYS += [
    Key(
        "material",
        "dma_modulus_unit",
        "string",
        "",
        "Pa",
        "Pa | kPa | MPa | GPa",
        "Unit of the DMA moduli (or in the header).",
    ),
    Key(
        "material",
        "dma_temperature_unit",
        "string",
        "",
        "K",
        "K | C",
        "Unit of the DMA table's temperature column (4-column tables); a kelvin value below 100 K is rejected "
        "as looking like degrees Celsius.",
    ),
    Key(
        "material",
        "dma_columns",
        "table",
        "",
        "by header name, else by position",
        "{frequency, storage, loss, temperature} = a header name or a column number (1-based)",
        "Which columns of the DMA table hold what, when the header's names are not recognised.",
    ),
    Key(
        "material",
        "shift",
        "table",
        "",
        None,
        '{law = "wlf", C1, C2, reference_temperature} | {law = "arrhenius", activation_energy, reference_temperature}',
        "Time-temperature shift law (K, J/mol). With a temperature column in the DMA table: all its constants "
        "impose it, only law and reference_temperature fit it jointly with the Prony series.",
    ),
    Key(
        "loading",
        "temperatures",
        "list",
        "K",
        None,
        "numbers >= 100 (kelvin); needs [material] shift",
        "One speed sweep per temperature.",
    ),
    Key(
        "loading",
        "superposition",
        "boolean",
        "",
        False,
        "true | false; needs temperatures and speeds > 0",
        "Make the temperature study from one friction curve on the reference material over the reduced speeds "
        "v a_T (time-temperature superposition, bem.friction_map) instead of one sweep per temperature.",
    ),
    Key(
        "loading",
        "direction_deg",
        "number or list",
        "degree",
        0.0,
        "finite; 1-D profiles 0 or 180; a list sweeps directions",
        "Sliding direction from +x toward +y.",
    ),
    Key(
        "surface",
        "detrend",
        "string",
        "",
        "plane",
        "plane | none | mean | curvature",
        "measured: polynomial removed from the solved patch (the same default as bem.surfaces.from_scan).",
    ),
    Key(
        "surface",
        "boundary",
        "string",
        "",
        "periodic",
        "periodic | isolated",
        "measured: the patch as a periodic cell (a patch of a larger surface) or as the whole loaded domain of an "
        "isolated contact (a scan of a whole finite body; warned about otherwise).",
    ),
    Key(
        "surface",
        "window",
        "string",
        "",
        "mirror (none for a scan the file declares periodic)",
        "mirror | periodic_component | tukey | hann | none",
        "measured, periodic: how the patch is made periodic; mirror tiles it with its mirror images (a cell of "
        "twice its side holding it 4 times, with 4 times the load: the same pressure).",
    ),
    Key("surface", "alpha", "number", "", 0.25, "[0, 1]", "measured, tukey window: tapered fraction of each side."),
    Key(
        "surface",
        "scan_size",
        "list",
        "unit",
        None,
        "sizes > 0 per axis",
        "measured: extent along x, y, only if the file has no size.",
    ),
    Key("surface", "channel", "integer", "", 0, ">= 0", "measured: height channel of a multi-channel file."),
    Key(
        "surface",
        "transpose",
        "boolean",
        "",
        False,
        "true | false",
        "measured: swap the file's axes and sizes (for a matrix whose rows run along y, as an image).",
    ),
    Key(
        "surface",
        "patch",
        "string or list",
        "m",
        "centre",
        "centre | cover | [x0, y0] | [x0, y0, side]",
        "measured: the square of the scan that is solved (cells are square): the largest centred one (warned about "
        "when it is not the whole scan), every square covering the scan (one realisation each), or one from an "
        "origin.",
    ),
]


def keys_of(section):
    """The :class:`Key` rows of ``section`` ("" for top-level keys), in table order."""
    return [k for k in KEYS if k.section == section]


def names_of(section):
    """The valid key names of ``section``; the top level also lists the sections."""
    names = {k.name for k in keys_of(section)}
    return names | set(SECTIONS) if section == "" else names


def default(section, name):
    """The default of the key ``name`` of ``section`` (the one source the parser reads)."""
    for k in keys_of(section):
        if k.name == name:
            return k.default
    raise KeyError(f"[{section}] {name} is not a scene key")
