"""The job tabs: one pane per job kind (form, run, results); the Robot tab is
:mod:`planar_tui.app.widgets.robot_pane`.

Panes get the preset document (:class:`~planar_tui.app.workbench.Workbench`) when they
are built and never call the app: they post :mod:`planar_tui.app.messages` (an edit, Run,
Cancel) and the app handles them. A job kind without a dedicated pane gets
:class:`JobPane` itself: its form, Run/Cancel/progress, and the job's summary and first
CSV rows.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Any

from textual.app import ComposeResult
from textual.containers import Horizontal, ScrollableContainer, Vertical, VerticalScroll
from textual.widgets import Button, Label, Select, Static

from planar_tui.app.messages import CancelRequested, DocumentEdited, RunRequested
from planar_tui.app.widgets.fields import TableForm, required_keys
from planar_tui.app.widgets.job_controls import JobControls
from planar_tui.progress import ProgressState
from planar_tui.registry import JOB_KINDS

if TYPE_CHECKING:
    from planar_tui.app.workbench import Workbench
    from planar_tui.jobkind import JobResult
    from planar_tui.presets import Job

#: Lines of the CSV (header included) shown by the generic result view.
GENERIC_ROWS = 12


class Results(Vertical):
    """A job tab's results area (the summary, tables and plots); ``ctrl+b`` maximises it
    when the focus is not on a plot or table of its own (see the app's ``maximise``)."""

    ALLOW_MAXIMIZE = True


class JobPane(Vertical):
    """A job tab: which job of the preset, its settings form, results, Run/Cancel/progress.

    ``JobPane(workbench, kind="torques")`` is the generic tab of any job kind: the job's
    summary and the first :data:`GENERIC_ROWS` lines of its CSV. Dedicated panes subclass
    it, set :attr:`kind` and fill the results area (:meth:`compose_results`,
    :meth:`render_result`).
    """

    DEFAULT_CSS = """
    JobPane .generic-rows { height: 1fr; }
    JobPane #result-rows { width: auto; }
    """

    #: The job kind of the tab (a dedicated pane sets it; the generic one is given it).
    kind: str = ""

    def __init__(self, workbench: Workbench, kind: str | None = None, **kwargs: Any):
        super().__init__(**kwargs)
        self.bench = workbench
        if kind is not None:
            self.kind = kind
        self.index = 0
        self.job: Job | None = None
        self.result: JobResult | None = None
        #: The inputs the shown result was computed from (see :meth:`inputs`).
        self.ran_inputs: Any = None
        #: Why the shown result is not current (``None``: it is), e.g. an edit since.
        self.stale_reason: str | None = None
        #: How the last run ended, when it left the shown result behind (a cancel, a failure).
        self.last_outcome: str | None = None

    def available(self) -> bool:
        return self.kind in JOB_KINDS

    def form_keys(self) -> tuple[str, ...]:
        """The job table's keys; a job's own robot is edited on the Robot tab."""
        return (*JOB_KINDS[self.kind].keys, "output")

    def required(self) -> frozenset[str]:
        """The job table's keys without a default (their empty field says so)."""
        return required_keys(JOB_KINDS[self.kind].settings)

    def robot_kind(self) -> str:
        return JOB_KINDS[self.kind].robot_kind

    def compose(self) -> ComposeResult:
        if not self.available():
            yield Static(
                f"The [{self.kind}] job kind is not installed in this build.", classes="missing"
            )
            return
        labels = self.bench.job_labels(self.kind)
        self.shown_labels = labels
        if len(labels) > 1:
            yield Select(
                [(label, i) for i, label in enumerate(labels)],
                value=self.index,
                allow_blank=False,
                compact=True,
                id="job-select",
            )
        table = self.bench.table(self.kind, self.index)
        form = VerticalScroll(classes="form")
        form.can_focus = False  # its fields take the focus and scroll into view
        # kept: each edit's check updates them (a query each time cost more than the check)
        self.form = TableForm(self.form_keys(), table, self.required(), id="job-form")
        self.results_area = Results(classes="results")
        self.stale_note = Static("", id="stale-note", markup=False)
        self.problem_line = Static("", id="pane-problem", markup=False)
        with Horizontal(classes="pane-body"):
            with form:
                if isinstance(table.get(self.robot_kind()), dict):
                    yield Label("own robot: Robot tab", classes="own-robot")
                yield self.form
            with self.results_area:
                yield self.stale_note
                yield from self.compose_results()
        yield self.problem_line
        yield JobControls()

    def compose_results(self) -> ComposeResult:
        """The results area; the generic one: the summary, then the CSV's first lines."""
        yield Static("Run the job (F5) to see its results.", id="result-text", markup=False)
        with ScrollableContainer(classes="generic-rows"):
            yield Static("", id="result-rows", markup=False)

    # -- editing --------------------------------------------------------------------
    def store_form(self) -> None:
        """Put the form's table into the document (the job's own robot, edited on the
        Robot tab, is kept as the document has it)."""
        table = self.form.table()
        current = self.bench.table(self.kind, self.index)
        if self.robot_kind() in current:
            table[self.robot_kind()] = current[self.robot_kind()]
        self.bench.set_table(self.kind, self.index, table)

    async def load_document(self) -> None:
        """Show the document's table in the fields already there (after an undo: the
        focus, the tab, the result and the status stay; the result is then marked stale
        if it no longer matches); rebuilt only when the jobs of the kind changed."""
        if not self.available():
            return
        if self.bench.job_labels(self.kind) != getattr(self, "shown_labels", None):
            self.index = min(self.index, max(len(self.bench.tables(self.kind)) - 1, 0))
            await self.recompose()
            self.call_after_refresh(self.rerender)
            return
        self.form.load(self.bench.table(self.kind, self.index))

    def mark_problems(self, problems: list[tuple[Any, str]]) -> list[Any]:
        """Show this tab's own problems, ``(location, message)`` pairs: the bad field
        marked, and the job's first problem that no field of the form shows on the line
        above the controls; returns the marked fields."""
        if not self.available():
            return []
        form = self.form
        form.clear_marks()
        mine = [
            (location, message)
            for location, message in problems
            if (location.table, location.index) == (self.kind, self.index)
        ]
        marked, unmarked = [], []
        for location, message in mine:
            field = None if location.robot else form.mark(location.field, message)
            if field is not None:
                marked.append(field)
            else:
                unmarked.append(message)
        # a problem marked on its field is said there (and on the validation line): said
        # a third time here, it took the rows of the results (an energy plot 2 rows high)
        line = self.problem_line
        line.update(f"error: {unmarked[0]}" if unmarked else "")
        line.set_class(bool(unmarked), "-shown")
        return marked

    # -- stale results ----------------------------------------------------------------
    def inputs(self) -> Any:
        """What the job's result depends on: its table and the preset robot of its kind."""
        import copy

        table = self.bench.table(self.kind, self.index)
        return copy.deepcopy((self.index, table, self.bench.document.get(self.robot_kind())))

    def update_stale(self) -> None:
        """Dim the shown result and say why when it no longer matches the inputs."""
        if self.result is None or not self.is_attached:
            return
        reason = self.last_outcome
        if reason is None and self.job is not None and self.job.index - 1 != self.index:
            reason = f"result of {self.job.key}, not of the job selected"
        elif reason is None and self.inputs() != self.ran_inputs:
            reason = "inputs changed since this run"
        self.stale_reason = reason
        self.stale_note.update(f"stale: {reason}; F5 runs it again" if reason else "")
        self.results_area.set_class(reason is not None, "stale")

    def on_table_form_changed(self, event: TableForm.Changed) -> None:
        self.store_form()
        self.post_message(DocumentEdited())

    async def on_select_changed(self, event: Select.Changed) -> None:
        if event.select.id == "job-select" and event.value != self.index:
            self.index = int(event.value)
            await self.recompose()
            self.rerender()
            self.post_message(DocumentEdited())  # the marks of the job now shown

    def on_button_pressed(self, event: Button.Pressed) -> None:
        if event.button.id == "run":
            event.stop()
            self.post_message(RunRequested(self))
        elif event.button.id == "cancel":
            event.stop()
            self.post_message(CancelRequested())

    # -- running --------------------------------------------------------------------
    def current_job(self) -> Job:
        """Store the form and return the validated job (raises the CLI's PresetError)."""
        self.store_form()
        return self.bench.job(self.kind, self.index)

    def controls(self) -> JobControls:
        return self.query_one(JobControls)

    def show_progress(self, state: ProgressState) -> None:
        self.controls().show_progress(state)

    def show_result(self, job: Job, result: JobResult, inputs: Any = None) -> None:
        """Keep the result (for export) and the inputs it came from, and draw it."""
        self.job, self.result = job, result
        self.ran_inputs = self.inputs() if inputs is None else inputs
        self.last_outcome = None
        self.render_result(job, result)
        self.update_stale()

    def run_ended(self, outcome: str) -> None:
        """A run was cancelled or failed: the result shown (if any) is from before it."""
        self.last_outcome = f"the last run {outcome}; this result is from an earlier run"
        self.placeholder(f"The last run {outcome}.")
        self.update_stale()

    def placeholder(self, text: str) -> None:
        """Replace a running job's live text (a tab without a result shows ``text``)."""
        if self.result is not None:
            self.rerender()
        else:
            self.query_one("#result-text", Static).update(text)

    def end_live_view(self) -> None:
        """Take a running job's live view off (a run-all job's text and partial map): the
        kept result drawn again, else the results area emptied to its first line."""
        if not self.is_attached or not self.available():
            return
        if self.result is not None:
            self.rerender()
            return
        for text in self.results_area.query(Static):
            if text.id not in ("stale-note", "result-text"):
                text.update("")
        self.query_one("#result-text", Static).update("Run the job (F5) to see its results.")

    def rerender(self) -> None:
        """Draw the kept result again (the results area changed size)."""
        if self.result is not None and self.job is not None and self.is_attached:
            self.render_result(self.job, self.result)
            self.update_stale()

    def on_resize(self) -> None:
        self.call_after_refresh(self.rerender)

    def render_result(self, job: Job, result: JobResult) -> None:
        """Generic view: the summary and the first lines of the CSV table (header first)."""
        self.query_one("#result-text", Static).update(result.summary)
        rows = itertools.islice(result.table.lines(), GENERIC_ROWS)
        self.query_one("#result-rows", Static).update("\n".join(rows))
