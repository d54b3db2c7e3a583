"""What ``planar-tui export`` and ``planar-tui import`` do, front-end free (the CLI module
only parses options and prints): pick a preset's serial robot, write it as MJCF or URDF,
or its parallel robot (``--robot robot3rrr``, ``--robot robot5r``) as a closed-chain MJCF
(:mod:`.closed_mjcf`; URDF is refused: it has no loops), read a URDF or MJCF file back as
a ``[robot]`` preset. Every problem is a
:class:`~planar_tui.errors.PresetError` (one line, exit 2); nothing existing is replaced
(:mod:`.files`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from planar_tui.dynamics.robot import SerialRobot
from planar_tui.errors import PresetError
from planar_tui.interop.closed_chain import ClosedChain, Home, fivebar_chain, rrr_chain
from planar_tui.interop.closed_mjcf import chain_mjcf
from planar_tui.interop.files import write_new_text
from planar_tui.interop.mjcf import robot_mjcf
from planar_tui.interop.robot_import import ImportedRobot, preset_text, read_robot
from planar_tui.interop.urdf import robot_urdf
from planar_tui.presets import parse_preset
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS

#: ``--format`` of ``export``: the writer of each format.
FORMATS: dict[str, Callable[[SerialRobot], str]] = {"mjcf": robot_mjcf, "urdf": robot_urdf}
#: The table a preset's serial robot is in (``--robot robot``).
ROBOT_TABLE = "robot"
#: Each closed chain's path job kind, whose first job gives the exported home pose.
PATH_KINDS = {"robot3rrr": "path3rrr", "robot5r": "path5r"}
#: The parallel robots exported as closed chains: their table, and what builds the chain.
CLOSED_CHAINS: dict[str, Callable[[Any, Any, Home | None], ClosedChain]] = {
    "robot3rrr": rrr_chain,
    "robot5r": fivebar_chain,
}


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
    keys += list(CLOSED_CHAINS)
    expected = "one of " + ", ".join(keys)
    if key is None or key == ROBOT_TABLE:
        if ROBOT_TABLE in preset.robots:
            return preset.robots[ROBOT_TABLE]
        robots = list(dict.fromkeys(job.robot for job in jobs))
        if key is None and len(robots) == 1:
            return robots[0]
        problem = (
            "no serial robot: name a parallel one (a closed chain, MJCF only)"
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


def preset_chain(preset: Any, key: str) -> ClosedChain:
    """The parallel robot ``--robot KEY`` (a key of :data:`CLOSED_CHAINS`) names: the
    preset's table of that name, else the robot its jobs of that kind run on."""
    robot = preset.robots.get(key)
    if robot is None:
        model = ROBOT_KINDS[key].model
        jobs = [job for job in preset.jobs if isinstance(job.robot, model)]
        robots = list(dict.fromkeys(job.robot for job in jobs))
        if len(robots) != 1:
            raise PresetError(
                preset.path, f"[{key}]", "missing", f"a [{key}] table (or a job on one robot)"
            )
        robot = robots[0]
    return CLOSED_CHAINS[key](robot, preset.path, path_home(preset, key, robot))


def path_home(preset: Any, key: str, robot: Any) -> Home | None:
    """The start of the preset's first path job on ``robot`` (its ``from_pose`` in the
    working mode its kind's ``prepare`` resolves), or ``None``."""
    for job in preset.jobs:
        if job.kind == PATH_KINDS[key] and job.robot == robot:
            kind = JOB_KINDS[job.kind]
            spec: Any = job.spec if kind.prepare is None else kind.prepare(job)
            return Home(tuple(spec.from_pose), tuple(spec.elbow), f"{job.key}.from_pose")
    return None


def check_format(format_name: str, table: str | None) -> None:
    """Refuse a format that cannot hold the robot: an unknown one, or URDF for the closed
    chain of the table ``table`` (URDF describes only trees of links)."""
    if format_name not in FORMATS:
        raise PresetError("command line", "--format", f"is {format_name!r}", " or ".join(FORMATS))
    if table is not None and format_name != "mjcf":
        raise PresetError(
            "command line",
            "--format",
            f"is {format_name!r}: URDF has no closed loops and [{table}] is a closed chain",
            "mjcf (connect equality constraints close its loops)",
        )


def export_robot(robot: SerialRobot, format_name: str, out: Path) -> Path:
    """Write ``robot`` as ``format_name`` (``mjcf``, ``urdf``) to the new file ``out``."""
    check_format(format_name, None)
    return write_new_text(out, FORMATS[format_name](robot), "--out")


def export_chain(chain: ClosedChain, out: Path) -> Path:
    """Write the closed chain ``chain`` as MJCF to the new file ``out``."""
    return write_new_text(out, chain_mjcf(chain), "--out")


def import_robot(source: Path) -> tuple[ImportedRobot, str]:
    """``(imported, preset text)`` of a URDF or MJCF file; the text is checked to load as
    a preset (a value outside ``[robot]``'s ranges is refused naming the source file)."""
    import tomllib

    if Path(source).is_dir():
        raise PresetError(source, "(file)", "is a folder", "a URDF or MJCF file")
    imported = read_robot(source)
    text = preset_text(imported, source)
    parse_preset(source, tomllib.loads(text))
    return imported, text


def write_preset(text: str, out: Path) -> Path:
    """Write an imported preset to the new file ``out``."""
    return write_new_text(out, text, "--out")
