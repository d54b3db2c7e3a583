"""What a robot's mechanism gives the path core: its actuators' names
(:class:`PathModel`) and, at sampled platform states, its actuators' coordinates, rates,
accelerations and efforts (:class:`PathSolution`), with a status per time.

The status of a time is :data:`OK` or ``code * 10 + leg`` (leg 1-based; 0 where no one leg
is at fault) of its first problem, ``code`` one of :data:`PROBLEMS`'s keys; the robots'
kernels write the same codes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

OK = 0
#: A problem's code and its words, by the status ``code * 10 + leg``.
PROBLEMS = {
    1: "cannot close (out of reach)",
    2: "leaves its joint limits",
    3: "meets a serial (type I) singularity",
    4: "meets a parallel (type II) singularity",
}
#: Relative threshold below which a pose is singular: |sin| of a leg's folding angle, or
#: |det A| over the product of its rows' norms.
SINGULAR_RELATIVE = 1e-9


@dataclass(frozen=True)
class PathModel:
    """A robot's path columns: its pose's dimension (3: ``x, y, phi``; 2: ``x, y``), its
    actuators' coordinate (``theta``: revolute, rad; ``rho``: prismatic, m in SI and cm in
    the CSV) and effort (``tau``, N m; ``force``, N), and their number."""

    pose_dimension: int
    actuators: int
    prismatic: bool = False

    @property
    def coordinate(self) -> str:
        return "rho" if self.prismatic else "theta"

    @property
    def effort(self) -> str:
        return "force" if self.prismatic else "tau"

    @property
    def effort_unit(self) -> str:
        return "N" if self.prismatic else "Nm"


@dataclass(frozen=True)
class PathSolution:
    """Per sampled time (rows): actuator coordinates (an angle within its joint limit's
    turn, or in [-pi, pi) without one), rates and accelerations (SI: rad or m), efforts (N m or N), status (:data:`OK` or ``code * 10 + leg``) and the loop
    closure's residual (m; the largest over the legs)."""

    coordinate: Any
    rate: Any
    acceleration: Any
    effort: Any
    status: Any
    closure_m: Any


def problem_text(status: int) -> str:
    """The words of a status: ``"leg 2 cannot close (out of reach)"``."""
    code, leg = divmod(int(status), 10)
    words = PROBLEMS.get(code, f"fails (status {status})")
    return f"leg {leg} {words}" if leg else f"the platform {words}"
