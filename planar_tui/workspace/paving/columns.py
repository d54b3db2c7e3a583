"""The sweep columns of the 3-RPR, 3-PRR and five-bar jobs, named without running them (the
kinds' ``figure_names`` hook: a resumed sweep checks its checkpoint's records against them,
an optimisation's objectives and constraints must name one of them, before anything runs).

A job's columns are its summary CSV's but the wall time (``seconds``: a sweep row has its
own): the 3-RRR's summary columns (:data:`~planar_tui.workspace.paving.levels.SUMMARY_HEADER`;
the 3-RPR and 3-PRR with the 3-RRR's orientation columns,
:data:`~planar_tui.workspace.paving.orientation.ORIENTATION_HEADER`),
then its singularity-free circle's (every job has them, empty without ``singularities``):
the 3-RRR's for the 3-RPR and 3-PRR (:data:`planar_tui.workspace.paving.circle.HEADER`), for
a robot whose Mechanism certifies singularities; the five-bar names its own
(:func:`planar_tui.workspace.fivebar.job.fivebar_figure_names`: its ``working_mode``
in place of the ``strategy``); with a tolerance, ``tolerance_mode`` and the half-widths
(:func:`tolerance_names`). ``tests/test_workspace_columns.py`` holds them to the runs'.
"""

from __future__ import annotations

from typing import Any

from planar_tui.workspace.paving.accuracy import accuracy_names
from planar_tui.workspace.paving.circle import HEADER
from planar_tui.workspace.paving.dexterity import dexterity_names
from planar_tui.workspace.paving.interference import interference_names
from planar_tui.workspace.paving.orientation import ORIENTATION_HEADER
from planar_tui.workspace.paving.tolerance import spec_keys, tolerance_header, tolerance_of


def planar_figure_names(job: Any) -> tuple[str, ...]:
    """The columns of a 3-RPR or 3-PRR job (:func:`planar_tui.workspace.paving.runner.run_planar`)."""
    from planar_tui.workspace.paving.levels import SUMMARY_HEADER

    circle = HEADER if job.spec.mechanism.has_singularities else ()
    dexterous = (*dexterity_names(job), *interference_names(job), *accuracy_names(job))
    return (*SUMMARY_HEADER[:-1], *ORIENTATION_HEADER, *circle, *dexterous, *tolerance_names(job))


def tolerance_names(job: Any) -> tuple[str, ...]:
    """A tolerance-certified job's last columns (:func:`~planar_tui.workspace.paving.tolerance.
    tolerance_header` of its kind's quantities; none without a tolerance)."""
    if tolerance_of(job.spec) is None:
        return ()
    return tolerance_header(spec_keys(job.spec))
