"""What a workspace job of the 3-RPR, 3-PRR and five-bar kinds will ask for, before it runs:
its processed boxes, memory and computing time (the kinds' ``estimate`` hook, held against
:mod:`planar_tui.limits` when the job is read, and summed by sweeps and optimisations,
:mod:`planar_tui.sweep.budget`, :mod:`planar_tui.optimise.budget`).

These kinds pave (x, y) boxes with an exact per-leg test: a box proved inside or outside is
never split, so the paving refines the workspace's boundary only. Its processed boxes grow
with the boundary length :math:`L` (of the outer polygon of the exact workspace, 32
segments per turn: a few ms) over the precision:

.. math::

    N \\approx c_b \\frac{L}{\\varepsilon} + c_b \\frac{L}{\\varepsilon_r}
      + c_t \\frac{L\\,t}{\\varepsilon^2} + c_s \\frac{w + h}{\\varepsilon_s} + N_0,

with the boundary refinement at :math:`\\varepsilon_r` (``refine_precision_cm``, if any), a
tolerance :math:`t` (the largest half-width; the band of width about :math:`2t` about the
boundary where the robots within the tolerances disagree is paved down to
:math:`\\varepsilon`), the singularity paving of the search box (width :math:`w`, height
:math:`h`) at :math:`\\varepsilon_s` (the singular curves' length is not known before it
runs, so the search box's size stands for it) and :data:`MIN_BOXES` for the levels
above the boundary. The constants were measured on the bundled designs
(``presets/workspace-3rpr.toml``, ``workspace-3prr.toml``, ``fivebar-illustrative.toml``)
at ε = 0.02 to 1 cm: :math:`c_b` observed 6.4 to 10.6, :math:`c_t` 3 to 4 (3-PRR "some":
14 to 15), :math:`c_s` 4.6 to 8.7 (3-PRR), 19 to 20.5 (five-bar, with its circle), and
far fewer for the 3-RPR (its singular curve mostly outside the workspace). Memory is
:data:`~planar_tui.workspace.paving.settings.BYTES_PER_BOX` a box (as ``box_budget`` is checked),
time :data:`SECONDS_PER_BOX` a box (measured 1.7 to 9.3 µs on a busy 2-core machine) and
:data:`JOB_SECONDS` for the exact reference and the rest. Rough, like every estimate of
:mod:`planar_tui.limits`: the paving's count within a factor 2 on the bundled designs
(``tests/test_workspace_estimate.py``), meant to refuse what cannot finish.
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

from planar_tui.limits import memory_problem, time_problem
from planar_tui.workspace.paving.settings import BYTES_PER_BOX

if TYPE_CHECKING:
    from planar_tui.reader import TableReader

#: Processed boxes per ε of the workspace's boundary length (observed 6.4-10.6).
BOXES_PER_BOUNDARY_STEP = 10.0
#: Processed boxes per ε² of boundary length × tolerance of a mode its robot's
#: :class:`~planar_tui.workspace.paving.mechanism.Mechanism` has no constant for (its
#: ``tolerance_boxes``; the singularity boxes are its ``singular_boxes_per_step``).
TOLERANCE_BOXES = 16.0
#: Boxes of the levels above the boundary, of an empty workspace.
MIN_BOXES = 64
#: Computing time of one processed box (s).
SECONDS_PER_BOX = 5e-6
#: Computing time of one job besides its boxes (s): the exact reference, the polygons.
JOB_SECONDS = 0.5
#: What a job over the limits is asked to change.
COARSER = "a coarser precision_cm (and refine_precision_cm, singularity_precision_cm)"
#: Segments per turn of the polygon whose length is the boundary's.
SEGMENTS_PER_TURN = 32


def _geometry(kind: str, robot: Any, spec: Any) -> tuple[float, tuple[float, ...]]:
    """The boundary length :math:`L` (cm) and the search box ``(x_lo, x_hi, y_lo, y_hi)``
    the job paves."""
    from shapely.errors import GEOSException

    from planar_tui.workspace.paving.levels import square_about

    mechanism = spec.mechanism
    reach = mechanism.reach_box(robot, spec)
    box = spec.search_box_cm or square_about(reach, spec.precision_cm)
    xlo, xhi, ylo, yhi = box[0][0], box[0][1], box[1][0], box[1][1]
    try:
        with warnings.catch_warnings():  # infinite coordinates (legs near 1e200 cm): capped
            warnings.simplefilter("ignore", RuntimeWarning)
            length = float(mechanism.polygon(robot, spec, SEGMENTS_PER_TURN, True).length)
    except GEOSException:  # GEOS cannot node it (lengths near 1e199 cm): the box's perimeter
        length = 2.0 * ((xhi - xlo) + (yhi - ylo))
    return length, (xlo, xhi, ylo, yhi)


def largest_tolerance_cm(spec: Any) -> tuple[float, str] | None:
    """The largest half-width of the job's tolerance and its mode (``None`` without)."""
    uniform = getattr(spec, "tolerance_cm", None)
    table = getattr(spec, "tolerances_cm", None)
    if uniform is None and table is None:
        return None
    widths = [uniform or 0.0, *(width for _, width in table or ())]
    return max(widths), getattr(spec, "tolerance_mode", None) or "all"


