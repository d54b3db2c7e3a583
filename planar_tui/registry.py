"""The registries of robot kinds and job kinds: one line per kind.

A new job kind is one module in its domain package ending with a
:class:`~planar_tui.jobkind.JobKind`, plus one line in :data:`JOB_KINDS`; the preset
loader, the batch service, the run plan, sweeps, the CLI (its ``run`` and the kind's own
command), preset saving, figures, warm-up and the app (the kind's tab) pick it up.
Nothing imported here loads numpy, numba, SALib or Textual (runners import them when they
run), so ``planar-tui --help`` can list the kinds' commands at once.
"""

from collections.abc import Iterator
from contextlib import contextmanager

from planar_tui.dynamics import robot as serial_robot
from planar_tui.dynamics import simulate, torques
from planar_tui.jobkind import JobKind, RobotKind
from planar_tui.motion import job as motion_uncertainty
from planar_tui.sensitivity import job as sensitivity
from planar_tui.workspace import fivebar as robot5r
from planar_tui.workspace import fivebar_job as workspace5r
from planar_tui.workspace import job as workspace
from planar_tui.workspace import prr, prr_job, rpr, rpr_job
from planar_tui.workspace import robot as robot3rrr

ROBOT_KINDS: dict[str, RobotKind] = {
    kind.name: kind
    for kind in (
        serial_robot.ROBOT_KIND,
        robot3rrr.ROBOT_KIND,
        rpr.ROBOT_KIND,
        prr.ROBOT_KIND,
        robot5r.ROBOT_KIND,
    )
}

JOB_KINDS: dict[str, JobKind] = {
    kind.name: kind
    for kind in (
        simulate.JOB_KIND,
        torques.JOB_KIND,
        sensitivity.JOB_KIND,
        workspace.JOB_KIND,
        workspace5r.JOB_KIND,
        motion_uncertainty.JOB_KIND,
        rpr_job.JOB_KIND,
        prr_job.JOB_KIND,
    )
}


@contextmanager
def registered(kind: JobKind) -> Iterator[JobKind]:
    """Register ``kind`` while the block runs, then remove it (for tests: a kind defined in
    a test file alone). Front ends read the registry when they are built (the CLI's
    :func:`planar_tui.cli.build_app`, the app's tabs), so build them inside the block."""
    if kind.name in JOB_KINDS:
        raise ValueError(f"a job kind named {kind.name!r} is registered already")
    if kind.robot_kind not in ROBOT_KINDS:
        raise ValueError(f"{kind.name}: no robot kind {kind.robot_kind!r}")
    JOB_KINDS[kind.name] = kind
    try:
        yield kind
    finally:
        del JOB_KINDS[kind.name]


__all__ = ["JOB_KINDS", "ROBOT_KINDS", "registered"]
