"""The registries of robot kinds and job kinds: one line per kind.

A new job kind is one module in its domain package ending with a
:class:`~planar_tui.jobkind.JobKind`, plus one line in :data:`JOB_KINDS`; the preset
loader, the batch service, the CLI's ``run``, preset saving and the app pick it up.
Nothing imported here loads numba, SALib or Textual (runners import them when they run).
"""

from planar_tui.dynamics import robot as serial_robot
from planar_tui.dynamics import simulate, torques
from planar_tui.jobkind import JobKind, RobotKind
from planar_tui.motion import job as motion_uncertainty
from planar_tui.sensitivity import job as sensitivity
from planar_tui.workspace import job as workspace
from planar_tui.workspace import robot as robot3rrr

ROBOT_KINDS: dict[str, RobotKind] = {
    kind.name: kind
    for kind in (
        serial_robot.ROBOT_KIND,
        robot3rrr.ROBOT_KIND,
    )
}

JOB_KINDS: dict[str, JobKind] = {
    kind.name: kind
    for kind in (
        simulate.JOB_KIND,
        torques.JOB_KIND,
        sensitivity.JOB_KIND,
        workspace.JOB_KIND,
        motion_uncertainty.JOB_KIND,
    )
}

__all__ = ["JOB_KINDS", "ROBOT_KINDS"]
