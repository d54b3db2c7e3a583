"""What the ``planar-tui`` commands share: the consoles, the one-line outcome and exit
code of an error or an interrupt, the checks of the run options, and the progress
displays (one bar per job, one per sweep)."""

from __future__ import annotations

import contextlib
import os
import re
import signal
import sys
import threading
import types
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

import typer
from rich.console import Console
from typer.core import TyperCommand, TyperGroup

try:  # Typer's private coercion API, used only with the Typer releases it was checked with
    from planar_tui.cli.coercion import install_common_values
except ImportError:
    install_common_values = None

from planar_tui import provenance
from planar_tui.cli.loglines import ProgressLog, clock_text, rate_of, rate_text, stage_title
from planar_tui.errors import Cancelled, ExitCode, PresetError, Terminated
from planar_tui.jobkind import resolve
from planar_tui.presets import load_preset
from planar_tui.progress import WAIT_FOR_THREAD, Progress
from planar_tui.resources import resolve_preset
from planar_tui.schema import FIGURE_SUFFIXES, figure_suffix_problem

if TYPE_CHECKING:
    from planar_tui.presets import Preset


class _FlagsWithoutMetavar:
    """Help for flags (``--map/--no-map``, ``--version``, ``--help``) without a value
    placeholder: Typer's rich help otherwise prints ``<bool>`` after them, as if they took
    a value. A flag's metavar is only ever shown in help. An argument is named in capitals
    in the usage line (``PRESET``; this Click shows ``{preset}``). Help texts are shown as
    written: Typer reads them as Rich markup, which would swallow ``[[sweep]]``, so
    brackets are escaped (:func:`rich.markup.escape`)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.help = _escaped(_reflowed(self.help))
        self.short_help = _escaped(_reflowed(self.short_help))

    def format_help(self, ctx, formatter):
        _import_help_formatter()
        return super().format_help(ctx, formatter)

    def collect_usage_pieces(self, ctx):
        """The usage line's pieces with a required argument as ``PRESET``, not Typer's
        ``{PRESET}`` (an optional one stays ``[NAME]``)."""
        pieces = super().collect_usage_pieces(ctx)
        return [re.sub(r"^\{(.+)\}(\.\.\.)?$", r"\1\2", piece) for piece in pieces]

    def get_params(self, ctx):
        params = super().get_params(ctx)
        for param in params:
            if getattr(param, "is_flag", False) and param.metavar is None:
                param.metavar = ""
            if param.param_type_name == "argument" and param.metavar is None:
                param.metavar = param.name.upper()  # not Click's ``{preset}``
            _coerce_common_values(param)
            if getattr(param, "help", None) and not getattr(param, "_escaped", False):
                param.help = _escaped(param.help)
                param._escaped = True
        return params


def _coerce_common_values(param) -> None:
    """Give a Typer parameter the pydantic-free coercion of :mod:`planar_tui.cli.coercion`
    where this Typer is one it was checked with; with any other Typer, Typer's own."""
    if install_common_values is not None:
        install_common_values(param)


def _reflowed(text: str | None) -> str | None:
    """``text`` with each paragraph (separated by an empty line) on one line: a docstring's
    line breaks would otherwise break the help's lines mid-sentence."""
    if text is None:
        return None
    paragraphs = re.split(r"\n\s*\n", text.strip())
    return "\n\n".join(" ".join(paragraph.split()) for paragraph in paragraphs)


def _escaped(text: str | None) -> str | None:
    """``text`` with Rich markup escaped (shown as written)."""
    from rich.markup import escape

    return None if text is None else escape(text)


class _Deferred(type):
    """The class of a stand-in for a class of another module (:func:`_import_help_formatter`):
    calling it or reading an attribute of it imports that module and forwards there."""

    _origin: tuple[str, str]

    def _real(cls):
        module, name = cls._origin
        return resolve(f"{module}:{name}")

    def __call__(cls, *args, **kwargs):
        return cls._real()(*args, **kwargs)

    def __getattr__(cls, name):
        return getattr(cls._real(), name)


