"""Plots of the speed-induced anisotropy: polar m2(theta), the contact-PSD contour with its
fitted ellipse, and the anisotropy measures against xi."""

import numpy as np

from .style import mark_peak, nan_array, pyplot, save


def polar_m2(scene, record, l, i, path):
    """m2(theta) of the deformed surface (ensemble tensor) at xi_i and at the lowest xi."""
    from bem.analysis.anisotropy import moments_from_tensor

    plt = pyplot()
    pts = [p for p in record["points"] if p["l"] == l and p.get("moments")]
    theta = np.linspace(0, 2 * np.pi, 361)
    fig = plt.figure(figsize=(5.2, 5.0), constrained_layout=True)
    ax = fig.add_subplot(projection="polar")
    order = np.argsort(scene.speeds, kind="stable")
    for idx, style, name in [(int(order[0]), "--", "lowest"), (i, "-", "")]:
        ms = [p["moments"] for p in pts if p["i"] == idx]
        if not ms:
            continue
        m = moments_from_tensor(*(np.mean([d[k] for d in ms]) for k in ("m20", "m02", "m11")))
        r = m.m2(theta) / m.m2_max
        ax.plot(
            theta,
            r,
            style,
            label=rf"$\xi$ = {scene.xi[idx]:.3g} {name}: $\gamma$ = {m.gamma:.3f}, "
            rf"$\Theta$ = {np.degrees(m.theta_max):.0f}°",
        )
    ax.set_title(r"$m_2(\theta) / \max m_2$ of the deformed surface (sliding along $\theta = 0$)", fontsize=9)
    ax.legend(fontsize=7, loc="lower center", bbox_to_anchor=(0.5, -0.22))
    save(fig, path)


def psd_contour(scene, cpsd, ellipse, xi, path):
    """C_chi / C_chi(0) around q = 0 with the level contour and the fitted ellipse."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.4, 4.8), constrained_layout=True)
    qL = 2 * np.pi / scene.surface.length
    reach = 2.2 * ellipse.semi_axes[0] / qL
    q = cpsd.q / qL
    sel = np.abs(q) <= reach
    z = cpsd.level_map[np.ix_(sel, sel)]
    im = ax.pcolormesh(q[sel], q[sel], z.T, shading="nearest", cmap="viridis")
    fig.colorbar(im, ax=ax, label=r"$C_\chi(q) / C_\chi(0)$")
    ax.contour(q[sel], q[sel], z.T, levels=[ellipse.level], colors="w", linewidths=1)
    t = np.linspace(0, 2 * np.pi, 200)
    vals, vecs = np.linalg.eigh(np.array([[ellipse.A, ellipse.B], [ellipse.B, ellipse.D]]))
    pts = vecs @ np.vstack([np.cos(t) / np.sqrt(vals[0]), np.sin(t) / np.sqrt(vals[1])]) / qL
    ax.plot(
        pts[0],
        pts[1],
        "r--",
        lw=1.2,
        label=f"ellipse: aspect {ellipse.aspect_ratio:.3f}, q_x/q_y extent {ellipse.stretch_x:.3f}",
    )
    ax.set_aspect("equal")
    ax.set_xlabel(r"$q_x / q_L$ (sliding direction)")
    ax.set_ylabel(r"$q_y / q_L$")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(rf"contact PSD at $\xi$ = {xi:.3g}, contour {ellipse.level:g}", fontsize=9)
    save(fig, path)


def anisotropy_vs_xi(scene, record, path, peak):
    """gamma (own and relative to the low-speed surface) and the C_chi ellipse against xi."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.2), constrained_layout=True)
    xi = np.asarray(scene.xi)
    if "anisotropy" in record:
        a = record["anisotropy"][0]
        ax.errorbar(
            xi,
            nan_array(a["gamma"]),
            yerr=nan_array(a["gamma_se"]),
            fmt="o-",
            ms=4,
            capsize=2,
            label=r"$\gamma$ of the deformed surface",
        )
        ax.errorbar(
            xi,
            nan_array(a["gamma_relative"]),
            yerr=nan_array(a["gamma_relative_se"]),
            fmt="s-",
            ms=4,
            capsize=2,
            label=r"$\gamma$ relative to the lowest-speed surface",
        )
    if "contact_psd" in record:
        c = record["contact_psd"][0]
        ax.plot(xi, 1 / nan_array(c["stretch_x"]), "^-", ms=4, label=r"$C_\chi$ contour: extent $q_y/q_x$")
        ax.plot(
            xi,
            1 / nan_array(c["stretch_x_relative"]),
            "v-",
            ms=4,
            label=r"$C_\chi$ contour: $q_y/q_x$ relative to the lowest speed",
        )
    mark_peak(ax, xi, peak)
    ax.set_xscale("log")
    ax.set_xlabel(r"$\xi = v\,\tau / L$  (dotted: friction peak)")
    ax.set_ylabel("anisotropy ratio (1 = isotropic)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, path)
