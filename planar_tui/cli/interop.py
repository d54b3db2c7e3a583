"""The interoperability commands and options: ``planar-tui export`` (a preset's serial
robot as MJCF or URDF), ``planar-tui import`` (a URDF or MJCF arm as a ``[robot]``
preset), and the job commands' ``--export-problem DIR`` (sensitivity, motion: the SALib
hand-off) and ``--format netcdf`` (motion). They parse options and print; the work is
:mod:`planar_tui.interop`'s. Problems are one line and exit code 2, found before any job
runs; no existing file is ever replaced."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from planar_tui.batch import check_writable, numbered_path
from planar_tui.cli.output import load_presets, reported_errors, stderr, stdout
from planar_tui.errors import OutputFailed, PresetError

if TYPE_CHECKING:
    from planar_tui.plan import RunPlan

#: ``export --format``'s values (:data:`planar_tui.interop.exchange.FORMATS`, kept here
#: so that ``--help`` imports nothing of the core).
EXPORT_FORMATS = ("mjcf", "urdf")
#: ``export --robot``'s parallel robots, written as closed chains (MJCF only):
#: :data:`planar_tui.interop.exchange.CLOSED_CHAINS`.
CLOSED_CHAIN_TABLES = ("robot3rrr", "robot5r")


def export_command(
    preset: Annotated[
        str,
        typer.Argument(help="Preset file, or a bundled preset name (see `planar-tui presets`)."),
    ],
    robot: Annotated[
        str | None,
        typer.Option(
            "--robot",
            metavar="KEY",
            help="The robot of this job (sensitivity[2], "
            "its label or output name) instead of the preset's [robot] table; robot3rrr or "
            "robot5r: that parallel robot as a closed chain (MJCF only).",
        ),
    ] = None,
    format_name: Annotated[
        str | None, typer.Option("--format", "-f", metavar="FORMAT", help="mjcf or urdf.")
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="The file to write (never replaced).")
    ] = None,
) -> None:
    """Write a preset's serial robot as an MJCF (MuJoCo) or URDF model, or its 3-RRR or
    five-bar as a closed-chain MJCF (docs/interop.md, docs/closed-chain-export.md)."""
    with reported_errors():
        if format_name is None:
            raise PresetError("command line", "--format", "missing", " or ".join(EXPORT_FORMATS))
        if out is None:
            raise PresetError("command line", "--out", "missing", "the file to write")
        from planar_tui.interop import exchange

        closed = robot if robot in CLOSED_CHAIN_TABLES else None
        exchange.check_format(format_name, closed)
        (loaded,) = load_presets([preset])
        if closed is None:
            model: Any = exchange.preset_robot(loaded, robot)
        else:
            model = exchange.preset_chain(loaded, closed)
        check_writable(out, "model file")
        if closed is None:
            written = exchange.export_robot(model, format_name, out)
        else:
            written = exchange.export_chain(model, out)
    stdout.print(f"wrote {written}", markup=False, highlight=False, soft_wrap=True)


def import_command(
    source: Annotated[Path, typer.Argument(help="A URDF (.urdf) or MJCF (.xml, .mjcf) file.")],
    out: Annotated[
        Path | None,
        typer.Option("--out", "-o", help="The preset to write (never replaced); default stdout."),
    ] = None,
) -> None:
    """Read a serial arm of revolute joints (URDF or MJCF) as a preset's robot table."""
    with reported_errors():
        from planar_tui.interop.exchange import import_robot, write_preset

        imported, text = import_robot(source)
        if out is not None:
            check_writable(out, "preset file")
        written = None if out is None else write_preset(text, out)
    for note in imported.notes:
        stderr.print(f"note: {note}", markup=False, highlight=False, soft_wrap=True)
    if written is None:
        typer.echo(text, nl=False)
    else:
        stdout.print(f"wrote {written}", markup=False, highlight=False, soft_wrap=True)


#: The commands, as the CLI registers them: (name, function).
COMMANDS = (("export", export_command), ("import", import_command))


ExportProblemOption = Annotated[
    Path | None,
    typer.Option(
        "--export-problem",
        metavar="DIR",
        help="Also write each design's SALib problem (JSON), sample matrix and model outputs "
        "(.npy) into DIR/METHOD/ (with several jobs: DIR-1, DIR-2 ...); never replaces a file.",
    ),
]
FormatOption = Annotated[
    str | None,
    typer.Option(
        "--format",
        metavar="FORMAT",
        help="csv (the default) or netcdf: also the band and the indices as one NetCDF "
        "file, the band CSV's name with .nc (pip install 'planar-tui[netcdf]').",
    ),
]
#: The options each job command gets (by kind), as (parameter, annotation).
KIND_OPTIONS: dict[str, tuple[tuple[str, Any], ...]] = {
    "sensitivity": (("export_problem", ExportProblemOption),),
    "motion_uncertainty": (("export_problem", ExportProblemOption), ("format", FormatOption)),
}
FORMATS = ("csv", "netcdf")


def job_exports(plan: RunPlan, given: Mapping[str, Any]) -> Callable[[Any, Any], None] | None:
    """Check the export options against ``plan`` before anything runs (a file that would
    be replaced, an unknown format, a missing extra: :class:`PresetError`) and return what
    writes them after each job (``None`` when none was asked)."""
    directory, format_name = given.get("export_problem"), given.get("format")
    if format_name is not None and format_name not in FORMATS:
        raise PresetError("command line", "--format", f"is {format_name!r}", " or ".join(FORMATS))
    netcdf = format_name == "netcdf"
    if directory is None and not netcdf:
        return None
    from planar_tui.interop import files, salib_problem
    from planar_tui.interop import netcdf as nc

    if netcdf:
        nc.require_netcdf()
    targets: dict[int, tuple[Path | None, Path | None]] = {}
    for number, output in enumerate(plan.jobs, start=1):
        folder = None if directory is None else numbered_path(directory, number, len(plan.jobs))
        if folder is not None:
            planned = salib_problem.planned_files(output.job, folder)
            files.refuse_existing(planned, "--export-problem")
            for planned_file in planned:
                check_writable(planned_file, "SALib file")
        path = nc.netcdf_path(output.main) if netcdf else None
        if path is not None:
            files.refuse_existing([path], "--format")
            check_writable(path, "NetCDF file")
        targets[id(output.job)] = (folder, path)

    def write(job: Any, result: Any) -> None:
        folder, path = targets[id(job)]
        try:
            if folder is not None:
                written = salib_problem.export_job(job, result, folder)
                stderr.print(
                    f"{job.label}: SALib runs in {folder} ({len(written)} files)",
                    markup=False,
                    highlight=False,
                    soft_wrap=True,
                )
            if path is not None:
                nc.export_job(job, result, path)
                stderr.print(
                    f"{job.label}: NetCDF {path}", markup=False, highlight=False, soft_wrap=True
                )
        except PresetError as error:  # after the job ran (a disk full): exit 1, CSVs kept
            raise OutputFailed(error.path, error.problem) from None

    return write
