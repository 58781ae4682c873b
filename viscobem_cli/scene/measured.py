"""Scene kind ``measured``: a measured topography file on the solver grid.

``[surface]`` keys (SI lengths; the file's own units are read from it)::

    kind = "measured"
    path = "scan.x3p"          # any format SurfaceTopography reads (relative to the scene file)
    n = 128                    # solver grid points per side
    detrend = "plane"          # "none" | "mean" | "plane" | "curvature"
    boundary = "isolated"      # "isolated" (the measured patch) | "periodic"
    window = "tukey"           # periodic only: "tukey" | "hann" | "mirror" | "none"
    alpha = 0.25               # tukey only: tapered fraction of each side
    unit = "um"                # only if the file has no unit: unit of heights and sizes
    scan_size = [50, 40]       # only if the file has no size: extent along x, y in `unit`
    channel = 0                # height channel of a multi-channel file

``[solver] periodic`` follows ``boundary`` (a contradicting value is an error).
``results.json["measured"]`` records the boundary, window, patch and cell sides, the file's
format and units, and the PSD report (the measurement's radially averaged PSD beside the
grid's wavevector range, rms heights and slopes, variance lost above the grid's Nyquist);
with plots on, ``measured_psd.png`` shows it.
"""

from bem.errors import InputError
from bem.surfaces import measured

__all__ = ["KEYS", "periodic", "surface"]

KEYS = {"path", "n", "detrend", "boundary", "window", "alpha", "unit", "scan_size", "channel"}


def surface(t, base):
    """The solver surface of a ``kind = "measured"`` table (with its PSD report in metadata)."""
    extra = sorted(set(t) - KEYS - {"kind"})
    if extra:
        raise InputError(
            f"[surface] key(s) {', '.join(map(repr, extra))} do not apply to kind = 'measured'; "
            f"its keys: {', '.join(sorted(KEYS))}"
        )
    for key in ("path", "n"):
        if key not in t:
            raise InputError(f"[surface] {key} is required for kind = 'measured'")
    if not isinstance(t["path"], str):
        raise InputError(f"[surface] path must be a file path (string), got {t['path']!r}")
    size = t.get("scan_size")
    if size is not None and not (isinstance(size, list) and all(isinstance(v, (int, float)) for v in size)):
        raise InputError(f"[surface] scan_size must be a list of sizes (in unit) per axis, got {size!r}")
    m = measured.read_topography(base / t["path"], unit=t.get("unit"), physical_sizes=size, channel=t.get("channel", 0))
    m = measured.detrend(m, t.get("detrend", "plane"))
    s = measured.to_surface(
        m, t["n"], boundary=t.get("boundary", "isolated"), window=t.get("window", "tukey"), alpha=t.get("alpha", 0.25)
    )
    meta = dict(s.metadata)
    meta["measured"] = {**dict(s.metadata["measured"]), "psd": measured.psd_report(m, s)}
    return type(s)(s.heights, s.length, name=s.name, centered=s.centered, metadata=meta)


def periodic(t, solver):
    """``[solver] periodic`` of a measured scene: the boundary's choice."""
    want = t.get("boundary", "isolated") == "periodic"
    given = solver.get("periodic", want)
    if given != want:
        raise InputError(
            f"[solver] periodic = {str(given).lower()} contradicts [surface] boundary = "
            f"{t.get('boundary', 'isolated')!r}; leave periodic out"
        )
    return want
