"""The interoperability commands: ``planar-tui export`` (a preset's serial robot as MJCF
or URDF) and ``planar-tui import`` (a URDF or MJCF arm as a ``[robot]`` preset). They
parse options and print; the work is :mod:`planar_tui.interop.exchange`'s. Problems are
one line and exit code 2; no existing file is ever replaced."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from planar_tui.cli import load_presets, reported_errors, stderr, stdout
from planar_tui.errors import PresetError

#: ``export --format``'s values (:data:`planar_tui.interop.exchange.FORMATS`, kept here
#: so that ``--help`` imports nothing of the core).
EXPORT_FORMATS = ("mjcf", "urdf")


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
            "its label or output name) instead of the preset's [robot] table.",
        ),
    ] = None,
    format_name: Annotated[
        str | None, typer.Option("--format", "-f", metavar="FORMAT", help="mjcf or urdf.")
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="The file to write (never replaced).")
    ] = None,
) -> None:
    """Write a preset's serial robot as an MJCF (MuJoCo) or URDF model (docs/interop.md)."""
    with reported_errors():
        if format_name not in EXPORT_FORMATS:
            problem = "missing" if format_name is None else f"is {format_name!r}"
            raise PresetError("command line", "--format", problem, " or ".join(EXPORT_FORMATS))
        if out is None:
            raise PresetError("command line", "--out", "missing", "the file to write")
        from planar_tui.batch import check_writable
        from planar_tui.interop.exchange import export_robot, preset_robot

        (loaded,) = load_presets([preset])
        robot_model = preset_robot(loaded, robot)
        check_writable(out, "model file")
        written = export_robot(robot_model, format_name, out)
    stdout.print(f"wrote {written}", markup=False, highlight=False, soft_wrap=True)


def import_command(
    source: Annotated[Path, typer.Argument(help="A URDF (.urdf) or MJCF (.xml, .mjcf) file.")],
    out: Annotated[
        Path | None,
        typer.Option("--out", "-o", help="The preset to write (never replaced); default stdout."),
    ] = None,
) -> None:
    """Read a serial arm of revolute joints from a URDF or MJCF file as a [robot] preset."""
    with reported_errors():
        from planar_tui.batch import check_writable
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
