"""Certified worst-case accuracy of any parallel robot: the paving, its columns and boxes.

With ``accuracy = { actuator_deg = δθ, tolerance_cm = t }`` (a robot with prismatic
actuators: ``actuator_cm``) a single-orientation workspace job also paves its search box
for the platform's *pose error*: a robot whose actuated coordinates are off by up to the
actuator error and whose geometry (each robot says which quantities: its joints'
coordinates, its links' lengths, each within :math:`\\pm t`, each leg's its own) is off by
up to the tolerance, commanded to the nominal actuator values of the working mode (the
job's ``elbow``, resolved as with ``singularities = true``) at a nominal pose :math:`x`,
stands at :math:`x + \\Delta x`. A robot's
:class:`~planar_tui.workspace.paving.mechanism.Mechanism` gives an *evaluator* (its
``accuracy`` method): for (k, 4) boxes, each box's verdict in the mode (as the dexterity
evaluator's) and, where every leg closes and the Krawczyk test of :mod:`kernels.accuracy`
holds, certified bounds of :math:`|\\Delta x|`, :math:`|\\Delta y|` (cm) and
:math:`|\\Delta\\varphi|` (rad; none for the five-bar) over every pose of the box and every
perturbed robot (``inf`` elsewhere: *not certified*).

The paving is the dexterity paving's (:mod:`planar_tui.workspace.paving.dexterity`) with
"certified" as the property: a box is *certified* (``IN`` and the test holds), *outside*
(``OUT``) or halved down to ``precision_cm``, its leaves refined on a grid; the kept boxes
not certified (holding the workspace's boundary, or near a singularity where the
linearisation's remainder cannot be bounded) are reported by area. The summary's worst
errors are the largest bounds over the certified boxes.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.schema import TableReader, setting
from planar_tui.workspace.paving.dexterity import IN, OUT, decider, refine_leaves, refuse_unpaved
from planar_tui.workspace.paving.orientation_dexterity import range_phi_rad, sliced
from planar_tui.workspace.paving.rows import AppendedRows

if TYPE_CHECKING:
    import numpy as np

    from planar_tui.workspace.paving.levels import BoxBudget

#: The summary's accuracy columns (after the interference's, before the wall time).
HEADER = (
    "accuracy_actuator_deg",
    "accuracy_actuator_cm",
    "accuracy_tolerance_cm",
    "accuracy_dx_max_cm",
    "accuracy_dy_max_cm",
    "accuracy_dphi_max_deg",
    "accuracy_certified_area_cm2",
    "accuracy_uncertified_area_cm2",
)
#: The boxes CSV's extra columns with ``accuracy``: each certified box's error bounds.
BOXES_COLUMNS = ("dx_max_cm", "dy_max_cm", "dphi_max_deg")
#: The accuracy boxes' labels in the boxes CSV.
STATUS_NAMES = {2: "accuracy-certified", 1: "accuracy-not-certified"}
#: The keys of the ``accuracy`` table by actuator kind (``deg`` revolute, ``cm`` prismatic).
ACTUATOR_KEYS = {"deg": "actuator_deg", "cm": "actuator_cm"}

Evaluator = Callable[["np.ndarray"], tuple["np.ndarray", "np.ndarray"]]


@dataclass(frozen=True)
class AccuracySpec:
    """The ``accuracy`` table of a robot whose actuators are in ``unit`` (``deg`` or
    ``cm``): the actuator error ± (0 when not given) and the geometric tolerance ± (cm)."""

    actuator: float
    unit: str
    tolerance_cm: float

    @classmethod
    def of(cls, table: tuple[tuple[str, float], ...], unit: str) -> AccuracySpec:
        """The spec's ``accuracy`` value (sorted ``(key, value)`` pairs) read for ``unit``."""
        values = dict(table)
        return cls(values.get(ACTUATOR_KEYS[unit], 0.0), unit, values.get("tolerance_cm", 0.0))

    def kernel_errors(self, platform: bool = True) -> tuple[float, ...]:
        """The kernels' ``errors`` row (:mod:`kernels.accuracy`): the actuator error (rad or
        cm), the tolerance of the joints and of the platform's points (cm; 0 without a
        platform, the five-bar's end point)."""
        actuator = math.radians(self.actuator) if self.unit == "deg" else self.actuator
        t = self.tolerance_cm
        return (actuator, t, t if platform else 0.0)


