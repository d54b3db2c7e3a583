"""Orientation workspaces: ``orientation_deg = [lo, hi]`` with ``orientation_mode``.

The *maximal* workspace holds the positions reachable with at least one orientation of the
range, the *total orientation* workspace those reachable with every one. Both are paved in
(x, y) level by level, in parallel, by
:func:`planar_tui.kernels.workspace_orientation.range_level`, whose box test treats φ as
an interval variable, bisected per box (the classification rules and their proofs are in that module's docstring), giving a certified bracket
``area_inside <= exact <= area_kept`` like the single-orientation job. The optional
reference (``geometric_reference``) is the certified sampled bracket of
:mod:`planar_tui.workspace.rrr.orientation_reference`.
"""

from __future__ import annotations

import math

MODES = ("maximal", "total")


def read_orientation(reader, name, default, robot, values):
    """``orientation_deg``: one number (a single orientation) or ``[lo, hi]`` in degrees
    with ``lo < hi`` and ``hi - lo <= 360``."""
    if not reader.has(name) or not isinstance(reader.raw(name), list):
        return reader.number(name, default)
    row = reader.numbers(name)
    if len(row) != 2:
        raise reader.error(name, f"has {len(row)} values", "a number or [lo, hi]")
    lo, hi = row
    if not lo < hi:
        raise reader.error(name, f"range [{lo:g}, {hi:g}] is empty or reversed", "lo < hi")
    if hi - lo > 360.0:
        raise reader.error(name, f"range spans {hi - lo:g} deg", "at most 360 deg")
    return (lo, hi)


def check_orientation(values: dict, reader, range_form: str = "arc-distance") -> None:
    """``orientation_mode`` goes with a range and only with one; a range takes the form
    ``range_form`` only (the 3-RRR's ``arc-distance``, its default there)."""
    mode = values["orientation_mode"]
    ranged = isinstance(values["orientation_deg"], tuple)
    if ranged and mode is None:
        raise reader.error(
            "orientation_mode",
            "missing key with orientation_deg = [lo, hi]",
            '"maximal" or "total"',
        )
    if not ranged and mode is not None:
        raise reader.error(
            "orientation_mode",
            f"is {mode!r} with a single orientation_deg",
            "orientation_deg = [lo, hi], or no orientation_mode",
        )
    if ranged and values["form"] != range_form:
        raise reader.error(
            "form",
            f"is {values['form']!r} with orientation_deg = [lo, hi]",
            f'"{range_form}" (the only form over a range of orientations)',
        )


def arc_extent(q: tuple[float, float], lo: float, hi: float) -> tuple[float, ...]:
    """``(min, max)`` of the x and y components of :math:`R(\\varphi) q` over
    :math:`\\varphi \\in [lo, hi]` (radians): the ends and the axis crossings inside."""
    radius, angle = math.hypot(*q), math.atan2(q[1], q[0])
    angles = [lo, hi]
    for k in range(4):  # phi + angle = k pi / 2 (mod 2 pi): an x or y extreme
        base = k * 0.5 * math.pi - angle
        first = base + 2.0 * math.pi * math.ceil((lo - base) / (2.0 * math.pi))
        angles += [t for t in (first, first + 2.0 * math.pi) if lo <= t <= hi]
    xs = [radius * math.cos(t + angle) for t in angles]
    ys = [radius * math.sin(t + angle) for t in angles]
    return min(xs), max(xs), min(ys), max(ys)


def range_reach_box(bases, points, reaches, orientation_deg) -> tuple[float, float, float, float]:
    """Bounding box of the union over :math:`\\varphi \\in` ``orientation_deg`` (degrees) of
    :math:`\\cap_i D(A_i - R(\\varphi) q_i, r_i)` (base joints ``bases``, platform points
    ``points``, radii ``reaches``): its x extent lies in :math:`[\\max_i (\\min_\\varphi
    c_{x,i} - r_i), \\min_i (\\max_\\varphi c_{x,i} + r_i)]` (y alike)."""
    lo, hi = (math.radians(v) for v in orientation_deg)
    extents = [arc_extent(q, lo, hi) for q in points]
    legs = list(zip(bases, extents, reaches, strict=True))
    # centre c_i = A_i - R q_i: its min is A_i - max(R q_i)
    return (
        max(a[0] - e[1] - r for a, e, r in legs),
        min(a[0] - e[0] + r for a, e, r in legs),
        max(a[1] - e[3] - r for a, e, r in legs),
        min(a[1] - e[2] + r for a, e, r in legs),
    )


