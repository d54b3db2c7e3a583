"""The Robot tab: the serial robot's links and gravity (or a job's own robot, chosen in its
picker), a drawing of the arm in the simulation's initial posture, and the parallel
robots' geometry tables. Edits go into the preset document; the tab posts
:class:`~planar_tui.app.messages.DocumentEdited` and the app handles it."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from textual.app import ComposeResult
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.widgets import Button, Label, Select, Static

from planar_tui.app.messages import DocumentEdited
from planar_tui.app.widgets.fields import LinkEditor, TableForm, required_keys
from planar_tui.app.widgets.robot_drawing import draw_serial_robot, numbers_or_zeros
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS

if TYPE_CHECKING:
    from planar_tui.app.workbench import Workbench


class RobotPane(VerticalScroll):
    """The serial robot's links and gravity, a drawing, and the 3-RRR geometry.

    Edits go into ``workbench`` (the preset document), then a
    :class:`~planar_tui.app.messages.DocumentEdited` tells the app.
    """

    can_focus = False  # its fields take the focus and scroll into view

    def __init__(self, workbench: Workbench, **kwargs: Any):
        super().__init__(**kwargs)
        self.bench = workbench
        #: Whose robot the tab edits: ``None`` for the preset's robots, else a job's own
        #: robot, ``(kind, index)`` (the job picker).
        self.target: tuple[str, int] | None = None

    def robot_kind(self) -> str:
        """The robot kind edited: ``robot`` for the preset, the job's kind's robot else."""
        return "robot" if self.target is None else JOB_KINDS[self.target[0]].robot_kind

    def compose(self) -> ComposeResult:
        targets = self.bench.robot_targets()
        self.shown_targets = targets
        #: The forms and link editor shown (kept: each edit's check marks them).
        self.forms: list[TableForm] = []
        self.editors: list[LinkEditor] = []
        if len(targets) > 1:
            current = next(
                i
                for i, (_, kind, index) in enumerate(targets)
                if (None if index is None else (kind, index)) == self.target
            )
            yield Select(
                [(label, i) for i, (label, _, _) in enumerate(targets)],
                value=current,
                allow_blank=False,
                compact=True,
                id="robot-select",
            )
        own = self.target is not None
        if self.robot_kind() == "robot":
            robot = self.serial_table()
            where = f"{targets_label(targets, self.target)} robot" if own else "[robot]"
            with Horizontal(classes="robot-top"):
                with Vertical(classes="robot-links"):
                    yield Label(f"Serial robot {where}", classes="section", markup=False)
                    required = required_keys(ROBOT_KINDS["robot"].model)
                    self.forms.append(
                        TableForm(("name", "gravity_m_s2"), robot, required, id="robot-form")
                    )
                    self.editors.append(LinkEditor(robot, id="links"))
                    yield self.forms[-1]
                    yield self.editors[-1]
                    with Horizontal(classes="link-buttons"):
                        yield Button("Add link ^n", id="add-link", compact=True)
                        yield Button("Remove link ^r", id="remove-link", compact=True)
                yield Static(self.drawing(), id="robot-drawing", markup=False)
        for name, kind in ROBOT_KINDS.items():
            if name == "robot" or (own and name != self.robot_kind()):
                continue
            table = self.bench.job_robot(*self.target) if own else self.bench.table(name)
            yield Label(
                f"{name} [{name}] (joint limits: Workspace tab)", classes="section", markup=False
            )
            self.forms.append(
                TableForm(kind.keys, table, required_keys(kind.model), id=f"form-{name}")
            )
            yield self.forms[-1]

    async def load_document(self) -> None:
        """Show the document's robots in the fields already there (after an undo: the
        focus, the tab and the picker stay); rebuilt only when the picker's choices
        changed."""
        targets = self.bench.robot_targets()
        chosen = [(kind, index) for _, kind, index in targets if index is not None]
        target = self.target
        if self.target is not None and self.target not in chosen:
            self.target = None
        if targets != getattr(self, "shown_targets", targets) or self.target != target:
            await self.recompose()
            return
        for form in self.forms:
            kind = (form.id or "").removeprefix("form-")
            if form.id == "robot-form":
                form.load(self.serial_table())
            elif self.target is None:
                form.load(self.bench.table(kind))
            else:
                form.load(self.bench.job_robot(*self.target))
        for editor in self.editors:
            await editor.load(self.serial_table())
        for drawing in self.query("#robot-drawing").results(Static):
            drawing.update(self.drawing())

    def serial_table(self) -> dict[str, Any]:
        """The serial robot table edited: the preset's ``[robot]`` or the job's own."""
        if self.target is None:
            return self.bench.table("robot")
        return self.bench.job_robot(*self.target)

    async def on_select_changed(self, event: Select.Changed) -> None:
        """The job picker: edit another job's robot (or the preset's)."""
        if event.select.id != "robot-select":
            return
        _, kind, index = self.bench.robot_targets()[int(event.value)]
        target = None if index is None else (kind, index)
        if target != self.target:
            self.target = target
            await self.recompose()
            self.post_message(DocumentEdited())  # the marks of the new target

    def mark_problems(self, problems: list[tuple[Any, str]]) -> list[Any]:
        """Mark the fields of the robot on screen named by ``(location, message)`` pairs;
        returns the marked widgets."""
        for form in self.forms:
            form.clear_marks()
        for editor in self.editors:
            editor.clear_marks()
        marked = []
        for location, message in problems:
            widget = self.widget_for(location, message)
            if widget is not None:
                marked.append(widget)
        return marked

    def widget_for(self, location: Any, message: str) -> Any:
        """Mark and return the field of ``location`` when it is on this tab now."""
        if self.target is None:
            if location.robot or location.table not in self.bench.robot_kinds():
                return None
            kind = location.table
        else:
            if (location.table, location.index) != self.target or not location.robot:
                return None
            kind = location.robot
        if kind == "robot":
            if location.field in LinkEditor.column_keys():
                return self.editors[0].mark(location.field, location.item, message)
            return self.query_one("#robot-form", TableForm).mark(location.field, message)
        forms = self.query(f"#form-{kind}")
        return forms.first(TableForm).mark(location.field, message) if forms else None

    def drawing(self) -> str:
        """The robot at the Simulate tab's initial angles (zeros when not numbers)."""
        robot = self.serial_table()
        lengths = robot.get("lengths_m")
        if not isinstance(lengths, list) or not all(
            isinstance(v, int | float) and not isinstance(v, bool) and v > 0 for v in lengths
        ):
            return "(no drawing: the lengths are not all positive numbers)"
        theta = numbers_or_zeros(self.bench.table("simulate").get("theta0_deg"), len(lengths))
        title = "posture: simulate theta0_deg\n"
        return title + draw_serial_robot([float(v) for v in lengths], theta, 34, 11)

    def robot_table(self) -> dict[str, Any]:
        """The serial robot table as edited."""
        table = self.query_one("#robot-form", TableForm).table()
        table |= self.editors[0].values()
        if "inertias_kgm2" not in table:
            table.pop("inertias_kgm2", None)
        return table

    def _store(self, kind: str, table: dict[str, Any]) -> None:
        """Put an edited robot table where it belongs: the preset's or the job's own."""
        if self.target is None:
            self.bench.set_table(kind, 0, table)
        else:
            self.bench.set_job_robot(*self.target, table)

    def _store_robot(self) -> None:
        self._store("robot", self.robot_table())
        self.query_one("#robot-drawing", Static).update(self.drawing())
        self.post_message(DocumentEdited())

    def on_link_editor_changed(self, event: LinkEditor.Changed) -> None:
        self._store_robot()

    def on_table_form_changed(self, event: TableForm.Changed) -> None:
        if event.form.id == "robot-form":
            self._store_robot()
        else:
            self._store(event.form.id.removeprefix("form-"), event.table)
            self.post_message(DocumentEdited())

    async def on_button_pressed(self, event: Button.Pressed) -> None:
        if event.button.id == "add-link":
            await self.action_add_link()
        elif event.button.id == "remove-link":
            await self.action_remove_link()

    async def action_add_link(self) -> None:
        """Append a link (a copy of the last one)."""
        for editor in self.editors:
            await editor.add_link()

    async def action_remove_link(self) -> None:
        """Remove the last link."""
        for editor in self.editors:
            await editor.remove_link()


def targets_label(targets: list[tuple[str, str, int | None]], target: Any) -> str:
    """The job name of the picker's ``target`` (``sensitivity[2]``)."""
    for label, kind, index in targets:
        if index is not None and (kind, index) == target:
            return label.rsplit(" ", 1)[0]
    return ""
