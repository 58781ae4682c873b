"""What a solution says about its own resolution: cheap, dimensionless indicators.

Each indicator is computed from what a solve already has (the pressure on its grid, the
heights, the material and the speed), in a few FFTs at most, and is the same for periodic
cells and isolated domains, 1-D profiles and 2-D surfaces, whatever made the surface
(docs/theory.md §13):

- :func:`contact_perimeter`: faces between contact and non-contact cells per contact cell.
  The area of a cell cut by the contact's edge is counted whole or not at all, so the
  discrete contact area is off by a share of a cell per unit of perimeter (Yastrebov,
  Anciaux & Molinari 2017).
- :func:`dissipation_moment`: the share of the dissipation that comes from wavelengths near
  the grid's Nyquist, ``sum_q D(q) (|q|/q_N)**4 / sum_q D(q)`` with
  ``D(q) = (q.d) Im(a_q) |p_q|**2`` the friction's spectrum (theory §4.3). Pressure modes near
  the Nyquist are the ones a grid gets wrong; friction that lives there is unresolved.
- :func:`interior_roughness`: the pressure's own roughness at the grid scale inside the contact,
  ``rms(discrete Laplacian of p) / rms(p)`` over contact cells whose neighbours are all in
  contact: near 0 for a smooth contact (a sphere, a cylinder), of order 1 where the pressure
  follows roughness a few cells wide. Near-Nyquist dissipation of a smooth contact comes from its
  edges (the grid cuts it short); that of a rough one largely from roughness both grids carry.
- :func:`peak_sharpness`: how far the largest pressure stands above its grid neighbours,
  ``(p_max - mean of its 2 ndim neighbours) / p_max``: 0 for a peak the grid resolves,
  near 1 for a spike a cell wide (a contact spot of one cell, or a leading-edge layer).
- :func:`subcell_layers`: the Prony terms whose leading-edge layer ``V tau_k`` is thinner than
  a cell, with their share of the modulus the grid's own frequency ``V / dx`` sees.
- :func:`leading_edge_layers`: whether the pressure's leading-edge spike lies inside the edge cell.
  Entering the contact, the material relaxes through each Prony term over ``V tau_k``; near the
  edge the strain rises like ``sqrt(s)`` at a distance ``s`` from it, and the stress follows by
  superposition through the relaxation modulus ``E(t)``, ``t = s / V``, so layers thinner than a cell can raise a spike there that the grid averages
  away. Read against the edge cell's own pressure, this gives the pressure's maximum inside that
  cell and the edge cell's pressure on a grid twice as fine.
- :func:`points_per_wavelength`: grid points per shortest wavelength of the heights (the
  wavelength below which 5 % of their curvature spectrum lies).
- :func:`form_gap` and :func:`edge_load`: the two friction forms' relative difference, and the
  share of the load that an isolated domain carries on its outermost cells.

Units: SI; every returned indicator is dimensionless unless its docstring says otherwise.
"""

import math

import numpy as np
import scipy.fft as sfft
from scipy.special import dawsn

from .. import fft

__all__ = [
    "contact_perimeter",
    "dissipation_moment",
    "edge_load",
    "form_gap",
    "interior_roughness",
    "leading_edge_layers",
    "loading_band",
    "peak_sharpness",
    "points_per_wavelength",
    "subcell_layers",
]

_CHUNK = 2**20  # complex compliance values evaluated at once (memory: ~16 bytes per value and term)


def contact_perimeter(contact, periodic):
    """Faces between contact and non-contact cells, per contact cell (0 with no contact).

    ``contact`` is the boolean contact map; on periodic cells the faces across the cell's
    sides count, on isolated domains the domain's boundary is not a face.
    """
    contact = np.asarray(contact, dtype=bool)
    cells = int(np.count_nonzero(contact))
    if cells == 0:
        return 0.0
    faces = 0
    for axis in range(contact.ndim):
        if periodic:
            faces += int(np.count_nonzero(contact != np.roll(contact, 1, axis=axis)))
        else:
            faces += int(np.count_nonzero(np.diff(contact, axis=axis)))
    return faces / cells


def _wavevectors_of(shape, length, periodic):
    """``((qx[, qy]), transform, full shape)``: wavevectors (rad/m) of the pressure's spectrum and the
    transform to take it with: the cell's own on periodic grids, the zero-padded domain (twice the
    side, so that the pressure is not seen as periodic) on isolated ones."""
    if periodic:
        return fft.wavevectors(shape, length), fft.forward, shape
    padded = tuple(2 * n for n in shape)
    return fft.wavevectors(padded, 2 * length), lambda p: sfft.rfftn(p, s=padded, norm="forward"), padded


