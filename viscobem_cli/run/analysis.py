"""Study-level analysis of a finished sweep: anisotropy, contact PSD, Persson's theory.

Anisotropy. Per point the spectral moments of the deformed surface (the
displacement field ``u``, the solid's surface shape) are computed in the sweep. Here,
for each load and speed:

- ``gamma``, ``theta_max``: mean and standard error over realisations of each
  realisation's own values (axial mean for the angle);
- ``gamma_ensemble``, ``theta_ensemble``: of the realisation-averaged moment tensor;
- ``gamma_relative``, ``theta_relative``: speed-induced anisotropy, each realisation's
  tensor whitened by its own tensor at the lowest speed of the sweep
  (:func:`bem.analysis.anisotropy.relative_moments`), then mean and standard error; and
  ``gamma_relative_ensemble`` from the averaged tensors.

Contact PSD: the indicator maps of all realisations at a point are averaged into one
smoothed PSD (:func:`bem.analysis.anisotropy.contact_psd`) and its contour at ``contact_level`` is
fitted by an ellipse (:func:`bem.analysis.anisotropy.psd_contour`); ``stretch_x`` (extent along
``q_x`` over extent along ``q_y``) is also given relative to its value at the lowest speed
(``stretch_x_relative``), since a finite ensemble keeps some anisotropy of its own.
"""

import numpy as np

from bem.analysis import anisotropy, persson
from bem.errors import InputError

from .points import load_fields


def _axial_mean(angles):
    a = np.asarray(angles, dtype=float)
    return float(0.5 * np.arctan2(np.mean(np.sin(2 * a)), np.mean(np.cos(2 * a))) % np.pi)


def _mean_se(values):
    v = np.asarray(values, dtype=float)
    if v.size == 0:
        return None, None
    return float(v.mean()), (float(v.std(ddof=1) / np.sqrt(v.size)) if v.size > 1 else None)


def _moments(d):
    return anisotropy.SpectralMoments(d["m20"], d["m02"], d["m11"], d["gamma"], d["theta_max"])


def _tensor_mean(ms):
    m20, m02, m11 = (float(np.mean([getattr(m, k) for m in ms])) for k in ("m20", "m02", "m11"))
    return anisotropy.moments_from_tensor(m20, m02, m11)


def anisotropy_summary(scene, recs, l):
    """Anisotropy of the deformed surface against xi for load index ``l`` (see module doc)."""
    n, k = scene.speeds.size, len(scene.realisations)
    order = np.argsort(scene.speeds, kind="stable")
    refs = {}
    for r in range(k):
        for i in order:
            p = recs.get((r, l, int(i)))
            if p is not None and p.get("moments"):
                refs[r] = (int(i), _moments(p["moments"]))
                break
    out = {"load": scene.loads[l], "xi": scene.xi.tolist(), "reference_xi": None}
    keys = [
        "gamma",
        "gamma_se",
        "theta_max",
        "gamma_ensemble",
        "theta_ensemble",
        "gamma_relative",
        "gamma_relative_se",
        "theta_relative",
        "gamma_relative_ensemble",
        "theta_relative_ensemble",
        "m02_over_m20",
    ]
    for key in keys:
        out[key] = [None] * n
    if refs:
        out["reference_xi"] = [float(scene.xi[refs[r][0]]) for r in sorted(refs)]
    ref_ens = _tensor_mean([m for _, m in refs.values()]) if refs else None
    for i in range(n):
        ms = {
            r: _moments(recs[(r, l, i)]["moments"])
            for r in range(k)
            if recs.get((r, l, i)) is not None and recs[(r, l, i)].get("moments")
        }
        if not ms:
            continue
        out["gamma"][i], out["gamma_se"][i] = _mean_se([m.gamma for m in ms.values()])
        out["theta_max"][i] = _axial_mean([m.theta_max for m in ms.values()])
        ens = _tensor_mean(list(ms.values()))
        out["gamma_ensemble"][i], out["theta_ensemble"][i] = ens.gamma, ens.theta_max
        out["m02_over_m20"][i] = ens.m02 / ens.m20
        rel = [anisotropy.relative_moments(m, refs[r][1]) for r, m in ms.items() if r in refs]
        if rel:
            out["gamma_relative"][i], out["gamma_relative_se"][i] = _mean_se([m.gamma for m in rel])
            out["theta_relative"][i] = _axial_mean([m.theta_max for m in rel])
            if len(ms) == len(refs):
                rel_ens = anisotropy.relative_moments(ens, ref_ens)
                out["gamma_relative_ensemble"][i] = rel_ens.gamma
                out["theta_relative_ensemble"][i] = rel_ens.theta_max
    return out


