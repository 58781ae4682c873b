"""PNG plots of a study (matplotlib, Agg backend). Isolated indenters get pressure maps at
three speeds and contact outlines instead of the periodic maps.

Friction and contact area against xi (log x axis, ensemble error bars, Persson overlay),
pressure / contact / deformed-surface maps with the sliding direction (+x) marked, polar
plots of m2(theta) and the contact-PSD contour with its fitted ellipse, and the anisotropy
measures against xi. Maps are drawn at ``[analysis] plot_xi`` (nearest sweep point) or at
the friction peak.
"""

from pathlib import Path

import numpy as np

from .anisotropy import anisotropy_vs_xi, polar_m2, psd_contour
from .style import label_log_axis, nan_array, pyplot, save, sliding_arrow, sweep_axis


def friction_curve(scene, record, path):
    """Friction (both forms, mean ± standard error) against the speed, on a linear and a log axis
    (xi or v in m/s first, :func:`~.style.speed_first`); Persson's theory if computed."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.4), constrained_layout=True)
    for ax in axes:
        xi = sweep_axis(ax, scene)  # the x values: xi, or the speeds
        for k, curve in enumerate(record["curves"]):
            tag = f" ({curve['load']:g} N)" if len(record["curves"]) > 1 else ""
            mu, se = nan_array(curve["friction"]), nan_array(curve["friction_se"])
            ax.errorbar(
                xi,
                mu,
                yerr=None if np.all(np.isnan(se)) else se,
                fmt="o-",
                ms=5,
                capsize=2,
                lw=1.5,
                label=r"$\mu$, dissipation form" + tag,
                zorder=2,
            )
            if k == 0:  # drawn on top, dashed with open markers: visible where the forms coincide
                ax.plot(
                    xi,
                    nan_array(curve["friction_eq6"]),
                    "s--",
                    ms=6,
                    mfc="none",
                    mew=1.2,
                    lw=1.2,
                    color="C3",
                    label=r"$\mu$, eq. 6 ($-\int p\,\partial h/\partial x$)",
                    zorder=3,
                )
        for row in record.get("persson", []):
            ax.plot(xi, row["friction"], "k-", lw=1.2, label=f"Persson (2001), {row['pressure']:.3g} Pa")
        ax.set_ylabel("friction coefficient $\\mu$")
        ax.grid(True, which="both", alpha=0.3)
    axes[1].set_yscale("log")
    label_log_axis(axes[1].yaxis)
    axes[0].set_ylim(bottom=0)
    axes[0].legend(fontsize=8, loc="best")
    axes[1].set_title("log scale: the tails", fontsize=9)
    k = len(scene.realisations)
    import textwrap

    fig.suptitle(textwrap.fill(scene.title + (f"  ({k} realisations, mean ± s.e.)" if k > 1 else ""), 110), fontsize=9)
    save(fig, path)


def contact_area(scene, record, path):
    """True contact area against the speed (xi or v, as :func:`friction_curve`): % of the cell
    (periodic), or contact radius (mm) and a / a_Hertz (indenters); Persson's P(q1) if computed."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.4), constrained_layout=True)
    xi = sweep_axis(ax, scene)  # the x values: xi, or the speeds
    indenter = "contact_radius" in record["curves"][0]
    for curve in record["curves"]:
        key = "contact_radius" if indenter else "contact_fraction"
        scale = 1e3 if indenter else 100.0
        a, se = nan_array(curve[key]) * scale, nan_array(curve[key + "_se"]) * scale
        ax.errorbar(
            xi,
            a,
            yerr=None if np.all(np.isnan(se)) else se,
            fmt="^-",
            ms=5,
            capsize=2,
            label=f"BEM, {curve['load']:g} N",
        )
    for row in record.get("persson", []):
        ax.plot(xi, 100 * np.asarray(row["contact_fraction"], dtype=float), "k-", lw=1.2, label="Persson P(q1)")
    if indenter:
        a0 = record["surface"]["hertz_radius_relaxed"][0] * 1e3
        glassy = record["surface"]["hertz_radius_glassy"][0] * 1e3
        ax.axhline(a0, color="0.4", ls=":", lw=1, label=f"Hertz, relaxed $E_0$: $a_0$ = {a0:.3g} mm")
        ax.axhline(glassy, color="0.4", ls="--", lw=1, label=rf"Hertz, glassy $E_\infty$: {glassy:.3g} mm")
        ax.set_ylabel("contact radius a (mm)")
        right = ax.secondary_yaxis("right", functions=(lambda y: y / a0, lambda r: r * a0))
        right.set_ylabel(r"$a / a_\mathrm{Hertz}$ (relaxed)")
    else:
        ax.set_ylabel("true contact area (% of the nominal area)")
        ax.set_ylim(bottom=0)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, path)


