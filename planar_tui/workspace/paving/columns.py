"""The sweep columns of the workspace jobs of the generic runner and the tolerance columns,
named without running them (the kinds' ``figure_names`` hook: a resumed sweep checks its
checkpoint's records against them, an optimisation's objectives and constraints must name
one of them, before anything runs).

A job's columns are its summary CSV's but the wall time (``seconds``: a sweep row has its
own): the summary columns (:data:`~planar_tui.workspace.paving.levels.SUMMARY_HEADER`), then
the singularity-free circle's of a robot that certifies them (every job has them, empty
without ``singularities``; :data:`planar_tui.workspace.paving.circle.HEADER`); with a
tolerance, ``tolerance_mode`` and the half-widths (:func:`tolerance_names`). A robot with its
own runner names its own (the five-bar's, :mod:`planar_tui.workspace.fivebar.job`).
``tests/test_workspace_columns.py`` holds them to the runs'.
"""

from __future__ import annotations

from typing import Any


def planar_figure_names(job: Any) -> tuple[str, ...]:
    """The columns of a job of the generic runner
    (:func:`planar_tui.workspace.paving.runner.run_planar`): the circle's with a robot that
    certifies singularities."""
    from planar_tui.workspace.paving.circle import HEADER
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER

    circle = HEADER if job.spec.mechanism.has_singularities else ()
    return (*SUMMARY_HEADER[:-1], *circle, *tolerance_names(job))


def tolerance_names(job: Any) -> tuple[str, ...]:
    """A tolerance-certified job's last columns (:func:`~planar_tui.workspace.paving.tolerance.
    tolerance_header` of its kind's quantities; none without a tolerance)."""
    from planar_tui.workspace.paving.tolerance import spec_keys, tolerance_header, tolerance_of

    if tolerance_of(job.spec) is None:
        return ()
    return tolerance_header(spec_keys(job.spec))