def _creep_symbol(material, speed, qs):
    """``Im J(-qs v)`` (1/Pa) at the slopes' wavenumbers ``qs`` (any shape), in chunks."""
    flat = np.ravel(qs)
    out = np.empty(flat.size)
    step = max(1, _CHUNK // max(1, material.creep_times.size))
    for start in range(0, flat.size, step):
        out[start : start + step] = np.imag(material.complex_compliance(-flat[start : start + step] * speed))
    return out.reshape(np.shape(qs))


def dissipation_moment(pressure, material, speed, length, *, periodic, direction=0.0, power=4):
    """``sum_q D(q) (|q|/q_N)**power / sum_q D(q)``, ``D(q) = (q.d) Im(a_q) |p_q|**2``, in [0, 1].

    ``a_q = 2 (1 - nu**2) J(-(q.d) v) / |q|`` is the symbol of theory §3.2 along the sliding
    direction ``d`` (radians from +x), ``q_N = pi / dx`` the grid's Nyquist wavenumber. ``None``
    where nothing dissipates (elastic, zero speed or no pressure): friction is then zero on
    any grid.
    """
    p = np.asarray(pressure, dtype=float)
    if material.is_elastic or speed == 0.0 or not np.any(p > 0):
        return None
    shape = p.shape
    q, transform, full = _wavevectors_of(shape, length, periodic)
    pq = transform(p)
    if len(q) == 1:
        qs, qn = q[0], np.abs(q[0])
    else:
        c, s = math.cos(direction), math.sin(direction)
        qs = c * q[0] + s * q[1] if s else np.broadcast_to(q[0], pq.shape)
        qn = np.sqrt(q[0] ** 2 + q[1] ** 2)
    if len(q) == 2 and not math.sin(direction):
        im_j = _creep_symbol(material, speed, q[0])  # a column: J depends on q_x only
    else:
        im_j = _creep_symbol(material, speed, qs)
    with np.errstate(divide="ignore", invalid="ignore"):
        spectrum = np.where(qn > 0, qs * im_j / qn, 0.0) * np.abs(pq) ** 2
    spectrum = spectrum * fft.full_spectrum_weights(full)
    total = float(np.sum(spectrum))
    if not total > 0:
        return None
    q_nyquist = math.pi * shape[0] / length
    return float(np.sum(spectrum * np.minimum(qn / q_nyquist, 1.0) ** power) / total)


def interior_roughness(pressure, periodic):
    """``rms(sum of second differences of p) / rms(p)`` over the contact cells whose 2 ndim
    neighbours are all in contact (on isolated domains, not on the domain's edge); 1 when fewer
    than 4 such cells exist (a contact of a few cells is as rough as the grid)."""
    p = np.asarray(pressure, dtype=float)
    contact = p > 0
    inner = contact.copy()
    laplacian = -2.0 * p.ndim * p
    for axis in range(p.ndim):
        for step in (-1, 1):
            inner &= np.roll(contact, step, axis=axis)
            laplacian += np.roll(p, step, axis=axis)
    if not periodic:
        border = np.ones_like(inner)
        border[tuple(slice(1, -1) for _ in p.shape)] = False
        inner &= ~border
    if np.count_nonzero(inner) < 4:
        return 1.0
    return float(np.sqrt(np.mean(laplacian[inner] ** 2) / np.mean(p[inner] ** 2)))


def _neighbours(p, index, periodic):
    """Values of the 2 ndim grid neighbours of ``index`` (0 beyond an isolated domain's edge)."""
    out = []
    for axis in range(p.ndim):
        for step in (-1, 1):
            j = list(index)
            j[axis] += step
            if periodic:
                j[axis] %= p.shape[axis]
            elif not 0 <= j[axis] < p.shape[axis]:
                out.append(0.0)
                continue
            out.append(float(p[tuple(j)]))
    return out


def _cells_to_edge(contact, index, periodic, reach):
    """Steps (1..reach) along a grid axis from ``index`` to the nearest non-contact cell (an
    isolated domain's outside counts), or ``None`` if there is none within ``reach``."""
    for step in range(1, reach + 1):
        for axis in range(contact.ndim):
            for sign in (-1, 1):
                j = list(index)
                j[axis] += sign * step
                if periodic:
                    j[axis] %= contact.shape[axis]
                elif not 0 <= j[axis] < contact.shape[axis]:
                    return step
                if not contact[tuple(j)]:
                    return step
    return None


def peak_sharpness(pressure, periodic, *, reach=2):
    """``(sharpness, cells_to_edge)`` at the largest pressure: ``(p_max - mean of its 2 ndim
    neighbours) / p_max``, and the grid steps from it to the contact's edge if within ``reach``
    (else ``None``): a peak on or next to the edge is a pressure rising within a cell or two."""
    p = np.asarray(pressure, dtype=float)
    index = np.unravel_index(int(np.argmax(p)), p.shape)
    top = float(p[index])
    if not top > 0:
        return 0.0, None
    around = _neighbours(p, index, periodic)
    return (top - float(np.mean(around))) / top, _cells_to_edge(p > 0, index, periodic, reach)


def subcell_layers(material, speed, spacing, *, share=0.01):
    """Prony terms whose leading-edge layer ``V tau_k`` (m) is thinner than the cell ``dx``.

    A term's layer is the distance over which the material, entering the contact, relaxes
    through it (relaxation time ``tau_k``). Returned as a list of ``(tau_k (s), V tau_k / dx,
    E_k / |E*(V/dx)|)`` for the terms whose modulus ``E_k`` is at least ``share`` of the
    modulus the grid's own frequency ``V / dx`` sees: sub-cell layers of terms that small do not
    change the contact's pressure. Thinnest first.
    """
    if material.is_elastic or speed == 0.0:
        return []
    w_cell = speed / spacing
    modulus = abs(complex(material.complex_modulus(w_cell)))
    out = []
    for e_k, tau in zip(material.moduli, material.relaxation_times):
        thickness = speed * tau / spacing
        if thickness < 1.0 and e_k >= share * modulus:
            out.append((float(tau), float(thickness), float(e_k / modulus)))
    return sorted(out, key=lambda t: t[1])


def _edge_profile(material, speed, s):
    """``g(s)`` (Pa m**0.5): the stress at a distance ``s`` (m, an array) from the leading edge of a
    material strained like ``sqrt(s)`` since it entered the contact, by Boltzmann superposition along
    its path, ``g(s) = int_0^s E((s - r) / V) d sqrt(r)``; a term's share is
    ``E_k sqrt(l_k) D(sqrt(s / l_k))`` with ``l_k = V tau_k`` and ``D`` Dawson's integral."""
    s = np.asarray(s, dtype=float)
    ell = speed * material.relaxation_times
    terms = np.sqrt(ell) * dawsn(np.sqrt(s[..., None] / ell))
    return material.E0 * np.sqrt(s) + terms @ material.moduli


def _edge_means(material, speed, s, g):
    """``A(s) = (1/s) int_0^s g`` at the samples ``s`` (ascending, log-spaced) of ``g``; below the first
    sample the material is glassy, ``g = E_inf sqrt(s)``."""
    head = 2.0 / 3.0 * material.E_inf * s[0] ** 1.5
    return (head + np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(s))])) / s


