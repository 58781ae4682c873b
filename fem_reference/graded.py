"""Mesh plan for rolling on real rubbers: which Prony terms act, and where to refine.

A tensor mesh of rectangles, graded geometrically (:mod:`fem_reference.grading`):

- in ``x`` toward the trailing and the leading contact edges (element size
  ``a_c / resolution`` there, ``a_c`` the contact half-width), further toward the trailing
  edge (:data:`LAYER_ELEMENTS` elements across a zone one edge element wide about it), and
  further toward the leading edge, where material enters the contact and each Prony term ``k`` relaxes over a
  layer of width ``ell_k = V tau_k`` behind the edge: the thinnest over the kept terms gets
  :data:`LAYER_ELEMENTS` elements if it is at least ``layer_floor * a_c / resolution`` (for a
  single kept term, :data:`SINGLE_TERM_FLOOR` instead, if lower); a thinner one gets elements of
  that floor and is not resolved; where those elements would be smaller than the block
  half-width over :data:`MAX_SPAN` (elements that long and thin spoil the factors), the edge
  elements stay and the layer is not resolved either;
- in depth toward the surface (size ``a_c / resolution`` at ``y = 0``).

Every row of quadrature points stays a horizontal line (a streamline), so the exact
exponential update of the viscous strains applies on any grading.

Folding (a term is dropped only when it cannot matter at the mesh's scales): the stress
of arm ``k`` is ``E_k (eps - alpha_k)``.

- Relaxed side: ``eps - alpha_k ~ ell_k d(eps)/dx`` and no strain varies faster than over
  the smallest element ``h_min``, so the arm carries at most ``(E_k / E0) ell_k / h_min``
  of the relaxed stress ``E0 eps``; it is dropped when that is below ``tol``.
- Glassy side: over the whole block (length ``2 L``) ``alpha_k`` moves by at most
  ``2 L / ell_k`` of the strain, so the arm differs from a spring ``E_k`` by at most
  ``(E_k / E0) 2 L / ell_k``; below ``tol`` it is added to the relaxed modulus.
"""

from __future__ import annotations

import numpy as np

from bem.materials.material import Material

from .grading import graded_coordinates

__all__ = ["fold_terms", "initial_edges", "graded_half_space"]

# elements across the thinnest leading-edge layer: the pressure rises to its peak over that layer,
# and the nodal peak converges once a few elements span it (Hunter at E_inf/E0 = 1000, four speeds
# about its friction peak: within 0.5 % at 4, from -0.1 to +3.8 % at 2, where it moved with where the
# nodes fell on the layer)
LAYER_ELEMENTS = 4
# a single kept term's layer is resolved down to this many edge elements whatever ``layer_floor``.
# Hunter at E_inf/E0 = 1000 resolved this way to within 0.3 % of his peak pressure at layers of 6e-4
# and 1.8e-4 edge elements; at 1.2e-4 the contact's active set cycled (elements 3e-5 edge elements
# along a surface row that spans the whole block), so a margin of four from there
SINGLE_TERM_FLOOR = 5e-4
# largest block half-width over the leading-edge elements. The tensor mesh carries its smallest
# columns through the whole depth and its smallest row along the whole length, so this is about the
# largest aspect ratio of its elements, and the factors lose accuracy with it. Measured on broad
# rubbers (E_inf/E0 = 500-1000): refined meshes solved at spans up to 6.4e6 and missed PARDISO's
# residual limit at 1.6e7 (by 1.7 times) and 4e7-1.6e8 (by up to three orders), two decades above
# the friction peak, where the block (30 V lambda_max) is 1e4-1e5 contact half-widths; there the
# same blocks solved with no refinement toward the layer (spans of 4e5-1.3e6, edge elements)
MAX_SPAN = 1e7


def fold_terms(material, speed, h_min, length, tol):
    """``(material, info)``: the terms kept, and which ``tau_k`` were relaxed or glassy."""
    tau = material.relaxation_times
    Ek = material.moduli
    info = {"kept": [], "relaxed": [], "glassy": []}
    if tol <= 0 or material.is_elastic:
        info["kept"] = [float(t) for t in tau]
        return material, info
    ell = speed * tau
    w = Ek / material.E0
    relaxed = w * ell / h_min < tol
    with np.errstate(divide="ignore"):
        glassy = ~relaxed & (w * 2.0 * length / ell < tol)
    kept = ~(relaxed | glassy)
    info = {"kept": tau[kept].tolist(), "relaxed": tau[relaxed].tolist(), "glassy": tau[glassy].tolist()}
    folded = Material(material.E0 + Ek[glassy].sum(), Ek[kept], tau[kept], material.nu)
    return folded, info


def _half_width(E, nu, radius, load):
    return float(np.sqrt(4.0 * load * radius * (1.0 - nu**2) / (np.pi * E)))


def initial_edges(material, radius, load, speed):
    """Hertz edges ``(-a, a)`` for the modulus ``|E(omega)|`` at ``omega = V / a`` (m)."""
    a = _half_width(material.E0, material.nu, radius, load)
    for _ in range(50):
        E = abs(complex(material.complex_modulus(speed / a))) if speed > 0 else material.E0
        a_new = _half_width(E, material.nu, radius, load)
        if abs(a_new - a) < 1e-6 * a:
            break
        a = np.sqrt(a * a_new)
    return -a, a


