"""The job kinds' own commands (``planar-tui simulate``, ``workspace`` ...), generated from
each kind's declared :class:`~planar_tui.jobkind.Command`: its overriding options, its
extra-table options and its view flag, plus the options every job command has."""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Annotated, Any

import typer

from planar_tui.cli.interop import KIND_OPTIONS, job_exports
from planar_tui.cli.output import check_figure_option, load_presets, reported_errors
from planar_tui.cli.running import run_jobs
from planar_tui.errors import PresetError
from planar_tui.jobkind import JobKind
from planar_tui.overrides import apply_overrides, select_jobs
from planar_tui.plan import plan_run
from planar_tui.registry import JOB_KINDS

PresetArg = Annotated[
    str, typer.Argument(help="Preset file, or a bundled preset name (see `planar-tui presets`).")
]
OutOption = Annotated[
    Path | None,
    typer.Option(
        "--out", "-o", help="CSV file to write (with several jobs: FILE-1.csv, FILE-2.csv ...)."
    ),
]
OutDirOption = Annotated[
    Path, typer.Option("--out-dir", "-d", help="Folder for the presets' output files.")
]
JobOption = Annotated[
    list[str] | None,
    typer.Option(
        "--job",
        "-j",
        metavar="NAME",
        help="Run only this job, named by its table key (workspace[2], simulate), "
        "PRESET:KEY or its output file name; repeatable.",
    ),
]
PlotOption = Annotated[
    Path | None,
    typer.Option(
        "--plot",
        metavar="FILE",
        help="Also draw the result's figure into FILE (.svg, .png or .pdf; with several "
        "jobs: FILE-1.png, FILE-2.png ...); overrides the jobs' `plot` keys.",
    ),
]


def run_kind(
    kind: str,
    preset_argument: str,
    out: Path | None,
    out_dir: Path,
    options: Mapping[str, object] | None = None,
    *,
    names: Sequence[str] | None = None,
    extra_out: Mapping[str, Path | None] | None = None,
    show: bool = True,
    plot: Path | None = None,
    exports: Mapping[str, Any] | None = None,
) -> None:
    """Run the jobs of one kind in a preset: all of them, or those ``names`` selects
    (``--job``); ``options`` are the command-line overrides by option name, applied and
    checked by :func:`planar_tui.overrides.apply_overrides`; ``exports`` the kind's
    interoperability options (:data:`planar_tui.cli.interop.KIND_OPTIONS`)."""
    with reported_errors():
        check_figure_option(plot)
        (preset,) = load_presets([preset_argument])
        jobs = preset.jobs_of(kind)
        if not jobs:
            raise PresetError(
                preset.path, kind, f"no [{kind}] job in this preset", f"a [{kind}] table"
            )
        jobs = select_jobs(jobs, names)
        if options:
            jobs = apply_overrides(jobs, options)
        plan = plan_run(jobs, out_dir, out=out, extra_out=extra_out, plot=plot)

        command = JOB_KINDS[kind].command
        run_jobs(
            plan,
            kind if command is None else command.name,
            show=show,
            after=job_exports(plan, exports or {}),
        )


def _parameter(name: str, annotation: Any, default: Any) -> inspect.Parameter:
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, annotation=annotation, default=default
    )


def kind_command(kind: JobKind) -> Callable[..., None]:
    """The function Typer makes ``planar-tui NAME`` of: its parameters are the preset, the
    kind's options (:class:`~planar_tui.jobkind.Option`: overrides, as given by Typer),
    ``--job``, ``--out``, the extra-table options, the view flag, ``--out-dir`` and
    ``--plot``; it runs :func:`run_kind`."""
    declared = kind.command
    assert declared is not None
    overrides = {f"option_{n}": option for n, option in enumerate(declared.options)}
    outputs = {f"output_{n}": output for n, output in enumerate(declared.outputs)}
    parameters = [
        inspect.Parameter("preset", inspect.Parameter.POSITIONAL_OR_KEYWORD, annotation=PresetArg)
    ]
    for parameter, option in overrides.items():
        names = (option.name, option.short) if option.short else (option.name,)
        value = list[option.type] if option.many else option.type
        info = typer.Option(*names, help=option.help)
        parameters.append(_parameter(parameter, Annotated[value | None, info], None))
    parameters.append(_parameter("job_name", JobOption, None))
    parameters.append(_parameter("out", OutOption, None))
    for parameter, output in outputs.items():
        info = typer.Option(output.name, help=output.help)
        parameters.append(_parameter(parameter, Annotated[Path | None, info], None))
    if declared.view is not None:
        flag, text = declared.view
        parameters.append(_parameter("show", Annotated[bool, typer.Option(flag, help=text)], True))
    parameters.append(_parameter("out_dir", OutDirOption, Path(".")))
    parameters.append(_parameter("plot", PlotOption, None))
    exports = KIND_OPTIONS.get(kind.name, ())
    parameters += [_parameter(name, annotation, None) for name, annotation in exports]

    def command(preset: str, **given: Any) -> None:
        options = {option.name: given[parameter] for parameter, option in overrides.items()}
        extra_out = {output.table: given[parameter] for parameter, output in outputs.items()}
        run_kind(
            kind.name,
            preset,
            given["out"],
            given["out_dir"],
            options,
            names=given["job_name"],
            extra_out=extra_out,
            show=given.get("show", True),
            plot=given["plot"],
            exports={name: given[name] for name, _ in exports},
        )

    command.__name__ = declared.name
    command.__doc__ = declared.help
    command.__signature__ = inspect.Signature(parameters)  # type: ignore[attr-defined]
    command.__annotations__ = {p.name: p.annotation for p in parameters}
    return command
