"""Workspaces certified for manufacturing tolerances (issue 25, item 2).

The preset keys ``tolerance_cm`` (one half-width on every length and joint position),
``tolerances_cm`` (a table of half-widths per robot quantity, overriding it) and
``tolerance_mode`` (``"all"``: the points every robot within the tolerances reaches, the
*robust* workspace; ``"some"``: the points at least one reaches) turn a workspace job into
a tolerance-certified one. Without them nothing changes.

The 3-RRR's quantities (:data:`~planar_tui.workspace.rrr.robot.TOLERANCE_KEYS_3RRR`): ``base_joints_cm`` (each coordinate
of each base joint :math:`A_i`), ``platform_points_cm`` (each coordinate of each platform
point :math:`q_i`, in the platform frame), ``proximal_cm`` (each leg's :math:`l_1`),
``distal_cm`` (each leg's :math:`l_2`); every leg's parts are made separately, so they vary
independently (in the paper's layout the side lengths ``a`` and ``b`` are not
parameters of their own: a side's error moves the joints, covered by the joints'
tolerances).

Quantifiers, for the (x, y) box :math:`B` and the box :math:`\\Pi` of robots:

* ``all``: inside iff :math:`\\forall \\pi \\in \\Pi\\; \\forall v \\in B`: :math:`v \\in
  W(\\pi)`; outside iff :math:`\\forall v \\in B\\; \\exists \\pi: v \\notin W(\\pi)`.
* ``some``: inside iff :math:`\\forall v \\in B\\; \\exists \\pi: v \\in W(\\pi)`; outside iff
  :math:`\\forall \\pi\\; \\forall v \\in B: v \\notin W(\\pi)`.

The *universal* certificates (``all``-inside, ``some``-outside) enclose the constraint over
:math:`B \\times \\Pi`: the interval forms (natural, mean-value, slope) over the (x, y) box
grown by the joints' and the proximal's tolerances and with :math:`l_2` as an interval
(:func:`planar_tui.kernels.workspace_legwise.leg_search`), the exact leg-wise test with the
Lipschitz bound :math:`\\sigma` (:mod:`planar_tui.kernels.workspace_tolerance`). The
*existential* ones (``all``-outside, ``some``-inside) exhibit one robot, a vertex of
:math:`\\Pi` per leg, and run the exact test on it. The bracket ``[inside, kept]`` holds
the mode's exact area, as for the nominal robot.

**Bound.** The legs' distances move by at most :math:`\\sigma` and :math:`l_2` by
:math:`t_2`, so the robust workspace contains the nominal workspace *eroded in constraint
value* by :func:`erosion_bound_cm` :math:`= \\sigma + t_2`: the points where every leg has
:math:`d_{\\min} \\le l_2 - (\\sigma + t_2)` and :math:`d_{\\max} \\ge l_2 + (\\sigma + t_2)`;
the "some" workspace lies inside the nominal one *dilated* the same way. (Not the metric
erosion: with :math:`l_1 = l_2`, paper B's design, a shorter distal opens a hole of
radius :math:`l_1 - l_2'` about the base joint where the nominal robot reaches a full
neighbourhood.)

**Adopting it in another mechanism** (3-RPR, 3-PRR, five-bar): declare the three fields
with :func:`tolerance_fields` (naming the robot's own quantities), call
:func:`check_tolerance` from the spec's ``check``, then :func:`tolerance_of` gives a
:class:`Tolerance` (half-width per quantity, mode); :func:`parameter_box` turns the
mechanism's nominal parameter vector and a per-entry half-width vector into the
intervals ``(lo, hi)`` its interval forms take, and :func:`vertex_parameters` one robot at
a vertex for the existential certificates.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from planar_tui.schema import setting, string

if TYPE_CHECKING:
    import numpy as np

#: ``tolerance_mode``'s values.
TOLERANCE_MODES = ("all", "some")
#: (a kind's own: :func:`tolerance_header`)


@dataclass(frozen=True)
class Tolerance:
    """Half-widths (cm) per quantity and the mode (``all`` or ``some``)."""

    half_widths_cm: tuple[tuple[str, float], ...]
    mode: str

    def of(self, key: str) -> float:
        """The half-width of quantity ``key`` (0 when not toleranced)."""
        return dict(self.half_widths_cm).get(key, 0.0)


def _read_tolerances(keys: Sequence[str]):
    def read(reader, name, default, robot, values):
        if not reader.has(name):
            return default
        table = reader.raw(name)
        wanted = "a table { " + ", ".join(f"{k} = 0.01" for k in keys) + " } (cm, >= 0)"
        if not isinstance(table, Mapping) or not table:
            raise reader.error(name, "is not a non-empty table", wanted)
        rows = []
        for key, value in table.items():
            if key not in keys:
                raise reader.error(f"{name}.{key}", "unknown quantity", "one of " + ", ".join(keys))
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise reader.error(f"{name}.{key}", "is not a number", "a number >= 0 (cm)")
            if not (math.isfinite(value) and value >= 0):
                raise reader.error(f"{name}.{key}", f"is {value!r}", "a finite number >= 0 (cm)")
            rows.append((key, float(value)))
        return tuple(sorted(rows))

    return read


def _read_tolerance_cm(reader, name, default, robot, values):
    if not reader.has(name):
        return default
    return reader.number(name, minimum=0.0)


def tolerance_fields(
    keys: Sequence[str],
    uniform_doc: str = "manufacturing tolerance ± on every length and joint coordinate (cm)",
) -> tuple[Any, Any, Any]:
    """The settings ``tolerance_cm`` (documented by ``uniform_doc``), ``tolerances_cm`` and
    ``tolerance_mode`` of a workspace spec whose robot's toleranced quantities are ``keys``."""
    listed = ", ".join(f"`{k}`" for k in keys)
    return (
        setting(
            _read_tolerance_cm,
            default=None,
            type_doc="number ≥ 0",
            default_doc="(none: the nominal robot)",
            doc=uniform_doc,
        ),
        setting(
            _read_tolerances(keys),
            default=None,
            type_doc=f"table of numbers ≥ 0 keyed by {listed}",
            default_doc="(none)",
            doc="per-quantity tolerances ± (cm), overriding `tolerance_cm` for those named "
            "(the others: `tolerance_cm`, or 0 without it)",
        ),
        setting(
            string(choices=TOLERANCE_MODES),
            default=None,
            type_doc="`all` or `some`",
            default_doc='`"all"` with a tolerance',
            doc="points reached by every robot within the tolerances (robust) or by one",
        ),
    )