def _leading_edge_cells(contact, periodic, direction):
    """Contact cells whose neighbour ahead (along the sliding direction's dominant axis, on the side
    the indenter moves to) is out of contact: where the material enters the contact."""
    c, s = math.cos(direction), math.sin(direction)
    axis, sign = (0, c) if abs(c) >= abs(s) else (1, s)
    if contact.ndim == 1:
        axis = 0
    step = -1 if sign >= 0 else 1
    if periodic:
        ahead = np.roll(contact, step, axis=axis)
    else:
        pad = [(0, 0)] * contact.ndim
        pad[axis] = (1, 1)
        padded = np.pad(contact, pad)
        ahead = np.roll(padded, step, axis=axis)[
            tuple(slice(1, -1) if a == axis else slice(None) for a in range(contact.ndim))
        ]
    return contact & ~ahead


def leading_edge_layers(pressure, material, speed, spacing, *, periodic, direction=0.0, samples=800):
    """``(spike, growth)``: the leading-edge pressure inside the edge cell, from the layers ``V tau_k``.

    With ``g(s)`` the pressure's rise at a distance ``s`` from the leading edge (:func:`_edge_profile`:
    the stress of a material strained like ``sqrt(s)``, an elastic contact's edge, since it entered
    the contact ``s / V`` ago, through its relaxation modulus ``E(t)``) and
    ``A(h)`` its mean over ``0 <= s <= h``, the largest leading-edge cell pressure ``p_e`` gives

    - ``spike = p_e max(g) / A(dx) / p_max``, the largest pressure inside the edge cell relative to
      the grid's peak, where ``g`` has its maximum inside the cell (layers thinner than the cell
      make it fall again before the cell ends), else 0: above 1 the contact's true peak lies in
      layers the grid cannot hold;
    - ``growth = A(dx / 2) / A(dx)``, how the edge cell's pressure changes on a grid twice as fine:
      ``2**-0.5`` for an elastic edge, above 1 where the layers stiffen the edge faster than the
      square root falls.

    ``(0, 0)`` for an elastic material, at rest or without contact. Dimensionless.
    """
    p = np.asarray(pressure, dtype=float)
    if material.is_elastic or speed == 0.0 or not np.any(p > 0):
        return 0.0, 0.0
    lead = _leading_edge_cells(p > 0, periodic, direction)
    if not np.any(lead):
        return 0.0, 0.0
    ell_min = float(speed * material.relaxation_times.min())
    s = np.geomspace(min(ell_min, spacing) * 1e-3, spacing, samples)
    g = _edge_profile(material, speed, s)
    means = _edge_means(material, speed, s, g)
    growth = float(np.interp(math.log(spacing / 2), np.log(s), means) / means[-1])
    top = int(np.argmax(g))
    if top == samples - 1:  # g still rises at the cell's end: no spike inside the cell
        return 0.0, growth
    return float(p[lead].max() * g[top] / means[-1] / p.max()), growth