#: What Typer's help formatter imports but ``planar-tui`` uses only in other cases:
#: Markdown help (``rich.markdown``: markdown_it, pygments), pretty tracebacks
#: (``rich.traceback``: rich.pretty, attrs; off here, ``pretty_exceptions_enable=False``).
_DEFERRED = (("rich.markdown", "Markdown"), ("rich.traceback", "Traceback"))


def _import_help_formatter() -> None:
    """Import Typer's rich help formatter (``typer.rich_utils``, the same help as ever)
    without the modules of :data:`_DEFERRED`: about 85 ms of a 0.3 s ``planar-tui --help``.
    While it imports, a stand-in module holds each of those classes (a :class:`_Deferred`
    that imports the real class when used); then the stand-ins leave ``sys.modules``, so
    any later import gets the real module."""
    if "typer.rich_utils" in sys.modules:
        return
    stand_ins = {}
    for module, name in _DEFERRED:
        if module not in sys.modules:
            stand_ins[module] = types.ModuleType(module)
            setattr(stand_ins[module], name, _Deferred(name, (), {"_origin": (module, name)}))
    sys.modules.update(stand_ins)
    try:
        import typer.rich_utils
    except ImportError:  # a Typer that wants more of those modules: load them for real
        sys.modules.pop("typer.rich_utils", None)
    finally:
        for module, stand_in in stand_ins.items():
            if sys.modules.get(module) is stand_in:
                del sys.modules[module]
    import typer.rich_utils  # noqa: F401


class Group(_FlagsWithoutMetavar, TyperGroup):
    """The ``planar-tui`` command group; it records the arguments it parses for the
    provenance sidecars (:data:`planar_tui.provenance.invoked`)."""

    def parse_args(self, ctx, args):
        provenance.invoked = ["planar-tui", *args]
        return super().parse_args(ctx, args)


class Command(_FlagsWithoutMetavar, TyperCommand):
    """A ``planar-tui`` command; an empty value of an option naming a file or folder is
    refused before it is parsed (:func:`refuse_empty_paths`)."""

    def parse_args(self, ctx, args):
        with reported_errors():
            refuse_empty_paths(self.params, args)
        return super().parse_args(ctx, args)


def refuse_empty_paths(params, args: Sequence[str]) -> None:
    """:class:`PresetError` for ``--out ''`` or ``--copy=`` where the option takes a path
    (``Path("")`` is ``.``: the current folder, which no one meant)."""
    options = {
        opt
        for param in params
        for opt in param.opts
        if getattr(getattr(param, "type_descriptor", None), "annotation", None) is Path
        and opt.startswith("-")
    }
    for at, arg in enumerate(args):
        if arg == "--":
            return
        name, equals, value = arg.partition("=")
        given = value if equals else (args[at + 1] if at + 1 < len(args) else None)
        if name in options and given == "":
            raise PresetError("command line", name, "is empty", "a file or folder path")


stdout = Console(highlight=False)
stderr = Console(stderr=True, highlight=False)

#: Whether this process has printed its one-line outcome (see :func:`main`).
_REPORTED = False
#: Set by every Ctrl-C (:func:`_interrupt`). The ``KeyboardInterrupt`` it raises can land
#: where Python can only report it and go on (a weakref callback of the import system:
#: "Exception ignored in ..."), so the runners' progress checks ask this too
#: (``should_stop``) and such a report is silenced (:func:`_unraisable`).
_INTERRUPTED = threading.Event()


def _interrupt(signum, frame) -> None:
    _INTERRUPTED.set()
    raise KeyboardInterrupt


def exit_now_if_compiling(code: object) -> None:
    """Exit at once (``os._exit(code)``, stdout and stderr flushed) while a cancelled
    kernel compilation still runs in a helper thread (:meth:`Progress.wait_for
    <planar_tui.progress.Progress.wait_for>`): the interpreter's shutdown under a thread
    inside LLVM printed an LLVM assertion (``DAG root value is not a chain!``) after the
    one-line outcome. Otherwise nothing: the usual exit follows."""
    if not any(
        thread.name == WAIT_FOR_THREAD and thread.is_alive() for thread in threading.enumerate()
    ):
        return
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    os._exit(code if isinstance(code, int) else 1)


