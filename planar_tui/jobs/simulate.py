"""The ``[simulate]`` job: RK4 forward dynamics under constant joint torques."""

from __future__ import annotations

from dataclasses import dataclass

from planar_tui.jobs.base import JobKind
from planar_tui.model import SerialRobot
from planar_tui.presets import TableReader


@dataclass(frozen=True)
class SimulateSpec:
    """Settings of one forward-dynamics run (angles are relative joint angles)."""

    duration_s: float
    step_s: float
    theta0_deg: tuple[float, ...]
    omega0_deg_s: tuple[float, ...]
    torques_Nm: tuple[float, ...]
    every: int = 1

    @property
    def n_steps(self) -> int:
        """Number of RK4 steps: ``round(duration_s / step_s)``."""
        return max(1, round(self.duration_s / self.step_s))


def parse_simulate(reader: TableReader, robot: SerialRobot) -> SimulateSpec:
    """Validate a ``[simulate]`` table against its robot."""
    n = robot.n_links
    zeros = (0.0,) * n
    duration_s = reader.number("duration_s", positive=True)
    step_s = reader.number("step_s", positive=True)
    if step_s > duration_s:
        raise reader.error(
            "step_s",
            f"is {step_s:g} s, longer than duration_s = {duration_s:g} s",
            "step_s <= duration_s",
        )
    return SimulateSpec(
        duration_s=duration_s,
        step_s=step_s,
        theta0_deg=reader.numbers("theta0_deg", zeros, length=n),
        omega0_deg_s=reader.numbers("omega0_deg_s", zeros, length=n),
        torques_Nm=reader.numbers("torques_Nm", zeros, length=n),
        every=reader.integer("every", 1, minimum=1),
    )


def dump_simulate(spec: SimulateSpec) -> dict:
    """The settings as a ``[simulate]`` table."""
    return {
        "duration_s": spec.duration_s,
        "step_s": spec.step_s,
        "theta0_deg": list(spec.theta0_deg),
        "omega0_deg_s": list(spec.omega0_deg_s),
        "torques_Nm": list(spec.torques_Nm),
        "every": spec.every,
    }


SIMULATE = JobKind(
    name="simulate",
    robot_kind="robot",
    keys=("duration_s", "step_s", "theta0_deg", "omega0_deg_s", "torques_Nm", "every"),
    parse=parse_simulate,
    dump=dump_simulate,
    runner="planar_tui.runners.simulate:run_simulate",
    summary="RK4 forward dynamics under constant torques",
)
