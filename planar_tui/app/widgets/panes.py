"""The tabs: Robot (edit the robots), and one pane per job kind (form, run, results).

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
from planar_tui.app.widgets.fields import LinkEditor, TableForm
from planar_tui.app.widgets.job_controls import JobControls
from planar_tui.app.widgets.robot_drawing import draw_serial_robot
from planar_tui.progress import ProgressState

if TYPE_CHECKING:
    from planar_tui.app.workbench import Workbench
    from planar_tui.jobkind import JobResult
    from planar_tui.presets import Job

#: Lines of the CSV (header included) shown by the generic result view.
GENERIC_ROWS = 12


def numbers_or_zeros(value: Any, n: int) -> list[float]:
    """``value`` as n floats when it is a list of numbers, else n zeros (for drawings)."""
    if isinstance(value, list) and all(
        isinstance(v, int | float) and not isinstance(v, bool) for v in value
    ):
        return [float(v) for v in value[:n]] + [0.0] * max(0, n - len(value))
    return [0.0] * n


class RobotPane(VerticalScroll):
    """The serial robot's links and gravity, a drawing, and the 3-RRR geometry.

    Edits go into ``workbench`` (the preset document), then a
    :class:`~planar_tui.app.messages.DocumentEdited` tells the app.
    """

    def __init__(self, workbench: Workbench, **kwargs: Any):
        super().__init__(**kwargs)
        self.bench = workbench

    def compose(self) -> ComposeResult:
        from planar_tui.registry import ROBOT_KINDS

        robot = self.bench.table("robot")
        with Horizontal(classes="robot-top"):
            with Vertical(classes="robot-links"):
                yield Label("Serial robot [robot]", classes="section")
                yield TableForm(("name", "gravity_m_s2"), robot, id="robot-form")
                yield LinkEditor(robot, id="links")
                with Horizontal(classes="link-buttons"):
                    yield Button("Add link ^n", id="add-link", compact=True)
                    yield Button("Remove link ^r", id="remove-link", compact=True)
            yield Static(self.drawing(), id="robot-drawing", markup=False)
        for name, kind in ROBOT_KINDS.items():
            if name == "robot":
                continue
            yield Label(f"{name} [{name}] (joint limits: Workspace tab)", classes="section")
            yield TableForm(kind.keys, self.bench.table(name), id=f"form-{name}")

    def drawing(self) -> str:
        """The robot at the Simulate tab's initial angles (zeros when not numbers)."""
        robot = self.bench.table("robot")
        lengths = robot.get("lengths_m")
        if not isinstance(lengths, list) or not all(
            isinstance(v, int | float) and not isinstance(v, bool) and v > 0 for v in lengths
        ):
            return "(no drawing: the lengths are not all positive numbers)"
        theta = numbers_or_zeros(self.bench.table("simulate").get("theta0_deg"), len(lengths))
        title = "posture: simulate theta0_deg\n"
        return title + draw_serial_robot([float(v) for v in lengths], theta, 34, 11)

    def robot_table(self) -> dict[str, Any]:
        """The ``[robot]`` table as edited."""
        table = self.query_one("#robot-form", TableForm).table()
        table |= self.query_one(LinkEditor).values()
        if "inertias_kgm2" not in table:
            table.pop("inertias_kgm2", None)
        return table

    def _store_robot(self) -> None:
        self.bench.set_table("robot", 0, self.robot_table())
        self.query_one("#robot-drawing", Static).update(self.drawing())
        self.post_message(DocumentEdited())

    def on_link_editor_changed(self, event: LinkEditor.Changed) -> None:
        self._store_robot()

    def on_table_form_changed(self, event: TableForm.Changed) -> None:
        if event.form.id == "robot-form":
            self._store_robot()
        else:
            self.bench.set_table(event.form.id.removeprefix("form-"), 0, event.table)
            self.post_message(DocumentEdited())

    async def on_button_pressed(self, event: Button.Pressed) -> None:
        if event.button.id == "add-link":
            await self.action_add_link()
        elif event.button.id == "remove-link":
            await self.action_remove_link()

    async def action_add_link(self) -> None:
        """Append a link (a copy of the last one)."""
        await self.query_one(LinkEditor).add_link()

    async def action_remove_link(self) -> None:
        """Remove the last link."""
        await self.query_one(LinkEditor).remove_link()


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

    def available(self) -> bool:
        from planar_tui.registry import JOB_KINDS

        return self.kind in JOB_KINDS

    def form_keys(self) -> tuple[str, ...]:
        from planar_tui.registry import JOB_KINDS

        kind = JOB_KINDS[self.kind]
        keys = (*kind.keys, "output")
        table = self.bench.table(self.kind, self.index)
        return (*keys, kind.robot_kind) if kind.robot_kind in table else keys

    def compose(self) -> ComposeResult:
        if not self.available():
            yield Static(
                f"The [{self.kind}] job kind is not installed in this build.", classes="missing"
            )
            return
        labels = self.bench.job_labels(self.kind)
        if len(labels) > 1:
            yield Select(
                [(label, i) for i, label in enumerate(labels)],
                value=self.index,
                allow_blank=False,
                compact=True,
                id="job-select",
            )
        with Horizontal(classes="pane-body"):
            with VerticalScroll(classes="form"):
                yield TableForm(
                    self.form_keys(), self.bench.table(self.kind, self.index), id="job-form"
                )
            with Vertical(classes="results"):
                yield from self.compose_results()
        yield JobControls()

    def compose_results(self) -> ComposeResult:
        """The results area; the generic one: the summary, then the CSV's first lines."""
        yield Static("Run the job (F5) to see its results.", id="result-text", markup=False)
        with ScrollableContainer(classes="generic-rows"):
            yield Static("", id="result-rows", markup=False)

    # -- editing --------------------------------------------------------------------
    def store_form(self) -> None:
        """Put the form's table into the document."""
        table = self.query_one("#job-form", TableForm).table()
        self.bench.set_table(self.kind, self.index, table)

    def on_table_form_changed(self, event: TableForm.Changed) -> None:
        self.store_form()
        self.post_message(DocumentEdited())

    async def on_select_changed(self, event: Select.Changed) -> None:
        if event.select.id == "job-select" and event.value != self.index:
            self.index = int(event.value)
            await self.recompose()

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

    def show_result(self, job: Job, result: JobResult) -> None:
        """Keep the result (for export) and draw it."""
        self.job, self.result = job, result
        self.render_result(job, result)

    def rerender(self) -> None:
        """Draw the kept result again (the results area changed size)."""
        if self.result is not None and self.job is not None and self.is_attached:
            self.render_result(self.job, self.result)

    def on_resize(self) -> None:
        self.call_after_refresh(self.rerender)

    def render_result(self, job: Job, result: JobResult) -> None:
        """Generic view: the summary and the first lines of the CSV table (header first)."""
        self.query_one("#result-text", Static).update(result.summary)
        rows = itertools.islice(result.table.lines(), GENERIC_ROWS)
        self.query_one("#result-rows", Static).update("\n".join(rows))
