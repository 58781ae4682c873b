"""The PSD of a measured topography against what the solver grid keeps."""

from .style import pyplot, save


def psd_plot(rec, path):
    """The measurement's PSD with the grid's wavevector range marked."""
    psd = rec["psd"]
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 4.2), constrained_layout=True)
    ax.loglog(psd["q"], psd["C"], "o-", ms=3, label="scan (radial average, Hann window)")
    ax.axvline(psd["q_grid_min"], color="C1", ls="--", label="grid: 2 pi / cell side")
    ax.axvline(psd["q_grid_max"], color="C3", ls="--", label="grid cut-off: pi n / cell side")
    ax.axvline(psd["q_measurement_max"], color="0.5", ls=":", label="scan Nyquist")
    ax.set_xlabel("q (rad/m)")
    ax.set_ylabel("C(q) (m^4)" if len(rec["pixel_sizes"]) == 2 else "C(q) (m^3)")
    lost = psd["variance_above_grid_nyquist"]
    ax.set_title(
        f"{rec['boundary']}"
        + (f", window {rec.get('window')}" if rec["boundary"] == "periodic" else "")
        + f", detrend {rec['detrend']}, patch {100 * rec['patch']['fraction_of_scan']:.3g} % of the scan"
        + f"\nrms slope {psd['rms_slope_measurement']:.3g} patch, {psd['rms_slope_grid']:.3g} grid; "
        f"{100 * lost:.2g} % of the patch's variance above the cut-off",
        fontsize=8,
    )
    ax.legend(fontsize=7)
    save(fig, path)