def _layer_sizes(edges, material, speed, resolution, layer_floor):
    """``(h_edge, thinnest, h_lead, resolved)``: the edge elements, the thinnest leading-edge layer
    ``V tau_k``, the elements toward it and whether they resolve it (m; see the module docstring)."""
    trail, lead = edges
    h_edge = 0.5 * (lead - trail) / resolution
    ell = speed * material.relaxation_times
    ell = ell[ell > 0]
    floor = layer_floor * h_edge
    thinnest = float(ell.min()) if ell.size else float("inf")
    if ell.size == 1 and thinnest >= SINGLE_TERM_FLOOR * h_edge:
        # one term (a standard solid): its fine zone adds rows of elements, logarithmic in the
        # layer's thinness, and no other memory spans them; the floor is for many terms, whose
        # memories all cross the fine elements
        floor = min(floor, thinnest)
    # a layer at or above the floor gets LAYER_ELEMENTS elements; a thinner one is left at the floor
    # and reported unresolved: refining toward it would add rows of elements along the whole surface
    # (and lengthen the condensed memories, in elements) for a peak still not resolved
    h_lead = min(thinnest / LAYER_ELEMENTS if thinnest >= floor else floor, h_edge)
    return h_edge, thinnest, h_lead, floor <= thinnest < np.inf


def graded_half_space(edges, material, speed, *, resolution, length, ratio=1.25, layer_floor=0.01, coarsen=1.0):
    """A :class:`~fem_reference.mesh.HalfSpaceMesh` graded toward the contact ``edges``.

    Parameters
    ----------
    edges : (float, float)
        Trailing and leading contact edges (m).
    material : bem.Material
        The terms kept (their ``V tau_k`` set the leading-edge layer).
    speed : float
        Rolling speed (m/s).
    resolution : float
        Elements per contact half-width at the edges and at the surface.
    length : float
        Block half-width = depth ``L`` (m).
    ratio : float
        Largest growth between neighbouring elements.
    layer_floor : float
        Thinnest leading-edge layer the mesh resolves, in edge elements (and the element size
        toward a thinner one); none where that would take elements below ``length / MAX_SPAN``.
    coarsen : float
        Every size the contact sets (the edge elements, the trailing zone, the layer's elements)
        times this, the same layers resolved: the twin of the rolling model's error estimate.
    """
    from .mesh import HalfSpaceMesh, half_space_boundaries

    trail, lead = edges
    h_edge, thinnest, h_lead, resolved = _layer_sizes(edges, material, speed, resolution, layer_floor)
    if length > MAX_SPAN * h_lead:
        # a block many decades larger than the layer (the wake of a slow creep mode at high speed):
        # elements of the layer's size would be needles across it, and elements in between solved no
        # better (MAX_SPAN), so the layer is left to the edge elements and reported unresolved
        h_lead, resolved = h_edge, False
    h_edge, h_lead = coarsen * h_edge, coarsen * h_lead
    # the trailing edge, where the pressure falls to zero as the square root of the distance, gets
    # LAYER_ELEMENTS elements across a zone one edge element wide about it, as the leading edge gets
    # them across its layer: its place within a node spacing sets the low-speed friction, whose
    # pressure centroid lies a small fraction of the contact ahead of its centre. The zone is twice
    # the distance the edge may still move when the passes stop (rolling), so it settles inside it
    h_trail = h_edge / LAYER_ELEMENTS
    zone = (trail - 0.5 * h_edge, trail + 0.5 * h_edge)
    caps = [(trail, lead, h_edge), (*zone, h_trail)]
    if resolved:
        # the whole layer at that size, and half a layer beyond it on each side: the nodal peak then
        # does not depend on where within that margin the edge settles (rolling's passes)
        pad = 0.5 * LAYER_ELEMENTS * h_lead
        caps.append((lead - thinnest - pad, lead + pad, h_lead))
    # the zone's ends are foci too, so that the elements grow from them by the ratio
    foci = [zone[0], trail, zone[1], lead]
    x = graded_coordinates(-length, length, foci, [h_trail] * 3 + [h_lead], ratio=ratio, caps=caps)
    y = graded_coordinates(-length, 0.0, [0.0], [h_lead], ratio=ratio)
    mesh = half_space_boundaries(x, y)
    return HalfSpaceMesh(mesh, x, y, float(min(h_lead, h_edge)), (float(x[0]), float(x[-1])), float(-y[0]))


def graded_quadtree(edges, material, speed, *, resolution, length, ratio=1.25, layer_floor=0.01, coarsen=1.0):
    """A :class:`~fem_reference.quadtree.QuadtreeMesh` graded toward the contact ``edges`` in both
    directions (parameters as :func:`graded_half_space`)."""
    from .quadtree import quadtree_half_space

    trail, lead = edges
    h_edge, thinnest, h_lead, resolved = _layer_sizes(edges, material, speed, resolution, layer_floor)
    h_edge, h_lead = coarsen * h_edge, coarsen * h_lead
    h_zone = h_edge / LAYER_ELEMENTS
    # each edge gets LAYER_ELEMENTS elements across a zone one edge element wide about it (as the
    # trailing edge of graded_half_space): squares do not put a node on the edge
    segments = [(trail, lead, h_edge), (lead, lead, h_lead)]
    segments += [(e - 0.5 * h_edge, e + 0.5 * h_edge, h_zone) for e in (trail, lead)]
    if resolved:
        pad = 0.5 * LAYER_ELEMENTS * h_lead
        segments.append((lead - thinnest - pad, lead + pad, h_lead))
    return quadtree_half_space(segments, length=length, ratio=ratio)
