"""Tolerance-certified five-bar workspaces (issue 25, item 2; the interface of
:mod:`planar_tui.workspace.paving.tolerance`, the kernel :mod:`planar_tui.kernels.workspace5r_tolerance`).

**Parameters as intervals.** Every robot within the tolerances has, per leg and
independently (each leg's parts are made separately), the base joint :math:`A_i + a`
(:math:`|a_x|, |a_y| \\le t_A`, ``base_joints_cm``: this covers the base separation), the
proximal :math:`l_{1,i} + \\tau` (:math:`|\\tau| \\le t_1`, ``proximal_cm``) and the distal
:math:`l_{2,i} + \\kappa` (:math:`|\\kappa| \\le t_2`, ``distal_cm``); the joint limits and
the working mode are exact. Leg ``i`` of that robot reaches :math:`P` iff

.. math:: D_{\\min}(P - A_i - a;\\, l_1 + \\tau) \\le l_2 + \\kappa \\le
          D_{\\max}(P - A_i - a;\\, l_1 + \\tau)

(any branch; :math:`D` the distances to the proximal arc, :mod:`kernels.workspace_arc`), and
in a working mode iff moreover :math:`P` lies in the mode's region :math:`R_\\sigma`, whose
boundary lies on four arcs (:mod:`planar_tui.workspace.fivebar.robot`).

**Bounds.** :math:`D_{\\min}, D_{\\max}` are 1-Lipschitz in the point and in :math:`l_1`, so
over the parameter box they move by at most :math:`\\sigma = \\sqrt2\\,t_A + t_1`; the distal
by :math:`t_2`. Each of the four arcs of a robot's :math:`R_\\sigma` is, point by point
(same angle), within

.. math:: h = \\sqrt2\\,t_A + t_1 + t_2

of the nominal one: the outer arc :math:`A + (l_1 + l_2) e(\\theta)`, the inner arc
:math:`A + (l_1 - l_2) e(\\theta)` (a signed radius), the arcs :math:`A + l_1 e(\\theta_\\pm) +
l_2 e(\\psi)` about the elbows at the joint limits. So a box whose centre :math:`c` is
farther than :math:`\\rho + h` from the nominal arcs meets no robot's boundary, and
:math:`B \\times \\Pi` being connected, every robot labels every point as the nominal robot
labels :math:`c` (the label changes only across a boundary). Per direction, an arc is also
proved far when every circle it may lie on is: centre :math:`A + a` (an elbow arc's: the
nominal elbow plus :math:`a` and at most :math:`t_1`), radius within :math:`t_1 + t_2` of
the nominal; with :math:`n, f` the exact nearest and farthest distances from :math:`q = c -`
centre to the square of :math:`a`, when :math:`n - (r + t_1 + t_2) > \\rho` or
:math:`\\max(0, r - t_1 - t_2) - f > \\rho`
(:func:`~planar_tui.kernels.workspace5r.circle_family_far`: a shift of :math:`t_A (|\\cos
\\theta| + |\\sin\\theta|) + t_1 + t_2` in the direction :math:`\\theta`, not :math:`h`).

**Certificates** (per leg, :math:`d` at the box centre, :math:`\\rho` its half-diagonal;
details in the kernel's docstring): ``all`` (robust) inside iff every leg has
:math:`d_{\\min} + \\rho + \\sigma \\le l_2 - t_2` and :math:`d_{\\max} - \\rho - \\sigma \\ge l_2
+ t_2` (or the 3-RRR's first-order bound) and, in a mode, the centre inside and every robot's arcs proved farther than
:math:`\\rho` (by :math:`\\rho + h` or per direction); ``all`` outside when one vertex robot (or, in a mode, the
nominal robot, or one of the 16 vertex robots) misses the box; ``some`` outside when :math:`d_{\\min} - \\rho - \\sigma > l_2
+ t_2` or :math:`d_{\\max} + \\rho + \\sigma < l_2 - t_2`, or in a mode the centre is outside,
every robot's arcs proved farther than :math:`\\rho`; ``some`` inside when one vertex robot (in a
mode, the nominal robot or a vertex robot) reaches the box (the legs' parameters are independent, so one
robot serves both legs).

**Bound** (:func:`erosion_bound_cm`, :math:`B = h = \\sqrt2\\,t_A + t_1 + t_2`): the robust
workspace contains the nominal workspace *eroded by* :math:`B`: the points where every
any-branch leg has :math:`d_{\\min} \\le l_2 - B` and :math:`d_{\\max} \\ge l_2 + B` (eroded
in constraint value, as the 3-RRR's) and every leg in a mode lies in :math:`R_\\sigma`
farther than :math:`B` from its four arcs (eroded metrically); the "some" workspace lies
in the nominal one dilated the same way. At zero tolerance the kernel's tests are the
nominal ones: the same boxes bit for bit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from planar_tui.workspace.paving.tolerance import (
    grown,
    kernel_tolerance,
    reach_margin_cm,
    tolerance_fields,
    tolerance_of,
)

if TYPE_CHECKING:
    import numpy as np

#: The five-bar's toleranced quantities (keys of ``tolerances_cm``).
TOLERANCE_KEYS_5R = ("base_joints_cm", "proximal_cm", "distal_cm")
#: The settings ``tolerance_cm``, ``tolerances_cm``, ``tolerance_mode`` of ``[[workspace5r]]``.
TOLERANCE_FIELDS_5R = tolerance_fields(
    TOLERANCE_KEYS_5R,
    "manufacturing tolerance ± on every base joint coordinate and link length (cm; the joint "
    "limits and the working mode are exact)",
)


def tolerant_vector5r(spec: Any) -> np.ndarray | None:
    """The kernel's ``tol`` of a five-bar spec with a tolerance (``None`` without one): the
    3-RRR's vector with no platform tolerance and :math:`\\varphi = 0`."""
    tolerance = tolerance_of(spec, TOLERANCE_KEYS_5R)
    return None if tolerance is None else kernel_tolerance(tolerance, 0.0)


