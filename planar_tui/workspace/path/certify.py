r"""Certified paths: a path job with ``kappa_max`` proves its continuous path safe for every
:math:`t \in [0, T]`, not only at its samples, by interval evaluation over time intervals.

**The pose over a time interval.** The quintic :math:`s(\tau) = 10\tau^3 - 15\tau^4 +
6\tau^5` has :math:`s'(\tau) = 30\tau^2(1 - \tau)^2 \ge 0`: it is monotone on
:math:`[0, 1]`, so every pose coordinate :math:`X_j(t) = X_{0j} + (X_{1j} - X_{0j})
s(t/T)` is monotone in :math:`t` and, being continuous, takes over :math:`[t_0, t_1]`
exactly the values between :math:`X_j(t_0)` and :math:`X_j(t_1)`. The pose box of a time
interval is therefore the hull of its two end poses (:func:`pose_boxes`, widened by
``ROUND_RELATIVE`` for the floating-point evaluation of :math:`s`): an exact enclosure, not
an estimate, and a sub-interval's box lies inside its parent's.

**The box test** is the robot's (its mechanism's ``path_box_test``): per pose box a verdict
(*in*: every leg closes in the working mode within its joint or leg limits at every pose;
*out*: some leg does so at none, with the reason ``leg`` or ``joint_limit``) and a certified
enclosure of κ (:mod:`planar_tui.workspace.paving.dexterity`'s definition) over the box's
poses where the legs close. A pose is *valid* when every leg closes within its limits and
:math:`\kappa \le` ``kappa_max``.

**Bisection** (:func:`certify`), level by level: an interval whose box is *in* with
:math:`\kappa_{hi} \le` ``kappa_max`` is certified; one whose box is *out*, or *in* with
:math:`\kappa_{lo} >` ``kappa_max``, proves its start time fails; each undecided
interval's midpoint is also tested as a point (a proved failure there ends the search to
its right) and the interval halved, down to ``MIN_WIDTH_FRACTION`` of :math:`T`. With
:math:`t^*` the first time the path leaves the valid set and :math:`c` the end of the
certified prefix, :math:`c \le t^* \le t_f` for every proved failure time :math:`t_f`.
The verdict is ``yes`` when every interval is certified, ``no`` when a failure is proved
with :math:`t_f - c \le T/1000` (the undecided leaf's window is also probed at
``PROBE_POINTS`` points), else ``unknown`` (ε in time ran out, e.g. a path that only
touches the boundary): the path is then certified on :math:`[0, c]` and
``first_failure_hi_s`` is the earliest proved failure, if any.

**The largest κ along the path** (over :math:`[0, c]`, all of it when certified) is
bracketed: below by the κ enclosures' lower ends at tested valid points (a point's
κ enclosure holds its κ), above by the largest upper end over the certified intervals,
tightened by halving the intervals whose upper end is above the lower bound by more than
``PEAK_RELATIVE`` (at most ``PEAK_ROUNDS`` rounds).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.csvio import CsvTable
from planar_tui.schema import number, setting

if TYPE_CHECKING:
    import numpy as np

#: The box test's verdicts (as :mod:`planar_tui.kernels.dexterity`'s) and its reasons.
OUT, UNSURE, IN = 0, 1, 2
REASONS = {1: "leg", 2: "joint_limit", 3: "interference"}
INTERFERENCE = 3
KAPPA = "kappa"
#: The narrowest time interval bisected, as a fraction of T.
MIN_WIDTH_FRACTION = 2.0**-24
#: The first failure's bracket width goal, as a fraction of T.
WINDOW_FRACTION = 1e-3
#: Points probed in the window after the certified prefix.
PROBE_POINTS = 64
#: Most pose boxes tested in one certificate (then ``unknown``).
MAX_BOXES = 4_000_000
#: Relative widening of a pose box for the floating-point evaluation of the quintic.
ROUND_RELATIVE = 1e-13
#: The κ peak's bracket goal (relative) and its most refinement rounds.
PEAK_RELATIVE = 1e-3
PEAK_ROUNDS = 40
PEAK_BATCH = 256

#: The certificate CSV's columns.
HEADER = (
    "certified",
    "first_failure_lo_s",
    "first_failure_hi_s",
    "reason",
    "kappa_max",
    "kappa_peak_lo",
    "kappa_peak_hi",
    "boxes_tested",
)

BoxTest = Callable[["np.ndarray"], tuple["np.ndarray", "np.ndarray", "np.ndarray"]]


def kappa_setting() -> Any:
    """``kappa_max``: the bound on κ a certified path keeps (> 1)."""
    return setting(
        number(positive=True),
        default=None,
        default_doc="(no certificate)",
        type_doc="number > 1",
        doc="certify the continuous path: legs closed within limits and κ ≤ kappa_max for "
        "every t in [0, T]; writes OUTPUT-certificate.csv (docs/certified-paths.md)",
    )


def check_certificate(values: dict[str, Any], reader: Any) -> None:
    """``kappa_max`` is above 1; ``characteristic_length_cm`` and ``leg_width_cm`` go with
    it."""
    kappa = values.get("kappa_max")
    if kappa is None:
        for name in ("characteristic_length_cm", "leg_width_cm"):
            if values.get(name) is not None:
                raise reader.error(name, "is set without kappa_max", "kappa_max")
        return
    if not kappa > 1.0:
        raise reader.error("kappa_max", f"is {kappa:g}: κ is at least 1", "a number > 1")


def certificate_outputs(job: Any) -> dict[str, str]:
    """With ``kappa_max``: the certificate beside the job's CSV (``-certificate.csv``)."""
    if getattr(job.spec, "kappa_max", None) is None:
        return {}
    stem = job.output[:-4] if job.output.lower().endswith(".csv") else job.output
    return {"certificate": f"{stem}-certificate.csv"}