def accuracy_setting() -> Any:
    """``accuracy``: the errors, sorted ``(key, value)`` pairs of ``actuator_deg``,
    ``actuator_cm`` and ``tolerance_cm`` (the robot's check refuses the actuator key it
    lacks, :func:`check_accuracy`)."""
    allowed = (*ACTUATOR_KEYS.values(), "tolerance_cm")
    wanted = "a table { actuator_deg = 0.05, tolerance_cm = 0.01 } (numbers >= 0)"

    def read(reader: TableReader, name: str, default: Any, context: Any, values: Any) -> Any:
        if not reader.has(name):
            return default
        table = reader.raw(name)
        if not isinstance(table, Mapping) or not table:
            raise reader.error(name, "is not a non-empty table", wanted)
        for item, value in table.items():
            if item not in allowed:
                raise reader.error(f"{name}.{item}", "unknown key", "one of " + ", ".join(allowed))
            number = isinstance(value, int | float) and not isinstance(value, bool)
            if not (number and math.isfinite(value) and value >= 0):
                raise reader.error(f"{name}.{item}", f"is {value!r}", "a finite number >= 0")
        return tuple(sorted((str(k), float(v)) for k, v in table.items()))

    return setting(
        read,
        default=None,
        type_doc="table { actuator_deg or actuator_cm, tolerance_cm } of numbers ≥ 0",
        doc="also certify the worst-case pose error under these actuator errors and "
        "geometric tolerances ± (docs/accuracy.md)",
        dump=dict,
    )


def check_accuracy(values: dict[str, Any], reader: TableReader, unit: str) -> None:
    """``accuracy`` names the actuator error of the robot's actuators (``unit``: ``deg``
    revolute, ``cm`` prismatic) and needs a form with boxes and no ``tolerance_cm`` (with a
    range of orientations, the working mode ``elbow`` or ``slider_modes`` given)."""
    table = values.get("accuracy")
    if table is None:
        return
    own = ACTUATOR_KEYS[unit]
    for key, _ in table:
        if key not in (own, "tolerance_cm"):
            kind = "revolute" if unit == "deg" else "prismatic"
            found = f"is set: this robot's actuators are {kind}"
            raise reader.error(f"accuracy.{key}", found, f"{own} or tolerance_cm")
    refuse_unpaved("accuracy", values, reader, ranges=True)


@dataclass
class AccuracyOutcome:
    """The accuracy paving's kept boxes (rows ``x_lo, x_hi, y_lo, y_hi``; ``status`` 2 =
    certified, 1 = not certified), their error bounds (``bound`` (k, 2) or (k, 3): cm, cm,
    rad; ``inf`` where not certified), the settings and the working mode."""

    boxes: np.ndarray
    status: np.ndarray
    bound: np.ndarray
    spec: AccuracySpec
    elbow: str
    seconds: float

    @property
    def worst(self) -> tuple[float, ...]:
        """The largest bounds over the certified boxes (|Δx| cm, |Δy| cm, |Δφ| deg; ``nan``
        with none certified)."""
        certified = self.bound[self.status == 2]
        if len(certified) == 0:
            return (math.nan,) * self.bound.shape[1]
        worst = certified.max(axis=0).tolist()
        return (*worst[:2], *(math.degrees(v) for v in worst[2:]))

    @property
    def certified_area_cm2(self) -> float:
        from planar_tui.workspace.paving.boxes import xy_area

        return xy_area(self.boxes[self.status == 2])

    @property
    def uncertified_area_cm2(self) -> float:
        from planar_tui.workspace.paving.boxes import xy_area

        return xy_area(self.boxes[self.status != 2])

    def columns(self) -> list:
        """The summary's :data:`HEADER` cells (the other actuator kind's and, for the
        five-bar, the orientation's empty; the maxima empty with nothing certified)."""
        spec = self.spec
        degrees = spec.actuator if spec.unit == "deg" else ""
        centimetres = spec.actuator if spec.unit == "cm" else ""
        worst: list = [v if math.isfinite(v) else "" for v in self.worst]
        worst += [""] * (3 - len(worst))
        areas = [self.certified_area_cm2, self.uncertified_area_cm2]
        return [degrees, centimetres, spec.tolerance_cm, *worst, *areas]

    def describe(self) -> str:
        """``accuracy: |Δx| ≤ 0.1 cm, |Δy| ≤ 0.1 cm, |Δφ| ≤ 0.2° on 520 cm2 (12 cm2 not
        certified)``."""
        names = ("|Δx|", "|Δy|", "|Δφ|")
        units = (" cm", " cm", "°")
        parts = [f"{n} ≤ {v:.4g}{u}" for n, v, u in zip(names, self.worst, units, strict=False)]
        errors = ", ".join(parts) if self.certified_area_cm2 > 0 else "nothing certified"
        return (
            f"accuracy: {errors} on {self.certified_area_cm2:.5g} cm2 "
            f"({self.uncertified_area_cm2:.5g} cm2 not certified)"
        )


