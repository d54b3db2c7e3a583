"""Tolerance-certified five-bar workspaces: the exact leg-wise test of
:mod:`kernels.workspace5r` with interval parameters (derivation and bound in
:mod:`planar_tui.workspace.fivebar.tolerance`).

Every robot within the tolerances has, per leg and independently, the base joint
:math:`A_i + a` (:math:`|a_x|, |a_y| \\le t_A`), the proximal :math:`l_1 + \\tau`
(:math:`|\\tau| \\le t_1`) and the distal :math:`l_2 + \\kappa` (:math:`|\\kappa| \\le t_2`);
the joint limits and the working mode are exact. ``tol`` is the 3-RRR's tolerance vector
(:func:`kernels.workspace_tolerance.tolerance_vector`) with :math:`t_q = 0` and
:math:`\\varphi = 0` (the five-bar's "platform" is the point :math:`P` itself), so
:func:`~kernels.workspace_tolerance.shift_bound` is :math:`\\sigma = \\sqrt2\\,t_A + t_1`,
the most a leg's :math:`D_{\\min}`, :math:`D_{\\max}` (distances from :math:`P - A_i` to the
proximal arc) move over the tolerances.

Per leg, over the box of centre :math:`c` and half-diagonal :math:`\\rho` (plus
``TOLERANCE_CM``):

* **any branch** (``sigma = 0``): the 3-RRR's certificates with one leg
  (:mod:`kernels.workspace_tolerance`): ``ALL``-inside by the Lipschitz bound
  :math:`d_{\\min} + \\rho + \\sigma \\le l_2 - t_2`, :math:`d_{\\max} - \\rho - \\sigma \\ge
  l_2 + t_2` or the first-order one; ``ALL``-outside by one vertex robot missing the box;
  ``SOME``-outside when :math:`d_{\\min} - \\rho - \\sigma > l_2 + t_2` or :math:`d_{\\max} +
  \\rho + \\sigma < l_2 - t_2`; ``SOME``-inside by one vertex robot reaching the box.
* **one working mode** (``sigma = ±1``): first the any-branch *outside* tests above (the
  mode's region lies in the any-branch one). Then, if the nominal centre is within
  :math:`\\rho` of the four arcs holding the boundary of :math:`R_\\sigma`
  (:func:`kernels.workspace5r.near_mode_boundary`), ``BOUNDARY``; else the nominal robot
  labels the whole box as it labels :math:`c`, which settles the existential claims
  (``ALL``-outside: the nominal robot misses the box; ``SOME``-inside: it reaches it). The
  universal ones (``ALL``-inside, ``SOME``-outside) need every robot's four arcs farther
  than :math:`\\rho` from the centre (:func:`robots_near_mode_boundary`), proved arc by arc
  either by the nominal arc farther than :math:`\\rho + h`, :math:`h = \\sigma + t_2`
  (:func:`boundary_shift`; each of a robot's arcs lies within :math:`h` of the nominal one,
  point by point) or by the per-direction circle bound (each robot's outer and inner arcs
  lie on circles of centre :math:`A + a` and radius :math:`|l_1 \\pm l_2|` moved by at
  most :math:`t_1 + t_2`, its elbow arcs on circles about the nominal elbow moved by
  :math:`a` and at most :math:`t_1`, radius :math:`l_2` moved by at most :math:`t_2`; the
  distance from the centre to every such circle is bounded below through the exact nearest
  and farthest points of the square of :math:`a`:
  :func:`kernels.workspace5r.circle_family_far`, which moves a circle by
  :math:`t_A (|\\cos\\theta| + |\\sin\\theta|) + t_1 + t_2` in the direction
  :math:`\\theta` from its centre instead of :math:`h`); then no robot's boundary meets the
  box, so every robot labels every point as the nominal robot labels :math:`c`.
  Otherwise, on a box of any size, the 16 vertex robots are tried for the existential
  claim with the same exact test on each robot (:func:`vertex_mode_label`); else
  ``BOUNDARY``. The vertex robots' boundaries are the extreme ones: each point of a
  boundary arc moves by a linear function of :math:`(a, \\tau, \\kappa)` along the arc's
  normal (the outer arc by :math:`a \\cdot e(\\theta) + \\tau + \\kappa`, the inner by
  :math:`a \\cdot e(\\theta) + \\tau - \\kappa`, an elbow arc by :math:`a \\cdot n + \\tau\\,
  e(\\theta_\\pm) \\cdot n + \\kappa`), extreme at a vertex; so the band between the nominal
  boundary and the nominal one shifted by :math:`h`, where the true robust (or "some")
  boundary lies, is decided on boxes as wide as the band instead of leaf by leaf (issue
  25: the robust paving of mode ``+-`` at ±1 mm processed 2.4x the nominal paving's boxes,
  "some" 3.9x; now 1.18x and 1.25x with the per-direction bound above). The search is skipped (``BOUNDARY``, always sound)
  where no robot can decide: the centre within :math:`\\rho - h` of the nominal arcs (each
  robot's arcs then come within :math:`\\rho` of it), or the nominal robot labelling the box
  against the claim with its arcs farther than :math:`h - \\rho` (no robot's arcs pass the
  box; a pruning only: its failure costs boxes, never soundness).

At zero tolerance every test is :func:`kernels.workspace5r.leg_label`'s: the same boxes.
"""

