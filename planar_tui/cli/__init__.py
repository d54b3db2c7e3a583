"""The ``planar-tui`` command line (Typer).

Batch jobs run from TOML presets and write CSV. Exit codes: 0 ok, 1 a job failed,
2 bad input (preset or option), 130 interrupted (Ctrl-C), 143 terminated (SIGTERM).
Progress goes to stderr (a bar in a terminal; in a log or pipe, plain lines at each stage
and at least every 10 s: :mod:`planar_tui.cli.loglines`); tables and summaries to stdout.
Heavy modules (numpy, numba, SALib, Textual) are imported only when a job or the app
runs, so ``planar-tui --help`` is instant.

The commands are made by :func:`build_app` when the CLI runs, from the registry: each
job kind's own command (:mod:`planar_tui.cli.kinds`, from its declared
:class:`~planar_tui.jobkind.Command`) and the commands that are not one kind's
(:data:`planar_tui.cli.commands.COMMANDS`: ``tui``, ``run``, ``plot``, ``sweep``,
``warmup``, ``presets``; a new one is a function there and a line in that tuple). A
command only turns its options into a :class:`~planar_tui.plan.RunPlan`
(:func:`planar_tui.plan.plan_run`) and prints (:mod:`planar_tui.cli.running`,
:mod:`planar_tui.cli.output`).
"""

from __future__ import annotations

import gc
import os
import signal
import sys
from typing import Annotated, Any

import typer

from planar_tui import __version__, csvio
from planar_tui.cli import output
from planar_tui.cli.commands import COMMANDS, open_app
from planar_tui.cli.kinds import kind_command
from planar_tui.cli.output import (
    Command,
    Group,
    fail,
    job_progress_display,
    progress_bar,
    stderr,
    stdout,
)
from planar_tui.errors import ExitCode
from planar_tui.registry import JOB_KINDS
from planar_tui.runtime import configure_process

__all__ = ["app", "build_app", "job_progress_display", "main", "progress_bar"]

HELP = (
    "Terminal workbench for planar robots: NOC dynamics, Sobol/eFAST sensitivity, "
    "3-RRR workspace by interval analysis. Without a command, opens the Textual app "
    "(in a terminal; without one, prints this help and exits with code 2)."
)


def _notice(text: str) -> None:
    """A one-line note of the core (stale temporary files removed) on stderr."""
    stderr.print(text, markup=False, highlight=False, soft_wrap=True)


def version_callback(value: bool) -> None:
    if value:
        stdout.print(f"planar-tui {__version__}")
        raise typer.Exit()


def root(
    context: typer.Context,
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=version_callback, is_eager=True, help="Print the version."
        ),
    ] = False,
) -> None:
    """Without a command: open the Textual app on a bundled preset (in a terminal)."""
    gc.enable()  # off while the CLI loaded (planar_tui.entry.main)
    csvio.notice = _notice
    if context.invoked_subcommand is None:
        if not (sys.stdin.isatty() and sys.stdout.isatty()):
            help_text = context.get_help()  # Typer's rich help prints itself, returns ""
            if help_text:
                typer.echo(help_text)
            raise fail(
                "error: no command given, and the app needs a terminal (stdin and stdout "
                "are not both one): name a command, e.g. planar-tui run PRESET"
            )
        open_app(None)


def build_app(command: str | None = None) -> typer.Typer:
    """The ``planar-tui`` Typer app, its job commands made from the registry now (a kind
    registered before this call has its command, :func:`planar_tui.registry.registered`).

    ``command`` is the command about to run (the first argument), when known: if it is one
    of the commands that are not a kind's (``run``, ``sweep``, ``plot`` ...), the kinds'
    own commands are left out, so that no job kind's module is imported for it (``run``
    loads only the kinds of the jobs it runs); any other value, or none, builds them all
    (the help lists them, a mistyped command is matched against them)."""
    app = typer.Typer(
        name="planar-tui",
        cls=Group,
        help=HELP,
        add_completion=False,
        no_args_is_help=False,
        pretty_exceptions_enable=False,
    )
    app.callback(invoke_without_command=True)(root)
    (first, function), *others = COMMANDS  # tui, then the kinds' commands, then the rest
    app.command(first, cls=Command)(function)
    if command not in dict(COMMANDS):
        for kind in JOB_KINDS.values():
            if kind.command is not None:
                app.command(kind.command.name, cls=Command, help=kind.command.help)(
                    kind_command(kind)
                )
    for name, function in others:
        app.command(name, cls=Command)(function)
    return app


def __getattr__(name: str) -> Any:
    """``planar_tui.cli.app``: the app built now (:func:`build_app`)."""
    if name == "app":
        return build_app()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def main() -> None:
    """Run the CLI (called by :func:`planar_tui.entry.main`, the console script): Ctrl-C
    raises ``KeyboardInterrupt`` again (and is remembered, :data:`_INTERRUPTED`) and
    SIGTERM has its default action, except while jobs run (:func:`sigterm_as_interrupt`)."""
    try:
        sys.unraisablehook = output._unraisable
        signal.signal(signal.SIGINT, output._interrupt)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        configure_process()
        build_app(sys.argv[1] if len(sys.argv) > 1 else None)(prog_name="planar-tui")
    except (KeyboardInterrupt, Exception) as error:
        # Ctrl-C before Typer's own handling starts: while it builds the Click command
        # from the commands' signatures (~50 ms after the imports), or while a kind's
        # module is imported for them, where one landing in a dataclass field's
        # ``__set_name__`` surfaces as a RuntimeError caused by it
        # (:func:`output.caused_by_interrupt`).
        if not output.caused_by_interrupt(error):
            raise
        if not output._REPORTED:
            os.write(2, b"interrupted: nothing was written\n")
        output.exit_now_if_compiling(ExitCode.INTERRUPTED)
        sys.exit(ExitCode.INTERRUPTED)
    except SystemExit as exit_:
        # Typer turns a Ctrl-C outside the commands' own handling (while a command's
        # modules load, say) into a silent exit 130: say it in one line too.
        if exit_.code == ExitCode.INTERRUPTED and not output._REPORTED:
            os.write(2, b"interrupted: nothing was written\n")
        output.exit_now_if_compiling(exit_.code)
        raise
    finally:
        # Exit without the interpreter's last full garbage collection over every object of
        # numba, rich and typer: ~0.3 s of a jitted command's wall time (measured with
        # `planar-tui run paper-a-table4 paper-a-table5`). Reference counting still frees.
        gc.freeze()


if __name__ == "__main__":
    main()
    sys.exit(0)