def caused_by_interrupt(error: BaseException) -> bool:
    """Whether ``error`` is a Ctrl-C (a ``KeyboardInterrupt``), or one that Python wrapped
    on its way up: a ``KeyboardInterrupt`` raised inside a class body's ``__set_name__``
    (a dataclass field while a module is imported) reaches the caller as a
    :class:`RuntimeError` caused by it (Python 3.11). Only explicit causes are followed
    (``raise ... from``, as Python's wrap is): an error merely raised while a Ctrl-C was
    being handled (its ``__context__``, such as the exit of a command that already
    reported the interrupt) is its own, and Typer's and Click's exits never count."""
    if isinstance(error, (typer.Exit, typer.Abort)):
        return False
    seen: set[int] = set()
    cause: BaseException | None = error
    while cause is not None and id(cause) not in seen:
        if isinstance(cause, KeyboardInterrupt):
            return True
        seen.add(id(cause))
        cause = cause.__cause__
    return False


def _unraisable(unraisable) -> None:
    """``sys.unraisablehook``: a Ctrl-C that could not be raised where it landed stops
    the run at its next progress check instead of printing a traceback and being lost."""
    if isinstance(unraisable.exc_value, KeyboardInterrupt):
        _INTERRUPTED.set()
        return
    sys.__unraisablehook__(unraisable)


def fail(message: str, code: ExitCode = ExitCode.BAD_INPUT) -> typer.Exit:
    """Print ``message`` on stderr and return the exit to raise."""
    global _REPORTED
    stderr.print(message, markup=False, highlight=False, soft_wrap=True)
    _REPORTED = True
    return typer.Exit(int(code))


@contextmanager
def reported_errors() -> Iterator[None]:
    """Turn preset errors, interrupts and job failures into one line and an exit code."""
    try:
        yield
    except PresetError as error:
        raise fail(str(error), ExitCode.BAD_INPUT) from None
    except Terminated:
        raise fail(
            "terminated: the running job's output was not written", ExitCode.TERMINATED
        ) from None
    except (KeyboardInterrupt, Exception) as error:
        if not (isinstance(error, Cancelled) or caused_by_interrupt(error)):
            raise
        raise fail(
            "interrupted: the running job's output was not written", ExitCode.INTERRUPTED
        ) from None


def check_figure_option(path: Path | None, option: str = "--plot") -> None:
    """Refuse a figure path whose suffix names no format (:class:`PresetError`, exit 2)."""
    problem = None if path is None else figure_suffix_problem(str(path))
    if problem is not None:
        raise PresetError(
            "command line",
            option,
            f"is {str(path)!r}: {problem}",
            "a file ending " + ", ".join(FIGURE_SUFFIXES),
        )


def check_workers(workers: int | None) -> None:
    """Refuse ``--workers`` out of range (:class:`PresetError`, exit 2), in one line as the
    job options' ranges are (checked here, not by Typer, whose usage box takes many lines)."""
    if workers is not None:  # the sweep's modules only where a sweep may run
        from planar_tui.sweep.budget import check_workers as check

        check(workers)


def load_presets(arguments: Sequence[str]) -> list[Preset]:
    """Resolve and validate every preset before anything runs."""
    return [load_preset(resolve_preset(argument)) for argument in arguments]


def progress_figures(
    completed: float,
    total: float,
    remaining_s: float | None,
    done_s: float | None = None,
    rate: str = "",
) -> str:
    """The figures beside a job's bar: percent, ``done/total`` when the runner counts whole
    units (steps, states, evaluations; a workspace counts a fraction and shows its boxes in
    the detail line), the ``rate`` text when given (a sweep's ``3.2 pt/s``), and ``ETA
    H:MM:SS`` (``-:--:--`` until known), or ``in H:MM:SS`` once the job is done
    (``done_s`` seconds after it started)."""
    parts = [f"{100.0 * completed / total if total else 100.0:3.0f}%"]
    if total > 1 and float(total).is_integer():
        parts.append(f"{completed:,.0f}/{total:,.0f}")
    if rate:
        parts.append(rate)
    if done_s is not None:
        parts.append(f"in {clock_text(done_s)}")
    else:
        parts.append("ETA " + ("-:--:--" if remaining_s is None else clock_text(remaining_s)))
    return "  ".join(parts)