def points_per_wavelength(heights):
    """Grid points per shortest wavelength of ``heights`` (any 1-D or square 2-D array).

    The shortest wavelength is ``2 pi / q_c`` with ``q_c`` the wavenumber below which 95 % of the
    curvature spectrum ``|q|**4 |h_q|**2`` lies (binned to whole modes): for a band-limited
    self-affine surface ``q_c`` is within a few per cent of its cut-off ``q_1``; for a measured
    one it is where its curvature lives, often the grid's own Nyquist (2 points). ``inf`` for a
    plane.
    """
    h = np.asarray(heights, dtype=float)
    n = h.shape[0]
    spectrum = np.abs(sfft.rfftn(h - h.mean())) ** 2
    k = [sfft.fftfreq(n, 1.0 / n)] * (h.ndim - 1) + [sfft.rfftfreq(n, 1.0 / n)]
    kk = np.sqrt(sum(g**2 for g in np.meshgrid(*k, indexing="ij", sparse=True)))
    weight = spectrum * kk**4
    if not np.any(weight > 0):
        return math.inf
    bins = np.rint(kk).astype(np.int64).ravel()
    cumulative = np.cumsum(np.bincount(bins, weights=weight.ravel()))
    k_c = int(np.searchsorted(cumulative, 0.95 * cumulative[-1]))
    return float(n / max(k_c, 1))


def loading_band(surface, speed, *, periodic, direction=0.0):
    """``(w_low, w_high)`` (rad/s): the angular frequencies at which the grid loads the material,
    ``v q`` for the wavenumbers ``q`` along the sliding direction that the grid holds: from the
    cell's (or domain's) longest, ``2 pi / L`` (``pi / L`` on isolated domains), to the Nyquist
    ``pi / dx`` (times ``|cos| + |sin|`` of an oblique direction). ``(0, 0)`` at rest."""
    speed = float(speed)
    if speed == 0.0:
        return 0.0, 0.0
    low = (2.0 if periodic else 1.0) * math.pi / surface.length
    high = math.pi / surface.spacing
    if surface.ndim == 2:
        high *= abs(math.cos(direction)) + abs(math.sin(direction))
    return speed * low, speed * high


def form_gap(friction, friction_eq6):
    """``|mu - mu_eq6| / max(|mu|, |mu_eq6|)``: 0 when the two friction forms agree (or both are 0)."""
    scale = max(abs(friction), abs(friction_eq6))
    return abs(friction - friction_eq6) / scale if scale > 0 else 0.0


def edge_load(pressure):
    """Share of the load on the outermost cells of an isolated domain (0: the contact stays inside)."""
    p = np.asarray(pressure, dtype=float)
    total = float(p.sum())
    if not total > 0:
        return 0.0
    inner = p[tuple(slice(1, -1) for _ in p.shape)]
    return float((total - inner.sum()) / total)