def contact_psd_summary(scene, recs, points_dir):
    """Ellipse of the ensemble contact PSD per load and speed; also the PSD maps (for plots)."""
    summary, maps = [], {}
    for l in range(len(scene.loads)):
        rows = {
            "load": scene.loads[l],
            "xi": scene.xi.tolist(),
            "level": scene.contact_level,
            "smoothing": scene.psd_smoothing,
            "aspect_ratio": [],
            "orientation": [],
            "stretch_x": [],
            "semi_major": [],
            "semi_minor": [],
            "fit_residual": [],
            "message": [],
        }
        for i in range(scene.speeds.size):
            chis = []
            for r, surf in enumerate(scene.realisations):
                rec = recs.get((r, l, i))
                if rec is not None and rec["success"]:
                    data = load_fields(points_dir, rec, surf)
                    if data is not None:
                        chis.append(data["chi"])
            ell, msg = None, ""
            if chis:
                try:
                    cpsd = anisotropy.contact_psd(np.stack(chis), scene.surface.length, smoothing=scene.psd_smoothing)
                    ell = anisotropy.psd_contour(cpsd, scene.contact_level, direction=scene.direction)
                    maps[(l, i)] = (cpsd, ell)
                except InputError as err:
                    msg = str(err)
            else:
                msg = "no converged point with a stored contact map"
            d = ell.as_dict() if ell is not None else {}
            for key in ("aspect_ratio", "orientation", "stretch_x", "semi_major", "semi_minor", "fit_residual"):
                rows[key].append(d.get(key))
            rows["message"].append(msg)
        # relative to the lowest speed with a fitted ellipse (the ensemble's own low-speed shape)
        order = [int(i) for i in np.argsort(scene.speeds, kind="stable") if rows["stretch_x"][int(i)] is not None]
        ref = rows["stretch_x"][order[0]] if order else None
        rows["reference_xi"] = float(scene.xi[order[0]]) if order else None
        rows["stretch_x_relative"] = [None if (x is None or ref is None) else x / ref for x in rows["stretch_x"]]
        summary.append(rows)
    return summary, maps


def persson_summary(scene):
    """Persson's friction and contact area per load: continuous (target PSD of a generated
    isotropic surface) and discrete (grid sums over each realisation, averaged)."""
    out = []
    area = scene.surface.length**2
    for load in scene.loads:
        row = {"load": load, "pressure": load / area, "xi": scene.xi.tolist()}
        mus, areas = [], []
        for surf in scene.realisations:
            mu, a = persson.friction_discrete(surf, scene.material, speeds=scene.speeds, pressure=load / area)
            mus.append(mu)
            areas.append(a)
        row["friction_discrete"] = np.mean(mus, axis=0).tolist()
        row["contact_fraction_discrete"] = np.mean(areas, axis=0).tolist()
        try:
            mu, a = persson.friction_for_surface(
                scene.surface, scene.material, speeds=scene.speeds, pressure=load / area
            )
            row["friction"], row["contact_fraction"] = mu.tolist(), a.tolist()
            row["form"] = "continuous (target PSD)"
        except InputError:
            row["friction"], row["contact_fraction"] = row["friction_discrete"], row["contact_fraction_discrete"]
            row["form"] = "discrete (grid sums; the surface has no target PSD)"
        out.append(row)
    return out