def reach_box_cm(robot: Any, spec: Any) -> tuple[float, float, float, float]:
    r"""The robot's reach box grown by :func:`~planar_tui.workspace.paving.tolerance.reach_margin_cm`
    (a "some" workspace reaches up to :math:`\sqrt2\,t_A + t_1 + t_2` farther), so the
    search box holds it."""
    return grown(robot.reach_box_cm(), reach_margin_cm(spec))


def tolerant_level_kernel(spec: Any, nominal: Any) -> Any:
    """The level kernel of a spec: ``nominal`` (signature ``(legs, limits, precision, rows,
    start, stop, children, outcome)``) without a tolerance, else
    :func:`~planar_tui.kernels.workspace5r_tolerance.tolerant_level` with the spec's ``tol``
    bound in."""
    tol = tolerant_vector5r(spec)
    if tol is None:
        return nominal
    from planar_tui.kernels.workspace5r_tolerance import tolerant_level

    def level(legs, limits, precision, rows, start, stop, children, outcome):
        tolerant_level(legs, limits, tol, precision, rows, start, stop, children, outcome)

    return level


def check_search_box(values: dict[str, Any], reader: Any, robot: Any) -> None:
    """A "some" job's ``search_box_cm`` holds :func:`reach_box_cm` (one line, exit 2, if
    not)."""
    from types import SimpleNamespace

    spec = SimpleNamespace(**values, tolerance_keys=TOLERANCE_KEYS_5R)
    xlo, xhi, ylo, yhi = reach_box_cm(robot, spec)
    (bxlo, bxhi), (bylo, byhi) = values["search_box_cm"]
    if not (bxlo <= xlo and xhi <= bxhi and bylo <= ylo and yhi <= byhi):
        raise reader.error(
            "search_box_cm",
            'cannot contain the reach of the robots within the tolerances (tolerance_mode = "some")',
            f"a box containing x in [{xlo:.4g}, {xhi:.4g}], y in [{ylo:.4g}, {yhi:.4g}] cm",
        )
