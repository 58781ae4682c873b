"""Scene kind ``measured``: a scan of part of a larger surface (any instrument format, any shape,
periodic or not) on the solver grid, through :func:`bem.surfaces.from_scan` with its defaults.

``[surface]`` keys (SI lengths; the file's own units are read from it)::

    kind = "measured"
    path = "scan.x3p"          # any format SurfaceTopography reads (relative to the scene file)
    n = 128                    # grid points per side of the solved patch (default: its own pixels)
    detrend = "plane"          # "plane" | "none" | "mean" | "curvature"
    boundary = "periodic"      # "periodic" | "isolated" (a scan of a whole finite body)
    window = "mirror"          # periodic only: "mirror" | "periodic_component" | "tukey" | "hann" | "none"
                               # (default "none" for a scan the file declares periodic)
    alpha = 0.25               # tukey only: tapered fraction of each side
    patch = "centre"           # "centre" | "cover" (every square of the scan) | [x0, y0] | [x0, y0, side] (m)
    unit = "um"                # only if the file has no unit: unit of heights and sizes
    scan_size = [50, 40]       # only if the file has no size: extent along x, y in `unit`
    channel = 0                # height channel of a multi-channel file
    transpose = false          # swap the file's axes: for a matrix whose rows run along y

``[loading] load`` is the force on the solved patch (N; N/m for a line scan), as in
:func:`bem.solve`: a mirrored cell holds the patch four times (twice for a line) and gets that
many times the load (same nominal pressure); ``results.json["loads"]`` are the patch's, as asked,
and ``results.json["measured"]`` gives ``load_factor``, ``patch_loads`` and ``cell_loads``. ``[solver] periodic`` follows ``boundary`` (a
contradicting value is an error). With ``patch = "cover"`` each square of the scan is one
realisation: every number is reported as their mean with a standard error, and
``results.json["measured"]["patches"]`` lists them. ``results.json["measured"]`` records the
boundary, window, detrending, the patch (origin, side, fraction of the scan), the file's format
and units, and the PSD report (the scan's radially averaged PSD beside the grid's wavevector
range, rms heights and slopes, variance lost above the grid's Nyquist); with plots on,
``measured_psd.png`` shows it. Warnings (a cropped scan, a boundary measured to misrepresent a
patch) go to the console and ``results.json["warnings"]``.
"""

import warnings

from bem.errors import InputError
from bem.surfaces import measured

__all__ = ["KEYS", "periodic", "surfaces", "warnings_of"]

KEYS = {"path", "n", "detrend", "boundary", "window", "alpha", "patch", "unit", "scan_size", "channel", "transpose"}


def _check(t):
    extra = sorted(set(t) - KEYS - {"kind"})
    if extra:
        raise InputError(
            f"[surface] key(s) {', '.join(map(repr, extra))} do not apply to kind = 'measured'; "
            f"its keys: {', '.join(sorted(KEYS))}"
        )
    if "path" not in t:
        raise InputError("[surface] path is required for kind = 'measured'")
    if not isinstance(t["path"], str):
        raise InputError(f"[surface] path must be a file path (string), got {t['path']!r}")
    size = t.get("scan_size")
    if size is not None and not (isinstance(size, list) and all(isinstance(v, (int, float)) for v in size)):
        raise InputError(f"[surface] scan_size must be a list of sizes (in unit) per axis, got {size!r}")
    patch = t.get("patch", "centre")
    if not (patch in ("centre", "cover") or isinstance(patch, list)):
        raise InputError(f"[surface] patch must be 'centre', 'cover', [x0, y0] or [x0, y0, side] (m), got {patch!r}")


def surfaces(t, base):
    """The solver surfaces of a ``kind = "measured"`` table: one, or one per square of the scan
    with ``patch = "cover"``; each with its PSD report in ``metadata["measured"]["psd"]``."""
    _check(t)
    with warnings.catch_warnings():  # the reader's warnings travel in the record (Scene.warnings)
        warnings.simplefilter("ignore", UserWarning)
        m = measured.read_topography(
            base / t["path"],
            unit=t.get("unit"),
            physical_sizes=t.get("scan_size"),
            channel=t.get("channel", 0),
            transpose=t.get("transpose", False),
        )
    patch = t.get("patch", "centre")
    patches = measured.cover(m) if patch == "cover" else [tuple(patch) if isinstance(patch, list) else patch]
    detrend = t.get("detrend", "plane")
    whole = measured.detrend(m, detrend)
    out = []
    for p in patches:
        with warnings.catch_warnings():  # the scene reports them (metadata -> Scene.warnings)
            warnings.simplefilter("ignore", UserWarning)
            s = measured.from_scan(
                m,
                t.get("n"),
                detrend=detrend,
                boundary=t.get("boundary", "periodic"),
                window=t.get("window"),
                alpha=t.get("alpha", 0.25),
                patch=p,
            )
        meta = dict(s.metadata)
        meta["measured"] = {**dict(s.metadata["measured"]), "psd": measured.psd_report(whole, s)}
        out.append(type(s)(s.heights, s.length, name=s.name, centered=s.centered, metadata=meta))
    return tuple(out)


def warnings_of(surfaces):
    """The surfaces' warnings, each once (the squares of a cover share theirs)."""
    return list(dict.fromkeys(w for s in surfaces for w in s.metadata["measured"]["warnings"]))


def periodic(t, solver):
    """``[solver] periodic`` of a measured scene: the boundary's choice."""
    boundary = t.get("boundary", "periodic")
    want = boundary == "periodic"
    given = solver.get("periodic", want)
    if given != want:
        raise InputError(
            f"[solver] periodic = {str(given).lower()} contradicts [surface] boundary = {boundary!r}; leave periodic out"
        )
    return want
