"""What ``planar-tui export`` and ``planar-tui import`` do, front-end free (the CLI module
only parses options and prints): pick a preset's serial robot, write it as MJCF or URDF,
read a URDF or MJCF file back as a ``[robot]`` preset. Every problem is a
:class:`~planar_tui.errors.PresetError` (one line, exit 2); nothing existing is replaced
(:mod:`.files`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError
from planar_tui.interop.files import write_new_text
from planar_tui.interop.mjcf import robot_mjcf
from planar_tui.interop.robot_import import ImportedRobot, preset_text, read_robot
from planar_tui.interop.urdf import robot_urdf

#: ``--format`` of ``export``: the writer of each format.
FORMATS: dict[str, Callable[[SerialRobot], str]] = {"mjcf": robot_mjcf, "urdf": robot_urdf}
#: The table a preset's serial robot is in (``--robot robot``).
ROBOT_TABLE = "robot"


def serial_jobs(preset: Any) -> list[Any]:
    """The preset's jobs that run on a serial robot (their own or the preset's)."""
    return [job for job in preset.jobs if isinstance(job.robot, SerialRobot)]


def preset_robot(preset: Any, key: str | None) -> SerialRobot:
    """The robot ``--robot KEY`` names: ``robot`` (the default) the preset's ``[robot]``
    table, else a job by its table key (``sensitivity[2]``), label or output file name
    (that job's own robot, or the preset's it runs on). Without ``--robot`` and without a
    ``[robot]`` table, the jobs' robot when they all run on one."""
    jobs = serial_jobs(preset)
    keys = [ROBOT_TABLE] if ROBOT_TABLE in preset.robots else []
    keys += [job.key for job in jobs]
    expected = "one of " + ", ".join(keys) if keys else "a preset with a [robot] table"
    if key is None or key == ROBOT_TABLE:
        if ROBOT_TABLE in preset.robots:
            return preset.robots[ROBOT_TABLE]
        robots = list(dict.fromkeys(job.robot for job in jobs))
        if key is None and len(robots) == 1:
            return robots[0]
        problem = (
            "no serial robot: a 3-RRR is not exported"
            if not jobs
            else "no [robot] table, and its jobs' robots differ: name one"
        )
        raise PresetError(preset.path, "--robot", problem, expected)
    for job in jobs:
        if key in (job.key, job.label, job.output):
            return job.robot
    raise PresetError(
        "command line",
        "--robot",
        f"is {key!r}, no job on a serial robot in {preset.path}",
        expected,
    )


def export_robot(robot: SerialRobot, format_name: str, out: Path) -> Path:
    """Write ``robot`` as ``format_name`` (``mjcf``, ``urdf``) to the new file ``out``."""
    writer = FORMATS.get(format_name)
    if writer is None:
        raise PresetError("command line", "--format", f"is {format_name!r}", " or ".join(FORMATS))
    return write_new_text(out, writer(robot), "--out")


def import_robot(source: Path) -> tuple[ImportedRobot, str]:
    """``(imported, preset text)`` of a URDF or MJCF file; the text is checked to load as
    a preset (a value outside ``[robot]``'s ranges is refused naming the source file)."""
    import tomllib

    from planar_tui.presets import parse_preset

    if Path(source).is_dir():
        raise PresetError(source, "(file)", "is a folder", "a URDF or MJCF file")
    imported = read_robot(source)
    text = preset_text(imported, source)
    parse_preset(source, tomllib.loads(text))
    return imported, text


def write_preset(text: str, out: Path) -> Path:
    """Write an imported preset to the new file ``out``."""
    return write_new_text(out, text, "--out")
