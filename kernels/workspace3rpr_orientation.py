"""The 3-RPR's piece test over a range of orientations (the 3-RRR's paving of
:mod:`kernels.workspace_orientation` with ``mechanism = RPR``).

Leg ``i`` closes at :math:`(p, \\varphi)` iff :math:`lo_i \\le d_i(p, \\varphi) = |p +
R(\\varphi) q_i - A_i| \\le hi_i` (:mod:`kernels.workspace3rpr`). **Enclosure over a box and a
piece.** For an (x, y) box :math:`X` and a piece :math:`[m - h, m + h]` (:math:`h \\le \\pi`)
write :math:`c_i(m) = A_i - R(m) q_i`; then :math:`p + R(\\varphi) q_i - A_i = (p - c_i(m))
+ (R(\\varphi) - R(m)) q_i` and :math:`|(R(\\varphi) - R(m)) q_i| = 2 |q_i| \\sin(|\\varphi -
m| / 2) \\le 2 |q_i| \\sin(h / 2) =: \\delta_i` (the chord of the arc), so by the triangle
inequality

.. math:: d_i(p, \\varphi) \\in [|p - c_i(m)| - \\delta_i,\\ |p - c_i(m)| + \\delta_i]
          \\subseteq [D_{lo} - \\delta_i,\\ D_{hi} + \\delta_i]
          \\quad \\forall p \\in X,\\ |\\varphi - m| \\le h,

with :math:`[D_{lo}, D_{hi}]` the exact range of :math:`|p - c_i(m)|` over :math:`X` (its
square enclosed by :func:`kernels.workspace3rpr.squared_distance_range`). Over
:math:`X \\times [m - h, m + h]` leg ``i`` is therefore

* ``OUT`` (fails everywhere) if :math:`D_{hi} < lo_i - \\delta_i` or :math:`D_{lo} > hi_i +
  \\delta_i`,
* ``IN`` (closes everywhere) if :math:`[D_{lo}, D_{hi}] \\subseteq [lo_i + \\delta_i, hi_i -
  \\delta_i]`,

which is :func:`kernels.workspace3rpr.leg_label` with the thresholds ``out = (max(0, lo -
δ), hi + δ)``, ``in = (lo + δ, max(0, hi - δ))`` (compared on squares rounded outward; with
``hi - δ < 0`` nothing is ``IN``: ``slo >= (lo + δ)² >= δ² > 0 = in_hi²``). The piece is
*all in* when every leg is ``IN``, *out* when one leg is ``OUT``; the box classification from
the pieces (maximal, total) is :func:`kernels.workspace_orientation.classify_box_range`'s.

**Rounding.** Over a piece (``h > 0``) :math:`\\delta_i` is enlarged by ``TOLERANCE_CM``
(1e-9 cm), far above the round-off of the chord, of :math:`c_i(m)`'s cos/sin and of the
threshold sums at robot scale (about 1e-14 cm at 100 cm). At a point orientation (``h = 0``,
a degenerate range or the midpoint tests) :math:`\\delta = 0` and :math:`c_i(m)` is computed by
the same float formula as :meth:`planar_tui.workspace.rpr.Robot3RPR.centres_cm`: the test is
then the constant-orientation job's (:func:`kernels.workspace3rpr.classify_rpr_box`) bit for
bit, trusting the same cos/sin.

Geometry vector ``g`` (the 3-RRR's layout, :func:`planar_tui.workspace.rpr_orientation.
geometry_vector`): ``[0, 0, qx1, qy1, qx2, qy2, qx3, qy3, ax1, ay1, ax2, ay2, ax3, ay3]``
(cm); ``limits`` the (3, 2) leg limits ``[lo, hi]`` (cm).
"""

import math

from ._jit import kernel
from .workspace3rpr import leg_label, squared_distance_range
from .workspace_arc import INSIDE, OUTSIDE, TOLERANCE_CM

#: Piece verdicts (the values of :mod:`kernels.workspace_orientation`'s ``PIECE_*``).
PIECE_OUT = 0
PIECE_UNKNOWN = 1
PIECE_IN = 2


@kernel
def rpr_piece_status(xlo, xhi, ylo, yhi, phi_mid, phi_half, g, limits):
    """``PIECE_IN``, ``PIECE_OUT`` or ``PIECE_UNKNOWN`` of the 3-RPR over the box and the
    orientations ``[phi_mid - phi_half, phi_mid + phi_half]`` (module docstring)."""
    c = math.cos(phi_mid)
    s = math.sin(phi_mid)
    chord = 2.0 * math.sin(0.5 * min(phi_half, math.pi)) if phi_half > 0.0 else 0.0
    all_in = True
    for leg in range(3):
        qx = g[2 + 2 * leg]
        qy = g[3 + 2 * leg]
        delta = chord * math.hypot(qx, qy) + TOLERANCE_CM if phi_half > 0.0 else 0.0
        cx = g[8 + 2 * leg] - (c * qx - s * qy)
        cy = g[9 + 2 * leg] - (s * qx + c * qy)
        slo, shi = squared_distance_range(xlo, xhi, ylo, yhi, cx, cy)
        lo = limits[leg, 0]
        hi = limits[leg, 1]
        label = leg_label(
            slo, shi, max(0.0, lo - delta), hi + delta, lo + delta, max(0.0, hi - delta)
        )
        if label == OUTSIDE:
            return PIECE_OUT
        all_in = all_in and label == INSIDE
    return PIECE_IN if all_in else PIECE_UNKNOWN