def phi_min_rad(points, precision_cm: float) -> float:
    """Narrowest orientation piece: its chord term :math:`2|q|\\sin(h/2) \\le |q| h` stays
    below ``precision_cm / 2`` for the farthest platform point of ``points`` (h the
    half-width)."""
    farthest = max(math.hypot(*q) for q in points)
    return precision_cm / max(farthest, 1e-300)


def range_stage(g, limits, mechanism, points, spec, seeds, precision, budget, inside_cm2=0.0):
    """Level-wise 2-D paving of the disjoint (x, y) boxes ``seeds`` with the orientation-range
    test of ``mechanism`` (``g``, ``limits``: its arrays, ``points`` its platform points;
    :mod:`planar_tui.kernels.workspace_orientation`), every level in parallel
    (:func:`planar_tui.workspace.paving.levels.pave_in_levels`); returns the kept boxes and their
    status (2 inside, 1 boundary)."""
    import numpy as np

    from planar_tui.kernels.workspace_orientation import MAXIMAL, TOTAL, range_level
    from planar_tui.workspace.paving.levels import pave_in_levels

    mode = MAXIMAL if spec.orientation_mode == "maximal" else TOTAL
    lo, hi = (math.radians(v) for v in spec.orientation_deg)
    phi_min = phi_min_rad(points, precision)

    def decide(rows, start, stop, children, outcome):
        work = np.empty(stop - start, dtype=np.int64)
        range_level(
            mode,
            lo,
            hi,
            phi_min,
            g,
            limits,
            precision,
            rows,
            start,
            stop,
            children,
            outcome,
            work,
            mechanism,
        )

    return pave_in_levels(seeds, budget, decide, inside_cm2)


def paved_range(stage, spec, budget, extent, geometric, started, disjoint=False):
    """The paving of an orientation range from the search box ``extent``: ``stage(seeds,
    precision, inside_cm2)`` (a :func:`range_stage`) down to ``precision_cm``, then the
    boundary boxes down to ``refine_precision_cm``
    (:func:`~planar_tui.workspace.paving.levels.finished_outcome`)."""
    import numpy as np

    from planar_tui.workspace.paving.levels import finished_outcome

    budget.progress.start(1.0, f"{spec.orientation_mode} orientation workspace")
    boxes, status = stage(np.array([extent]), spec.precision_cm, 0.0)

    def refine(seeds, inside_cm2):
        return stage(seeds, spec.refine_precision_cm, inside_cm2)

    return finished_outcome(
        spec,
        boxes,
        status,
        refine,
        budget,
        geometric,
        started,
        extent,
        form=spec.form,
        disjoint=disjoint,
    )


def orientation_columns(spec) -> list:
    """The summary's ``orientation_mode, orientation_lo_deg, orientation_hi_deg`` (a single
    orientation: no mode, ``lo = hi = φ``)."""
    if isinstance(spec.orientation_deg, tuple):
        return [spec.orientation_mode, *spec.orientation_deg]
    return ["", spec.orientation_deg, spec.orientation_deg]


ORIENTATION_HEADER = ("orientation_mode", "orientation_lo_deg", "orientation_hi_deg")


def describe(spec) -> str:
    """``φ = 10°`` or ``maximal, φ ∈ [-10, 10]°`` for titles and summaries."""
    if isinstance(spec.orientation_deg, tuple):
        lo, hi = spec.orientation_deg
        return f"{spec.orientation_mode}, φ ∈ [{lo:g}, {hi:g}]°"
    return f"φ = {spec.orientation_deg:g}°"


def summary_text(spec, outcome) -> str:
    """One short line: form, ε, mode and range, the certified bracket and the sampled
    reference's bracket."""
    text = (
        f"{outcome.form} eps={outcome.precision_cm:.4g}, {describe(spec)}: "
        f"[{outcome.area_inside_cm2:.5g}, {outcome.area_kept_cm2:.5g}] cm2"
    )
    if outcome.geometric is not None:
        g = outcome.geometric
        text += f", sampled reference [{g.inner_cm2:.5g}, {g.outer_cm2:.5g}]"
    return text