def as_bound(evaluate: Evaluator) -> Evaluator:
    """The evaluator as the dexterity paving's: ``(verdict, [0, 0])`` where certified,
    ``(verdict, [0, inf])`` elsewhere (a bound to hold at most ``0.5``)."""
    import numpy as np

    def bound(boxes: Any) -> tuple[Any, Any]:
        verdict, error = evaluate(boxes)
        kappa = np.zeros((len(boxes), 2))
        kappa[~np.all(np.isfinite(error), axis=1), 1] = math.inf
        return verdict, kappa

    return bound


def at_orientation(evaluate: Evaluator, phi_rad: float) -> Evaluator:
    """A pose-box evaluator (rows ``x_lo, x_hi, y_lo, y_hi, phi_lo, phi_hi``) at the one
    orientation ``phi_rad``: (k, 4) boxes."""
    import numpy as np

    def at_phi(boxes: Any) -> tuple[Any, Any]:
        boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
        phi = np.full((len(boxes), 2), phi_rad)
        return evaluate(np.ascontiguousarray(np.column_stack([boxes, phi])))

    return at_phi


def range_accuracy(mechanism: Any, job: Any, make_test: Callable[[], Evaluator]) -> Evaluator:
    """The evaluator of a job with ``accuracy`` and ``orientation_deg = [lo, hi]``: the
    robot's pose-box evaluator ``make_test()`` (built at the first call: its kernels import
    after ``prepare_kernels``) sliced over the range
    (:func:`~planar_tui.workspace.paving.orientation_dexterity.sliced`): a slice holds when
    ``IN`` and certified, fails when ``OUT``; a box's bounds are the largest over its final
    slices, certified (finite) only where every final slice is."""
    import numpy as np

    robot, spec = job.robot, job.spec

    def make_pose_test() -> Any:
        test = make_test()

        def pose_test(rows: Any) -> tuple[Any, Any, Any]:
            verdict, bound = test(rows)
            return verdict, bound, bound

        return pose_test

    evaluate = sliced(
        make_pose_test,
        range_phi_rad(spec),
        mechanism.characteristic_length_cm(robot, spec),
        3,
        lambda verdict, lo, hi: (verdict == IN) & np.isfinite(hi).all(axis=1),
        lambda verdict, lo, hi: verdict == OUT,
    )

    def evaluate_bound(boxes: Any) -> tuple[Any, Any]:
        verdict, _, upper = evaluate(boxes)
        return verdict, upper

    return evaluate_bound


def compute_accuracy(
    evaluate: Evaluator,
    extent: tuple[float, float, float, float],
    precision_cm: float,
    spec: AccuracySpec,
    elbow: str,
    budget: BoxBudget,
) -> AccuracyOutcome:
    """Pave ``extent`` (``x_lo, x_hi, y_lo, y_hi``, holding the workspace) for the certified
    pose error down to ``precision_cm`` (module docstring)."""
    import numpy as np

    from planar_tui.workspace.paving.levels import pave_in_levels

    started = time.perf_counter()
    budget.progress.start(1.0, "worst-case accuracy")
    bound = as_bound(evaluate)
    decide = decider(bound, 0.5, precision_cm)
    boxes, status = pave_in_levels(np.array([extent], dtype=float), budget, decide)
    boxes, status = refine_leaves(bound, boxes, status, 0.5, budget)
    _, error = evaluate(boxes)
    return AccuracyOutcome(boxes, status, error, spec, elbow, time.perf_counter() - started)


def job_accuracy(job: Any, prepared: Any, extent, budget: BoxBudget, elbow: str = ""):
    """The certified accuracy of a job with ``accuracy`` (its Mechanism's evaluator in the
    prepared working mode ``elbow``)."""
    spec = job.spec
    errors = AccuracySpec.of(spec.accuracy, spec.mechanism.accuracy_unit)
    evaluate = spec.mechanism.accuracy(job, prepared)
    return compute_accuracy(evaluate, extent, spec.precision_cm, errors, elbow, budget)


def position_error(outcome: AccuracyOutcome) -> np.ndarray:
    """Each accuracy box's bound of :math:`\\max(|\\Delta x|, |\\Delta y|)` in cm (``inf``
    where not certified)."""
    import numpy as np

    bound = np.asarray(outcome.bound, dtype=float).reshape(len(outcome.boxes), -1)
    return bound[:, :2].max(axis=1)


