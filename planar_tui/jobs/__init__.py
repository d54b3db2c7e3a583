"""Registries of robot kinds and job kinds.

Adding a job kind = one module here with a settings dataclass, a ``parse`` and a ``dump``
function and a :class:`~planar_tui.jobs.base.JobKind`, plus one runner module; then one
line in :data:`JOB_KINDS`. Nothing here imports numba, SALib or Textual.
"""

from planar_tui.jobs.base import JobKind, JobResult, RobotKind
from planar_tui.jobs.sensitivity import SENSITIVITY
from planar_tui.jobs.simulate import SIMULATE
from planar_tui.jobs.torques import TORQUES
from planar_tui.jobs.workspace import WORKSPACE
from planar_tui.model import SERIAL_ROBOT_KEYS, parse_serial_robot
from planar_tui.workspace.model import ROBOT3RRR_KEYS, parse_robot3rrr

ROBOT_KINDS: dict[str, RobotKind] = {
    "robot": RobotKind("robot", SERIAL_ROBOT_KEYS, parse_serial_robot),
    "robot3rrr": RobotKind("robot3rrr", ROBOT3RRR_KEYS, parse_robot3rrr),
}

JOB_KINDS: dict[str, JobKind] = {
    kind.name: kind
    for kind in (
        SIMULATE,
        TORQUES,
        SENSITIVITY,
        WORKSPACE,
    )
}

__all__ = ["JOB_KINDS", "ROBOT_KINDS", "JobKind", "JobResult", "RobotKind"]