def job_progress_display(console: Console):
    """A rich progress display for one job, complete at 80 columns: the job and stage on
    their own line, then the bar with percent, count and ETA, then the runner's detail
    (folded, never cut). Its task takes ``detail``, ``done_s``, ``rate`` (text) and
    ``eta_s`` fields (:func:`progress_bar` sets them)."""
    from rich.progress import BarColumn, Progress, ProgressColumn
    from rich.table import Column
    from rich.text import Text

    class FiguresColumn(ProgressColumn):
        def render(self, task) -> Text:
            fields = task.fields
            figures = progress_figures(
                task.completed,
                task.total or 0.0,
                fields["eta_s"],
                fields["done_s"],
                fields["rate"],
            )
            return Text(figures, no_wrap=True)

    class JobProgress(Progress):
        def get_renderables(self):
            for task in self.tasks:
                yield Text(task.description, overflow="fold")
                yield self.make_tasks_table([task])
                if task.fields.get("detail"):
                    yield Text(f"  {task.fields['detail']}", overflow="fold")

    bar = BarColumn(bar_width=None, table_column=Column(ratio=1))
    figures = FiguresColumn(table_column=Column(no_wrap=True))
    return JobProgress(bar, figures, console=console, transient=False, expand=True)


def _raise_terminated(signum, frame) -> None:
    raise Terminated("SIGTERM")


@contextmanager
def sigterm_as_interrupt() -> Iterator[None]:
    """While jobs run, SIGTERM raises :class:`~planar_tui.errors.Terminated` (a
    ``KeyboardInterrupt``) so it cleans up like Ctrl-C: no temporary file is left."""
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


@contextmanager
def progress_bar(bars, label: str, unit: str = ""):
    """One progress task for ``label``'s run (stage, figures and detail), as a
    :class:`~planar_tui.progress.Progress` for the runner. A new stage restarts the bar;
    the ETA is the stage's at its rate so far
    (:meth:`~planar_tui.progress.ProgressState.eta_s`); with ``unit`` (``pt``) the figures
    show the stage's rate (units per second since it began). The last line says ``done``
    with the total time and the runner's last detail (a workspace's final area
    bracket)."""
    import time

    started = time.monotonic()
    task = bars.add_task(label, total=1.0, detail="", done_s=None, rate="", eta_s=None)
    warned = set()
    stage = None

    def update(state) -> None:
        nonlocal stage
        if state.warning and state.warning not in warned:
            warned.add(state.warning)
            bars.console.print(f"warning: {label}: {state.warning}", markup=False)
        if state.stage != stage:
            stage = state.stage
            bars.reset(task, total=state.total, completed=state.completed)
        now_s = time.monotonic()
        rate = rate_text(rate_of(state, now_s), unit) if unit else ""
        bars.update(
            task,
            completed=state.completed,
            total=state.total,
            description=stage_title(label, state.stage),
            detail=state.detail,
            rate=rate,
            eta_s=state.eta_s(now_s),
        )

    yield Progress(on_update=update, should_stop=_INTERRUPTED.is_set)
    (current,) = (t for t in bars.tasks if t.id == task)
    done_s = time.monotonic() - started
    bars.update(task, completed=current.total, description=f"{label} done", done_s=done_s)


@contextmanager
def progress_display(label: str, unit: str = ""):
    """A :class:`~planar_tui.progress.Progress` for the run of ``label`` shown on stderr:
    a bar (:func:`job_progress_display`, :func:`progress_bar`) in a terminal, plain lines
    (:class:`~planar_tui.cli.loglines.ProgressLog`: each stage, at least every 10 s, then
    ``done``) in a log or pipe, where a bar would show nothing until the end."""
    if stderr.is_terminal:
        with job_progress_display(stderr) as bars, progress_bar(bars, label, unit) as progress:
            yield progress
        return
    import time

    started = time.monotonic()
    with ProgressLog(label, said, unit) as log:
        yield Progress(on_update=log.update, should_stop=_INTERRUPTED.is_set)
        log.done(time.monotonic() - started)


def said(text: str) -> None:
    """A line on stderr, as written (no markup, never wrapped)."""
    stderr.print(text, markup=False, highlight=False, soft_wrap=True)