#: The most boxes an estimate names (far beyond any limit): a geometry whose outline is
#: infinite or NaN (every leg limit near 1e200 cm) is refused by the limits, not by an
#: overflow.
MAX_ESTIMATED_BOXES = 1e18


def estimate_boxes(kind: str, robot: Any, spec: Any) -> int:
    """About how many boxes the job of kind ``kind`` processes (module docstring; 0 for the
    ``geometric`` form)."""
    if spec.form == "geometric":
        return 0
    length, (xlo, xhi, ylo, yhi) = _geometry(kind, robot, spec)
    eps = spec.precision_cm
    boxes = BOXES_PER_BOUNDARY_STEP * length / eps
    if spec.refine_precision_cm is not None:
        boxes += BOXES_PER_BOUNDARY_STEP * length / spec.refine_precision_cm
    tolerance = largest_tolerance_cm(spec)
    if tolerance is not None:  # the job's paving and its figure's: the nominal, the other mode
        width, mode = tolerance
        other = "some" if mode == "all" else "all"
        band = sum(spec.mechanism.tolerance_boxes.get(m, TOLERANCE_BOXES) for m in (mode, other))
        boxes = 3.0 * boxes + band * length * width / (eps * eps)
    if spec.singularities:
        precision = spec.singularity_precision_cm or eps
        per_step = spec.mechanism.singular_boxes_per_step
        boxes += per_step * ((xhi - xlo) + (yhi - ylo)) / precision
    if not boxes < MAX_ESTIMATED_BOXES:  # infinite or NaN (leg limits of 1e300 cm): capped
        boxes = MAX_ESTIMATED_BOXES
    return math.ceil(boxes) + MIN_BOXES


def needs(kind: str, robot: Any, spec: Any) -> tuple[int, float, float]:
    """``(boxes, memory_bytes, seconds)`` of a job (module docstring)."""
    boxes = estimate_boxes(kind, robot, spec)
    return boxes, float(boxes) * BYTES_PER_BOX, JOB_SECONDS + boxes * SECONDS_PER_BOX


def report_box_estimate(job: Any, progress: Any) -> int:
    """Put the job's box estimate in the progress figures (``boxes_estimate``), with a
    warning when it exceeds ``box_budget``, as the 3-RRR's
    (:func:`~planar_tui.workspace.paving.levels.report_boxes`)."""
    from planar_tui.workspace.paving.levels import report_boxes

    return report_boxes(estimate_boxes(job.kind, job.robot, job.spec), job.spec, progress)


def estimate(job: Any) -> tuple[float, float]:
    """The kinds' ``estimate`` hook: ``(memory_bytes, seconds)`` of ``job``."""
    _, memory, seconds = needs(job.kind, job.robot, job.spec)
    return memory, seconds


def count_text(count: int) -> str:
    """``48,475`` or, from a trillion, ``2.62e+12``: a box count for messages."""
    return f"{count:,}" if count < 10**12 else f"{count:.3g}"


def check_needs(kind: str, spec: Any, reader: TableReader, robot: Any) -> None:
    """Refuse a job whose estimated memory or time exceeds :mod:`planar_tui.limits`
    (:class:`~planar_tui.errors.PresetError` on ``precision_cm``, or ``command line:
    --precision`` when the option set it; one line with the estimate)."""
    boxes, memory, seconds = needs(kind, robot, spec)
    problem = memory_problem(memory) or time_problem(seconds) or budget_problem(boxes, spec)
    if problem is not None:
        found = f"is {spec.precision_cm:g} cm: about {count_text(boxes)} boxes, {problem}"
        raise reader.error("precision_cm", found, COARSER)


#: How many times ``box_budget`` an estimate may name before the job is refused up front:
#: the estimate is within a factor 2 on the bundled designs, so a job estimated past 4
#: times its budget would only stop at the budget, minutes later, with nothing written.
BUDGET_FACTOR = 4


def budget_problem(boxes: int, spec: Any) -> str | None:
    """``more than 4 × box_budget = …: it would stop at its budget`` when the estimate
    exceeds :data:`BUDGET_FACTOR` times the job's ``box_budget``, else ``None``."""
    budget = spec.box_budget
    if boxes <= BUDGET_FACTOR * budget:
        return None
    return (
        f"more than {BUDGET_FACTOR} × box_budget = {count_text(budget)}: it would stop at "
        "its budget with nothing written"
    )