import math

import numba

from ._jit import kernel
from .interval import up
from .workspace5r import (
    BOUNDARY,
    INSIDE,
    OUTSIDE,
    classify_box,
    leg_at,
    mode_point_in,
    near_mode_arcs,
    near_mode_boundary,
)
from .workspace_arc import LANES, TOLERANCE_CM, arc_distance_range, settle_xy_box
from .workspace_tolerance import (
    ALL,
    MODE,
    NOMINAL,
    T_BASE,
    T_DISTAL,
    T_PROXIMAL,
    VERTEX_SHRINK,
    _leg_proved_by_vertex,
    _leg_refuted_by_vertex,
    robust_range,
    shift_bound,
)


@kernel
def boundary_shift(tol):
    """:math:`h = \\sqrt2\\,t_A + t_1 + t_2`, rounded up: the most any point of a boundary arc
    of a leg's mode region moves over the tolerances."""
    return up(shift_bound(tol) + tol[T_DISTAL])


@kernel
def vertex_mode_label(px, py, rho, legs, leg, tlo, thi, tol, robust):
    """A mode leg's existential certificate by the 16 vertex robots (every sign of
    :math:`a_x, a_y, \\tau, \\kappa`, times ``VERTEX_SHRINK``): ``OUTSIDE`` if one misses
    the whole box (``robust``), ``INSIDE`` if one reaches it (else), by the nominal mode
    test on that robot (:func:`kernels.workspace5r.near_mode_arcs`, its elbows scaled by
    :math:`(l_1 + \\tau) / l_1`); else ``BOUNDARY``."""
    want = OUTSIDE if robust else INSIDE
    t_a = VERTEX_SHRINK * tol[T_BASE]
    t_1 = VERTEX_SHRINK * tol[T_PROXIMAL]
    t_2 = VERTEX_SHRINK * tol[T_DISTAL]
    if t_a == 0.0 and t_1 == 0.0 and t_2 == 0.0:
        return BOUNDARY  # the nominal robot was tried
    sigma = legs[leg, 4]
    for k in range(16):
        qx = px - (t_a if k & 1 else -t_a)  # P - (A + a)
        qy = py - (t_a if k & 2 else -t_a)
        l1 = legs[leg, 2] + (t_1 if k & 4 else -t_1)
        l2 = legs[leg, 3] + (t_2 if k & 8 else -t_2)
        scale = l1 / legs[leg, 2]
        lo_x, lo_y = scale * legs[leg, 5], scale * legs[leg, 6]
        hi_x, hi_y = scale * legs[leg, 7], scale * legs[leg, 8]
        if mode_point_in(qx, qy, l1, l2, tlo, thi, sigma) != (want == INSIDE):
            continue
        nominal = (0.0, 0.0, 0.0)  # this robot alone
        if not near_mode_arcs(
            qx, qy, rho, l1, l2, sigma, lo_x, lo_y, hi_x, hi_y, tlo, thi, nominal
        ):
            return want
    return BOUNDARY


@kernel
def robots_near_mode_boundary(px, py, rho, h, legs, leg, tlo, thi, tol):
    """:func:`kernels.workspace5r.near_mode_arcs` of leg ``leg`` for every robot within the
    tolerances: False proves that no robot's boundary arc comes within ``rho`` of ``p``,
    arc by arc by the isotropic :math:`h` or the per-direction circle bound
    (:func:`kernels.workspace5r.circle_family_far`)."""
    family = (h, tol[T_BASE], tol[T_PROXIMAL] + tol[T_DISTAL])
    return near_mode_arcs(
        px,
        py,
        rho,
        legs[leg, 2],
        legs[leg, 3],
        legs[leg, 4],
        legs[leg, 5],
        legs[leg, 6],
        legs[leg, 7],
        legs[leg, 8],
        tlo,
        thi,
        family,
    )