def check_tolerance(
    values: dict[str, Any], reader: Any, keys: Sequence[str], lengths: Mapping[str, float]
) -> None:
    """Cross-key checks: a mode needs a tolerance; a tolerance sets the mode to ``all`` by
    default, is below each of the robot's ``lengths`` it applies to (by key: every robot
    keeps positive lengths) and takes one orientation, the legwise interval forms or
    ``arc-distance``, and no singularities."""
    given = values["tolerance_cm"] is not None or values["tolerances_cm"] is not None
    if not given:
        if values["tolerance_mode"] is not None:
            raise reader.error(
                "tolerance_mode", "is set without a tolerance", "tolerance_cm or tolerances_cm"
            )
        return
    if values["tolerance_mode"] is None:
        values["tolerance_mode"] = "all"
    widths = dict.fromkeys(keys, values["tolerance_cm"] or 0.0)
    widths.update(dict(values["tolerances_cm"] or ()))
    for key, length in lengths.items():
        if widths[key] >= length:
            where = "tolerance_cm" if values["tolerance_cm"] == widths[key] else "tolerances_cm"
            raise reader.error(
                where, f"is ±{widths[key]:g} cm on {key} = {length:g} cm", f"< {length:g} cm"
            )
    problems = (
        ("orientation_deg", isinstance(values.get("orientation_deg"), tuple), "one orientation"),
        ("form", values["form"] == "geometric", "an interval form or arc-distance"),
        ("strategy", values.get("strategy") == "joint", '"legwise" (or form = "arc-distance")'),
        ("expanded", values.get("expanded"), "false"),
        ("singularities", values["singularities"], "false"),
    )
    for key, bad, expected in problems:
        if bad and not (key == "strategy" and values["form"] == "arc-distance"):
            raise reader.error(key, f"is {values[key]!r} with a tolerance", expected)


def refuse_reference(values: dict[str, Any], reader: Any) -> None:
    """With a tolerance, ``geometric_reference`` is off (its default, the nominal robot's
    exact area, is not the tolerance-certified one's) and refused if asked for."""
    if values["tolerance_mode"] is not None and values["geometric_reference"]:
        if reader.has("geometric_reference"):
            raise reader.error("geometric_reference", "is true with a tolerance", "false")
        values["geometric_reference"] = False