def field_map(surface, field, xi, path, *, label, cmap, title, scale=1.0, discrete=None, direction=0.0):
    """A 2-D map (profile for 1-D) with the sliding direction marked; ``discrete``: tick
    labels of a map of integer classes (e.g. ``["no contact", "contact"]``)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.6, 4.6), constrained_layout=True)
    x = surface.x * 1e3
    if surface.ndim == 1:
        ax.plot(x, field * scale)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel(label)
    else:
        ext = [0, surface.length * 1e3, 0, surface.length * 1e3]
        norm = None
        if discrete is not None:
            from matplotlib.colors import BoundaryNorm, ListedColormap

            cmap = (
                ListedColormap(["white", "black"]) if len(discrete) == 2 else pyplot().get_cmap("tab10", len(discrete))
            )
            norm = BoundaryNorm(np.arange(len(discrete) + 1) - 0.5, len(discrete))
        im = ax.imshow(
            np.asarray(field).T * scale, origin="lower", extent=ext, cmap=cmap, norm=norm, interpolation="nearest"
        )
        bar = fig.colorbar(im, ax=ax, label=label, ticks=None if discrete is None else range(len(discrete)))
        if discrete is not None:
            bar.ax.set_yticklabels(discrete)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        sliding_arrow(ax, direction)
    ax.set_title(rf"$\xi$ = {xi:.3g}: {title}", fontsize=9, pad=18)
    save(fig, path)


def deformed_surface(surface, f, xi, path, *, periodic=True, direction=0.0):
    """The deformed interface: the separation between the rigid surface and the deformed
    solid (map), and a profile along x through the row with most contact showing both
    surfaces (elevation toward the rigid body, µm)."""
    plt = pyplot()
    rigid = -(surface.heights - surface.heights.max() + f.approach) * 1e6  # heights point into the solid
    solid = -np.asarray(f.displacement) * 1e6  # displacement is positive into the solid
    gap = np.maximum(rigid - solid, 0.0)
    x = surface.x * 1e3
    if surface.ndim == 2:
        row = int(np.argmax(np.count_nonzero(np.asarray(f.pressure) > 0, axis=0)))
        fig, (top, bottom) = plt.subplots(
            2, 1, figsize=(6.4, 8.0), constrained_layout=True, gridspec_kw={"height_ratios": [1.4, 1]}
        )
        ext = [0, surface.length * 1e3, 0, surface.length * 1e3]
        im = top.imshow(gap.T, origin="lower", extent=ext, cmap="viridis", interpolation="nearest")
        fig.colorbar(im, ax=top, label="separation (µm); 0 in contact")
        top.axhline(surface.x[row] * 1e3, color="w", lw=0.8, ls="--")
        top.set_xlabel("x (mm)")
        top.set_ylabel("y (mm)")
        top.set_title(rf"$\xi$ = {xi:.3g}: gap between the rigid surface and the deformed solid", fontsize=9, pad=18)
        sliding_arrow(top, direction)
        touch = np.asarray(f.pressure)[:, row] > 0
        rigid, solid, where = rigid[:, row], solid[:, row], f" at y = {surface.x[row] * 1e3:.3g} mm (dashed)"
    else:
        fig, bottom = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
        touch, where = np.asarray(f.pressure) > 0, rf" at $\xi$ = {xi:.3g}"
    bottom.plot(x, rigid, "k-", lw=1.0, label="rigid surface")
    bottom.plot(x, solid, "C0-", lw=1.2, label="deformed solid surface")
    low = min(rigid.min(), solid.min())
    bottom.fill_between(x, low, solid, where=touch, color="C3", alpha=0.5, step="mid", label="contact")
    bottom.set_xlabel("x (mm), sliding toward +x")
    bottom.set_ylabel("elevation (µm; " + ("mean plane of the solid" if periodic else "solid far away") + " at 0)")
    bottom.set_title(f"profile{where}", fontsize=9)
    bottom.legend(fontsize=8, loc="lower right")
    bottom.grid(True, alpha=0.3)
    save(fig, path)


def plot_index(scene, record):
    """Speed index of the maps: nearest to ``plot_xi``, else the friction peak."""
    mu = nan_array(record["friction_curve"]["friction"])
    if np.all(np.isnan(mu)):
        return None, None
    peak = int(np.nanargmax(mu))
    if scene.plot_xi is None:
        return peak, peak
    return int(np.argmin(np.abs(np.log(scene.xi / scene.plot_xi)))), peak


def _three_speeds(scene, fields):
    """Indices of the slowest point, the friction peak and the fastest point (distinct, sorted)."""
    keys = sorted(fields, key=lambda k: scene.speeds[k])
    peak = max(fields, key=lambda k: fields[k].friction)
    return sorted({keys[0], peak, keys[-1]}, key=lambda k: scene.speeds[k])


def indenter_maps(scene, fields, out):
    """Isolated indenter: pressure at three speeds (slowest, friction peak, fastest) and the
    contact outlines of every computed speed. Returns the file names written."""
    plt = pyplot()
    surface = scene.surface
    x = surface.x * 1e3
    picks = _three_speeds(scene, fields)
    if surface.ndim == 1:
        fig, ax = plt.subplots(figsize=(6.4, 4.2), constrained_layout=True)
        for k in picks:
            r = fields[k]
            ax.plot(x, r.pressure / 1e6, label=rf"$\xi$ = {scene.xi[k]:.3g}, $\mu$ = {r.friction:.3g}")
        ax.set_xlabel("x (mm), sliding toward +x")
        ax.set_ylabel("pressure (MPa)")
        ax.legend(fontsize=8)
        ax.set_title(scene.title, fontsize=9)
        save(fig, out / "pressure_profiles.png")
        return ["pressure_profiles.png"]
    ext = [x[0] - surface.spacing * 5e2, x[-1] + surface.spacing * 5e2] * 2
    fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 4.0), constrained_layout=True, squeeze=False)
    for ax, k in zip(axes[0], picks):
        r = fields[k]
        im = ax.imshow(r.pressure.T / 1e6, origin="lower", extent=ext, cmap="magma", interpolation="nearest")
        ax.contour(x, x, (r.pressure > 0).T.astype(float), levels=[0.5], colors="c", linewidths=0.8)
        fig.colorbar(im, ax=ax, label="pressure (MPa)", shrink=0.8)
        ax.set_xlabel("x (mm), sliding toward +x")
        ax.set_ylabel("y (mm)")
        ax.set_title(rf"$\xi$ = {scene.xi[k]:.3g}: $\mu$ = {r.friction:.3g}", fontsize=9)
    save(fig, out / "pressure_maps.png")
    fig, ax = plt.subplots(figsize=(5.2, 4.6), constrained_layout=True)
    keys = sorted(fields, key=lambda k: scene.speeds[k])
    colours = plt.cm.viridis(np.linspace(0, 1, len(keys)))
    for c, k in zip(colours, keys):
        ax.contour(x, x, (fields[k].pressure > 0).T.astype(float), levels=[0.5], colors=[c], linewidths=1.0)
    sm = plt.cm.ScalarMappable(
        cmap="viridis",
        norm=plt.matplotlib.colors.LogNorm(
            vmin=scene.xi[keys[0]], vmax=max(scene.xi[keys[-1]], scene.xi[keys[0]] * 1.0001)
        ),
    )
    fig.colorbar(sm, ax=ax, label=r"$\xi = v\,\tau / L$")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm), sliding toward +x")
    ax.set_ylabel("y (mm)")
    ax.set_title("contact outlines", fontsize=9)
    save(fig, out / "contact_outlines.png")
    return ["pressure_maps.png", "contact_outlines.png"]


def write_all(scene, record, fields, extras, out):
    """Write the plots of a study; return the file names."""
    out = Path(out)
    names = []
    i, peak = plot_index(scene, record)
    if i is None:
        return names
    if scene.outputs["friction_curve"]:
        friction_curve(scene, record, out / "friction_curve.png")
        contact_area(scene, record, out / "contact_area.png")
        names += ["friction_curve.png", "contact_area.png"]
    if fields and not scene.periodic:
        names += indenter_maps(scene, fields, out)
    elif fields:
        j = i if i in fields else min(fields, key=lambda k: abs(k - i))
        f, x = fields[j], scene.xi[j]
        field_map(
            scene.surface,
            f.pressure,
            x,
            out / "pressure_map.png",
            label="pressure (MPa)",
            cmap="magma",
            scale=1e-6,
            title=rf"$\mu$ = {f.friction:.4g}, contact {100 * f.contact_fraction:.2f} %",
            direction=scene.direction,
        )
        field_map(
            scene.surface,
            (f.pressure > 0).astype(int),
            x,
            out / "contact_map.png",
            label="",
            cmap=None,
            title=f"contact area {100 * f.contact_fraction:.2f} % (realisation 0)",
            discrete=["no contact", "contact"],
            direction=scene.direction,
        )
        deformed_surface(
            scene.surface, f, x, out / "deformed_surface.png", periodic=scene.periodic, direction=scene.direction
        )
        names += ["pressure_map.png", "contact_map.png", "deformed_surface.png"]
    if scene.outputs["anisotropy"]:
        polar_m2(scene, record, 0, i, out / "polar_m2.png")
        names.append("polar_m2.png")
    if extras.get("psd") and (0, i) in extras["psd"]:
        cpsd, ell = extras["psd"][(0, i)]
        psd_contour(scene, cpsd, ell, scene.xi[i], out / "contact_psd.png")
        names.append("contact_psd.png")
    if scene.outputs["anisotropy"] or scene.outputs["contact_psd"]:
        anisotropy_vs_xi(scene, record, out / "anisotropy.png", peak)
        names.append("anisotropy.png")
    return names