@kernel
def tolerant_leg_label(cx, cy, rho, legs, limits, leg, tol, sigma, h):
    """``OUTSIDE``, ``BOUNDARY`` or ``INSIDE`` of one leg over the box about ``(cx, cy)`` of
    half-diagonal ``rho`` for the mode in ``tol`` (module docstring; ``sigma`` and ``h`` are
    :func:`~kernels.workspace_tolerance.shift_bound` and :func:`boundary_shift`)."""
    px, py, l1, l2, tlo, thi = leg_at(cx, cy, legs, limits, leg)
    t2 = tol[T_DISTAL]
    dmin, dmax = arc_distance_range(px, py, l1, tlo, thi)
    robust = tol[MODE] == ALL
    if robust:
        if _leg_refuted_by_vertex(px, py, l1, l2, tlo, thi, dmin, dmax, rho, sigma, tol):
            return OUTSIDE
    elif dmin - rho - sigma > l2 + t2 or dmax + rho + sigma < l2 - t2:
        return OUTSIDE
    if legs[leg, 4] != 0.0:
        if not near_mode_boundary(px, py, rho, legs, leg, tlo, thi):
            inside = mode_point_in(px, py, l1, l2, tlo, thi, legs[leg, 4])
            if inside != robust or not robots_near_mode_boundary(
                px, py, rho, h, legs, leg, tlo, thi, tol
            ):
                return INSIDE if inside else OUTSIDE  # the nominal robot, or every one (h)
            if rho >= h or not near_mode_boundary(px, py, h - rho, legs, leg, tlo, thi):
                return BOUNDARY  # no robot's arcs pass the box (pruning only)
        elif rho > h and near_mode_boundary(px, py, rho - h, legs, leg, tlo, thi):
            return BOUNDARY  # every robot's arcs come within rho of the centre
        return vertex_mode_label(px, py, rho, legs, leg, tlo, thi, tol, robust)
    if robust:
        if dmin + rho + sigma <= l2 - t2 and dmax - rho - sigma >= l2 + t2:
            return INSIDE  # the Lipschitz bound (looser than robust_range's)
        dmin_hi, dmax_lo = robust_range(px, py, l1, tlo, thi, dmin, dmax, sigma, tol)
        return INSIDE if dmin_hi + rho <= l2 - t2 and dmax_lo - rho >= l2 + t2 else BOUNDARY
    if _leg_proved_by_vertex(px, py, l1, l2, tlo, thi, dmin, dmax, rho, tol):
        return INSIDE
    return BOUNDARY


@kernel
def tolerant_classify_box(xlo, xhi, ylo, yhi, legs, limits, tol):
    """``OUTSIDE`` (some leg out), ``INSIDE`` (both in) or ``BOUNDARY`` for the box and the
    mode in ``tol`` (``NOMINAL``: :func:`kernels.workspace5r.classify_box`)."""
    if tol[MODE] == NOMINAL:
        return classify_box(xlo, xhi, ylo, yhi, legs, limits)
    cx = 0.5 * (xlo + xhi)
    cy = 0.5 * (ylo + yhi)
    rho = 0.5 * math.hypot(xhi - xlo, yhi - ylo) + TOLERANCE_CM
    sigma = shift_bound(tol)
    h = boundary_shift(tol)
    first = tolerant_leg_label(cx, cy, rho, legs, limits, 0, tol, sigma, h)
    if first == OUTSIDE:
        return OUTSIDE
    return min(first, tolerant_leg_label(cx, cy, rho, legs, limits, 1, tol, sigma, h))


@kernel(parallel=True)
def tolerant_level(legs, limits, tol, precision, rows, start, stop, children, outcome):
    """:func:`kernels.workspace5r.level` with :func:`tolerant_classify_box`: rows ``start ..
    stop - 1`` in parallel, each box's outcome its own (thread-count invariant)."""
    n = stop - start
    for lane in numba.prange(min(LANES, n)):
        for i in range(lane, n, min(LANES, n)):
            box = rows[start + i]
            label = tolerant_classify_box(box[0], box[1], box[2], box[3], legs, limits, tol)
            outcome[i] = settle_xy_box(label, rows, start + i, children, 2 * i, precision)


__all__ = ["BOUNDARY", "INSIDE", "OUTSIDE", "boundary_shift", "tolerant_level"]