@dataclass(frozen=True)
class Certificate:
    """A path's certificate (module docstring): the verdict, the first failure's bracket
    (``None``: none), its reason, the bound and the largest κ's bracket on the certified
    part, and the pose boxes tested."""

    certified: str
    failure_lo_s: float | None
    failure_hi_s: float | None
    reason: str
    kappa_max: float
    kappa_peak_lo: float
    kappa_peak_hi: float
    boxes_tested: int

    def table(self) -> CsvTable:
        """The one-row certificate CSV (:data:`HEADER`; an unbounded κ is empty)."""
        peak = [v if math.isfinite(v) else None for v in (self.kappa_peak_lo, self.kappa_peak_hi)]
        row = [
            self.certified,
            self.failure_lo_s,
            self.failure_hi_s,
            self.reason,
            self.kappa_max,
            *peak,
            self.boxes_tested,
        ]
        return CsvTable(HEADER, [row])

    def describe(self) -> str:
        """``certified yes, max κ in [2.1, 2.11]`` or the failure's bracket and reason."""
        peak = f"max κ in [{self.kappa_peak_lo:.4g}, {self.kappa_peak_hi:.4g}]"
        if math.isnan(self.kappa_peak_hi):
            peak = "no certified part"
        if self.certified == "yes":
            return f"certified yes (κ ≤ {self.kappa_max:g}), {peak}"
        hi = "?" if self.failure_hi_s is None else f"{self.failure_hi_s:.6g}"
        return (
            f"certified {self.certified}: first failure in [{self.failure_lo_s:.6g}, {hi}] s"
            f" ({self.reason or 'not proved'}), {peak} before it"
        )


def box_test(kernel: Callable[..., None], *inputs: Any) -> BoxTest:
    """The :data:`BoxTest` of a robot's pose-box kernel ``kernel(boxes, *inputs, verdict,
    reason, kappa)`` (e.g. :func:`kernels.path_certify_rr.rr_pose_boxes`)."""
    import numpy as np

    def test(boxes: Any) -> tuple[Any, Any, Any]:
        verdict = np.empty(len(boxes), dtype=np.int64)
        reason = np.empty(len(boxes), dtype=np.int64)
        kappa = np.empty((len(boxes), 2))
        kernel(np.ascontiguousarray(boxes), *inputs, verdict, reason, kappa)
        return verdict, reason, kappa

    return test


def width_setting() -> Any:
    """``leg_width_cm``: the links' capsule diameter a certified path keeps clear."""
    return setting(
        number(positive=True),
        default=None,
        default_doc="(no interference test)",
        type_doc="number > 0",
        doc="with kappa_max, also certify that no two links, nor a link and the platform, "
        "come closer than allowed (links as capsules of this width, docs/interference.md)",
    )


def with_clearance(test: BoxTest, clearance: Any) -> BoxTest:
    r"""``test`` with the clearance of ``clearance`` (pose boxes to ``(verdict, gap)``,
    the gap :math:`\min(d - d_{req})` enclosed over the box's poses where the legs close):
    a box whose gap is below 0 at every such pose fails (``OUT``, reason
    ``interference``: every pose either leaves the legs open or interferes); one whose gap
    may be below 0 is no longer ``IN`` (``UNSURE``)."""
    import numpy as np

    def test_clear(boxes: Any) -> tuple[Any, Any, Any]:
        verdict, reason, kappa = test(boxes)
        _, gap = clearance(boxes)
        clash = (verdict != OUT) & (gap[:, 1] < 0.0)
        verdict = np.where((verdict == IN) & ~(gap[:, 0] >= 0.0), UNSURE, verdict)
        verdict[clash] = OUT
        reason = np.where(clash, INTERFERENCE, reason)
        return verdict, reason, kappa

    return test_clear