def spec_keys(spec: Any) -> tuple[str, ...]:
    """The toleranced quantities of a spec's kind: its ``tolerance_keys``."""
    return tuple(spec.tolerance_keys)


def tolerance_of(spec: Any, keys: Sequence[str] | None = None) -> Tolerance | None:
    """The spec's :class:`Tolerance` (``None`` without one) over ``keys`` (default: the
    spec's kind's, :func:`spec_keys`)."""
    keys = spec_keys(spec) if keys is None else keys
    uniform = getattr(spec, "tolerance_cm", None)
    table = getattr(spec, "tolerances_cm", None)
    if uniform is None and table is None:
        return None
    widths = dict.fromkeys(keys, uniform or 0.0)
    widths.update(dict(table or ()))
    return Tolerance(tuple(widths.items()), spec.tolerance_mode or "all")


def erosion_bound_cm(tolerance: Tolerance) -> float:
    """:math:`\\sigma + t_2 = \\sqrt2 (t_A + t_q) + t_1 + t_2`: the most any leg's
    constraint (:math:`l_2 - d_{\\min}`, :math:`d_{\\max} - l_2`) moves over the tolerances."""
    t = tolerance.of
    return (
        math.sqrt(2.0) * (t("base_joints_cm") + t("platform_points_cm"))
        + t("proximal_cm")
        + t("distal_cm")
    )


def reach_margin_cm(spec: Any) -> float:
    r"""How far beyond the nominal robot's reach a spec's workspace may extend: for
    ``"some"``, :math:`\sqrt2 \sum_k t_k` over the kind's quantities (a toleranced point
    moves by at most :math:`\sqrt2\,t`, a length by :math:`t`, and a leg's reach by at most
    their sum: the 3-RPR's :math:`\sigma`, the 3-PRR's :math:`\sigma + t_l`, the five-bar's
    :math:`\sqrt2\,t_A + t_1 + t_2` are below it); 0 for the nominal robot and the robust
    workspace (inside the nominal one)."""
    tolerance = tolerance_of(spec)
    if tolerance is None or tolerance.mode != "some":
        return 0.0
    return math.sqrt(2.0) * sum(width for _, width in tolerance.half_widths_cm)


def grown(
    box: tuple[float, float, float, float], margin: float
) -> tuple[float, float, float, float]:
    """The box ``(x_lo, x_hi, y_lo, y_hi)`` grown by ``margin`` on every side."""
    xlo, xhi, ylo, yhi = box
    return (xlo - margin, xhi + margin, ylo - margin, yhi + margin)


def kernel_tolerance(tolerance: Tolerance | None, orientation_rad: float) -> np.ndarray:
    """The kernels' ``tol`` vector (:mod:`planar_tui.kernels.workspace_tolerance`)."""
    from planar_tui.kernels.workspace_tolerance import ALL, NOMINAL, SOME, tolerance_vector

    if tolerance is None:
        return tolerance_vector(NOMINAL, 0.0, 0.0, 0.0, 0.0, orientation_rad)
    t = tolerance.of
    return tolerance_vector(
        ALL if tolerance.mode == "all" else SOME,
        t("base_joints_cm"),
        t("platform_points_cm"),
        t("proximal_cm"),
        t("distal_cm"),
        orientation_rad,
    )


def tolerant_vector(spec: Any) -> np.ndarray | None:
    """The kernels' ``tol`` of a spec with a tolerance (``None`` without one)."""
    tolerance = tolerance_of(spec)
    return None if tolerance is None else kernel_tolerance(tolerance, spec.orientation_rad)


def tolerance_header(keys: Sequence[str]) -> tuple[str, ...]:
    """Summary CSV columns of a tolerance-certified job whose kind tolerances ``keys``:
    ``tolerance_mode`` and ``tolerance_<key>`` per key."""
    return ("tolerance_mode", *(f"tolerance_{key}" for key in keys))


def tolerance_columns(spec: Any) -> list[Any]:
    """The :func:`tolerance_header` values of a spec (``[]`` without a tolerance)."""
    tolerance = tolerance_of(spec)
    if tolerance is None:
        return []
    return [tolerance.mode, *(tolerance.of(key) for key in spec_keys(spec))]