def error_edges(outcome: AccuracyOutcome) -> np.ndarray:
    """The upper edges of the error map's four bands: quarters of [0, the largest
    certified :func:`position_error`] (of [0, 1] with none certified)."""
    import numpy as np

    error = position_error(outcome)
    finite = error[np.isfinite(error)]
    return (finite.max() if len(finite) else 1.0) * np.arange(1, 5) / 4


def error_glyph(value: float, edges: np.ndarray) -> str:
    """A cell's glyph: blank (``nan``: no box), ``?`` (``inf``: not certified) or its band."""
    import numpy as np

    from planar_tui.workspace.paving.kappa_map import BAND_GLYPHS, UNPROVED_GLYPH

    if np.isnan(value):
        return " "
    if np.isinf(value):
        return UNPROVED_GLYPH
    return BAND_GLYPHS[min(3, int(np.searchsorted(edges, value)))]


def error_legend_items(edges: np.ndarray) -> list[str]:
    """The bands' legend items and the "not certified" item."""
    from planar_tui.workspace.paving.kappa_map import BAND_GLYPHS, UNPROVED_GLYPH

    bands = [f"{g} ≤ {e:.3g} cm" for g, e in zip(BAND_GLYPHS, edges, strict=True)]
    return [*bands, f"{UNPROVED_GLYPH} not certified"]


def render_error_map(outcome: AccuracyOutcome, width: int = 80) -> list[str]:
    """The position error map as lines of at most ``width`` columns: each cell the worst
    certified bound of :math:`\\max(|\\Delta x|, |\\Delta y|)` over the accuracy boxes
    that touch it, in four bands of [0, the largest certified], ``?`` where a box touching
    it is not certified, blank where none is kept."""
    import numpy as np

    from planar_tui.workspace.paving.kappa_map import worst_cells
    from planar_tui.workspace.paving.map import CELL_ASPECT, fit_extent

    boxes = np.asarray(outcome.boxes).reshape(-1, 4)
    extent = fit_extent(boxes, (0.0, 1.0, 0.0, 1.0))
    xlo, xhi, ylo, yhi = extent
    columns = max(10, width - 2)
    rows = int(min(40, max(5, round(columns * (yhi - ylo) / (xhi - xlo) / CELL_ASPECT))))
    worst = worst_cells(boxes, position_error(outcome), extent, columns, rows)
    edges = error_edges(outcome)
    lines = [
        f"error map, x in [{xlo:.4g}, {xhi:.4g}] cm, y in [{ylo:.4g}, {yhi:.4g}] cm "
        "(worst certified max(|Δx|, |Δy|) per cell)"[:width]
    ]
    for j in range(rows - 1, -1, -1):
        lines.append("│" + "".join(error_glyph(v, edges) for v in worst[j]))
    legend = "  ".join(error_legend_items(edges))
    return [*lines, legend[:width]]


def accuracy_names(job: Any) -> tuple[str, ...]:
    """A job's accuracy columns: :data:`HEADER` with ``accuracy``, none without."""
    return HEADER if getattr(job.spec, "accuracy", None) is not None else ()


class AccuracyRows(AppendedRows):
    """The boxes CSV's rows with ``accuracy``: the table's rows with empty bound cells, then
    the accuracy boxes labelled ``accuracy-certified`` (with their bounds: cm, cm, deg) or
    ``accuracy-not-certified`` (the table's other extra columns empty)."""

    def __init__(self, rows: Any, width: int, outcome: AccuracyOutcome):
        super().__init__(rows, outcome)
        self._pad = [""] * (width - 5)

    def table_row(self, row: Any) -> list:
        return [*row, "", "", ""]

    def stage_row(self, i: int) -> list:
        out = self._outcome
        values = out.bound[i].tolist()
        values[2:] = [math.degrees(v) for v in values[2:]]
        cells = [v if math.isfinite(v) else "" for v in values] + [""] * (3 - len(values))
        return [*out.boxes[i].tolist(), STATUS_NAMES[int(out.status[i])], *self._pad, *cells]


def boxes_table(table: Any, outcome: AccuracyOutcome | None) -> Any:
    """The boxes CSV ``table`` with, with ``accuracy``, the accuracy boxes and their bound
    columns (:class:`AccuracyRows`)."""
    from planar_tui.csvio import CsvTable

    if outcome is None:
        return table
    rows = AccuracyRows(table.rows, len(table.header), outcome)
    return CsvTable((*table.header, *BOXES_COLUMNS), rows)