def with_leg_width(test: BoxTest, spec: Any, kernel: Callable[..., None], *inputs: Any) -> BoxTest:
    """``test``, with the spec's ``leg_width_cm`` :math:`w`, joined by the clearance of the
    robot's kernel ``kernel(boxes, *inputs, w, verdict, gap)`` (:func:`with_clearance`);
    ``test`` itself without it."""
    width = getattr(spec, "leg_width_cm", None)
    if width is None:
        return test
    return with_clearance(test, clearance_test(kernel, *inputs, float(width)))


def clearance_test(kernel: Callable[..., None], *inputs: Any) -> Any:
    """Pose boxes to ``(verdict, gap)`` by a robot's clearance kernel ``kernel(boxes,
    *inputs, verdict, gap)`` (e.g. :func:`kernels.path_interference_rr.rr_pose_clearance`)."""
    import numpy as np

    def clearance(boxes: Any) -> tuple[Any, Any]:
        verdict = np.empty(len(boxes), dtype=np.int64)
        gap = np.empty((len(boxes), 2))
        kernel(np.ascontiguousarray(boxes), *inputs, verdict, gap)
        return verdict, gap

    return clearance


def open_limits(limits: Any) -> Any:
    """Joint limits (legs, 2) radians with each full turn (``hi - lo >= 2 pi``) replaced by
    limits that cut nothing (two turns either way), so that no box straddling the turn's
    seam is left unsure."""
    import numpy as np

    limits = np.asarray(limits, dtype=np.float64)
    full = (limits[:, 1] - limits[:, 0] >= 2.0 * math.pi)[:, None]
    return np.ascontiguousarray(np.where(full, [-4.0 * math.pi, 4.0 * math.pi], limits))


def pose_boxes(start: Any, stop: Any, duration_s: float, t0: Any, t1: Any) -> Any:
    """The pose boxes (k, 6) ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi`` (cm, rad) of the
    time intervals ``[t0, t1]`` (k,) of the path from ``start`` to ``stop`` (cm, cm[, rad]):
    the hull of the end poses, widened for round-off (module docstring)."""
    import numpy as np

    from planar_tui.workspace.path.quintic import quintic

    start = np.asarray(start, dtype=np.float64)
    stop = np.asarray(stop, dtype=np.float64)
    a = quintic(start, stop, duration_s, t0)[0]
    b = quintic(start, stop, duration_s, t1)[0]
    slack = ROUND_RELATIVE * (np.abs(start) + np.abs(stop - start)) + 1e-300
    boxes = np.zeros((len(a), 6))
    d = len(start)
    boxes[:, 0 : 2 * d : 2] = np.minimum(a, b) - slack
    boxes[:, 1 : 2 * d : 2] = np.maximum(a, b) + slack
    return boxes


class _Scan:
    """The bisection's state: the path, the test and what was proved so far."""

    def __init__(self, test: BoxTest, start: Any, stop: Any, duration_s: float, kappa_max):
        self.test, self.start, self.stop = test, start, stop
        self.duration_s, self.kappa_max = duration_s, kappa_max
        self.fail_s, self.fail_reason = math.inf, ""
        self.boxes_tested = 0
        self.points: list[Any] = []  # (t, kappa_lo) of valid tested points
        self.certified: list[Any] = []  # (t0, t1, kappa_hi) rows

    def evaluate(self, t0: Any, t1: Any) -> tuple[Any, Any, Any]:
        self.boxes_tested += len(t0)
        return self.test(pose_boxes(self.start, self.stop, self.duration_s, t0, t1))

    def failures(self, times: Any, verdict: Any, reason: Any, kappa: Any) -> Any:
        """Record the proved failures among boxes starting at ``times``: the mask."""
        import numpy as np

        over = (verdict == IN) & (kappa[:, 0] > self.kappa_max)
        failed = (verdict == OUT) | over
        if failed.any():
            k = int(np.argmin(np.where(failed, times, np.inf)))
            if times[k] < self.fail_s:
                self.fail_s = float(times[k])
                self.fail_reason = KAPPA if over[k] else REASONS.get(int(reason[k]), "leg")
        return failed

    def points_at(self, times: Any) -> Any:
        """Test the poses at ``times`` (k,): the mask of proved failures."""
        verdict, reason, kappa = self.evaluate(times, times)
        self.points.append((times[verdict == IN], kappa[verdict == IN, 0]))
        return self.failures(times, verdict, reason, kappa)