def tolerance_companions(robot: Any, spec: Any, budget_for: Any, compute: Any) -> dict[str, Any]:
    """The other two workspaces a tolerance-certified job is drawn with (map, figure):
    ``{"nominal": ..., <the other mode>: ...}``, each paved at the job's precision by
    ``compute(robot, spec, budget)`` (the kind's paving: the 3-RRR's
    :func:`~planar_tui.workspace.rrr.compute.compute_workspace`...) with ``budget_for()`` (a
    fresh :class:`~planar_tui.workspace.paving.levels.BoxBudget`)."""
    from dataclasses import replace

    other = "some" if spec.tolerance_mode == "all" else "all"
    specs = {
        "nominal": replace(
            spec,
            tolerance_cm=None,
            tolerances_cm=None,
            tolerance_mode=None,
            geometric_reference=False,
        ),
        other: replace(spec, tolerance_mode=other, geometric_reference=False),
    }
    return {name: compute(robot, s, budget_for()) for name, s in specs.items()}


@dataclass(frozen=True)
class ToleranceReport:
    """What a tolerance-certified job adds to its result: the summary CSV's ``header`` and
    ``cells`` (before ``seconds``), the ``companions`` (:func:`tolerance_companions`) and
    the summary's ``text`` (``; tolerance all ±0.1 cm; nominal [..] cm2, some [..] cm2``)."""

    header: tuple[str, ...]
    cells: list[Any]
    companions: dict[str, Any]
    text: str


def tolerance_report(job: Any, budget_for: Any, compute: Any) -> ToleranceReport | None:
    """The :class:`ToleranceReport` of a job (``None`` without a tolerance), its companions
    paved by ``compute`` with ``budget_for()`` (:func:`tolerance_companions`)."""
    tolerance = tolerance_of(job.spec)
    if tolerance is None:
        return None
    companions = tolerance_companions(job.robot, job.spec, budget_for, compute)
    return ToleranceReport(
        tolerance_header(spec_keys(job.spec)),
        tolerance_columns(job.spec),
        companions,
        f"; {describe(tolerance)}; {companions_text(companions)}",
    )


def describe(tolerance: Tolerance) -> str:
    """``tolerance all ±0.01 cm`` or the per-quantity half-widths."""
    widths = {w for _, w in tolerance.half_widths_cm}
    if len(widths) == 1:
        return f"tolerance {tolerance.mode} ±{widths.pop():g} cm"
    parts = ", ".join(f"{k} ±{w:g}" for k, w in tolerance.half_widths_cm)
    return f"tolerance {tolerance.mode} ({parts} cm)"


def companions_text(companions: dict[str, Any]) -> str:
    """``nominal [105.35, 108] cm2, some [...]``: the companions' brackets."""
    return ", ".join(
        f"{name} [{o.area_inside_cm2:.5g}, {o.area_kept_cm2:.5g}] cm2"
        for name, o in companions.items()
    )


#: The map's layers of a tolerance-certified job beside its robust boxes: glyph, legend.
MAP_LAYERS = (("nominal", "▓", "nominal robot only"), ("some", "░", "some robot only"))


def map_layers(outcome: Any, companions: dict[str, Any], mode: str) -> tuple[Any, Any, list[Any]]:
    """The robust workspace's boxes and status, and the ``render_map`` layers (boxes,
    glyph, legend) of the nominal and "some" workspaces' kept boxes."""
    outcomes = {mode: outcome, **companions}
    robust = outcomes["all"]
    layers = [(outcomes[name].boxes, glyph, text) for name, glyph, text in MAP_LAYERS]
    return robust.boxes, robust.status, layers


def plus(value: float, amount: float, direction: float) -> float:
    """``value + amount`` nudged one ulp towards ``direction`` (exact when ``amount`` is 0)."""
    if amount == 0.0:
        return value
    return max(0.0, math.nextafter(value + amount, direction))


def shift_bounds_cm(t_base_cm: float, t_platform_cm: float) -> tuple[float, float]:
    """:math:`(\\sigma, \\gamma) = (\\sqrt2 (t_A + t_q), t_A + t_q)`, :math:`\\sigma` rounded
    up and :math:`\\gamma` down (module docstring)."""
    total = t_base_cm + t_platform_cm
    if total == 0.0:
        return 0.0, 0.0
    sigma = math.nextafter(
        math.nextafter(math.sqrt(2.0), 2.0) * math.nextafter(total, 1e300), 1e300
    )
    return sigma, math.nextafter(total, 0.0)