def certify(
    test: BoxTest, start: Any, stop: Any, duration_s: float, kappa_max: float, progress: Any
) -> Certificate:
    """The certificate of the path from ``start`` to ``stop`` (cm, cm[, rad]) over
    ``duration_s`` under the robot's pose-box ``test`` (module docstring);
    ``progress.advance`` between levels (Cancel)."""
    import numpy as np

    scan = _Scan(test, start, stop, duration_s, kappa_max)
    min_width = duration_s * MIN_WIDTH_FRACTION
    lo, hi = np.array([0.0]), np.array([duration_s])
    scan.points_at(np.array([0.0, duration_s]))
    leaves = [np.empty(0)]
    progress.start(1.0, f"certifying the path (κ ≤ {kappa_max:g})")
    while len(lo) and scan.boxes_tested < MAX_BOXES:
        verdict, reason, kappa = scan.evaluate(lo, hi)
        failed = scan.failures(lo, verdict, reason, kappa)
        good = (verdict == IN) & (kappa[:, 1] <= kappa_max)
        scan.certified.append(np.column_stack([lo[good], hi[good], kappa[good, 1]]))
        open_ = ~good & ~failed & (lo < scan.fail_s)
        narrow = open_ & (hi - lo <= min_width)
        leaves.append(lo[narrow])
        lo, hi = lo[open_ & ~narrow], hi[open_ & ~narrow]
        mid = 0.5 * (lo + hi)
        scan.points_at(mid)
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
        keep = lo < scan.fail_s
        order = np.argsort(lo[keep], kind="stable")
        lo, hi = lo[keep][order], hi[keep][order]
        progress.advance(0.0, f"{scan.boxes_tested:,} pose boxes tested")
    prefix = min([scan.fail_s, *(float(v.min()) for v in leaves if len(v)), *lo[:1]])
    return _verdict(scan, prefix, duration_s)


def _verdict(scan: _Scan, prefix: float, duration_s: float) -> Certificate:
    """The verdict and the brackets once the bisection is over (module docstring)."""
    import numpy as np

    window = duration_s * WINDOW_FRACTION
    if math.isfinite(prefix) and scan.fail_s - prefix > window:
        steps = np.arange(1, PROBE_POINTS + 1) / PROBE_POINTS
        scan.points_at(np.minimum(prefix + window * steps, duration_s))
    if not math.isfinite(prefix):
        certified, hi, reason = "yes", None, ""
    else:
        found = scan.fail_s - prefix <= window
        certified = "no" if found else "unknown"
        hi = scan.fail_s if math.isfinite(scan.fail_s) else None
        reason = scan.fail_reason if hi is not None else ""
    peak_lo, peak_hi = _peak(scan, min(prefix, duration_s))
    return Certificate(
        certified,
        None if certified == "yes" else prefix,
        hi,
        reason,
        scan.kappa_max,
        peak_lo,
        peak_hi,
        scan.boxes_tested,
    )


def _peak(scan: _Scan, until_s: float) -> tuple[float, float]:
    """The bracket of the largest κ over ``[0, until_s]`` (module docstring); ``nan`` where
    no interval there is certified."""
    import numpy as np

    rows = np.concatenate([np.empty((0, 3)), *scan.certified])
    rows = rows[rows[:, 0] < until_s] if until_s > 0.0 else rows[:0]
    times = np.concatenate([t for t, _ in scan.points])
    values = np.concatenate([k for _, k in scan.points])
    best = float(values[times <= until_s].max(initial=math.nan if not len(rows) else 1.0))
    if not len(rows):
        return best, math.nan
    narrowest = scan.duration_s * MIN_WIDTH_FRACTION
    for _ in range(PEAK_ROUNDS):
        wide = (rows[:, 2] > best * (1.0 + PEAK_RELATIVE)) & (rows[:, 1] - rows[:, 0] > narrowest)
        if not wide.any():
            break
        index = np.flatnonzero(wide)
        index = index[np.argsort(-rows[index, 2], kind="stable")][:PEAK_BATCH]
        parent = rows[index]
        mid = 0.5 * (parent[:, 0] + parent[:, 1])
        t0 = np.concatenate([parent[:, 0], mid, mid])
        t1 = np.concatenate([mid, parent[:, 1], mid])
        verdict, _, kappa = scan.evaluate(t0, t1)
        n = len(index)
        point_in = verdict[2 * n :] == IN
        best = max(best, float(kappa[2 * n :, 0][point_in].max(initial=best)))
        upper = np.minimum(np.tile(parent[:, 2], 2), kappa[: 2 * n, 1])
        children = np.column_stack([t0[: 2 * n], t1[: 2 * n], upper])
        rows = np.concatenate([np.delete(rows, index, axis=0), children])
    return best, float(rows[:, 2].max())
