"""The Workspace tab: the 3-RRR workspace map, explorable (:mod:`.workspace_explorer`),
the 3-RRR drawn at the map's cursor, the cell's status and the legs' joint angles read out;
the live area bracket and box count while the bisection runs; a coarse map redrawn
shortly after each valid edit of the robot or the job (before the job is run again)."""

from __future__ import annotations

import dataclasses
import math
import time
from typing import Any

import numpy as np
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.message import Message
from textual.widgets import Static

from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.robot_drawing import SceneView, rrr_scene
from planar_tui.app.widgets.workspace_explorer import MapExplorer, cell_status
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job
from planar_tui.progress import Progress, ProgressState
from planar_tui.registry import JOB_KINDS
from planar_tui.workspace.paving.levels import BoxBudget
from planar_tui.workspace.paving.map import render_map
from planar_tui.workspace.paving.result import map_content

#: Lines of :func:`planar_tui.workspace.paving.map.render_map` below the plot rows.
MAP_FOOTER_LINES = 3
#: Seconds between two redraws of the map of the boxes kept so far while a job runs.
PARTIAL_MAP_EVERY_S = 0.5
#: The preview's plot in cells (columns, rows) when the map pane has no size yet.
PREVIEW_CELLS = (64, 32)
#: The re-paving's precision: at most half the job's, and the view's width over this.
REPAVE_CELLS = 96


def fitted_map(boxes, status, width: int, height: int, **overlays) -> list[str]:
    """The CLI's aspect-true map (a cell twice as tall as wide) in at most ``width`` ×
    ``height`` cells, without its legend line (the tab shows the legend wrapped).

    ``render_map`` picks the plot rows from the width; when that is too tall the width is
    narrowed until it fits. A y tick ``┤`` is kept only on rows that carry a label (the
    others show the plain axis ``│``), so each label points at its row. ``overlays`` are
    ``render_map``'s ``singular`` and ``circle``.
    """
    lines = render_map(boxes, status, width=width, **overlays)
    while len(lines) > height and width > 20:
        width = max(20, min(width - 1, width * height // len(lines)))
        lines = render_map(boxes, status, width=width, **overlays)
    while lines and not lines[-1].lstrip().startswith("x (cm)") and overlays:
        lines = lines[:-1]  # the overlays' legend line: the tab shows its own
    if lines and lines[-1].lstrip().startswith("x (cm)"):
        lines = lines[:-1]
    plot = lines[: len(lines) - MAP_FOOTER_LINES + 1]
    for row, line in enumerate(plot):
        tick = line.find("┤")
        if tick > 0 and not line[:tick].strip():
            plot[row] = f"{line[:tick]}│{line[tick + 1 :]}"
    return plot + lines[len(plot) :]


def fine_job(job, **changes) -> Any:
    """``job`` with its spec changed (no refinement, no reference area, no singularities)."""
    spec = dataclasses.replace(
        job.spec,
        refine_precision_cm=None,
        geometric_reference=False,
        singularities=False,
        **changes,
    )
    return dataclasses.replace(job, spec=spec)


def pave(job, should_stop, threads: int | None = None) -> Any:
    """Pave ``job``'s workspace (its mechanism's
    :meth:`~planar_tui.workspace.paving.mechanism.Mechanism.pave`),
    its parallel kernels on ``threads`` threads when given (Numba's count is per calling
    thread: the other threads keep theirs)."""
    import numba

    progress = Progress(should_stop=should_stop)
    before = numba.get_num_threads()
    if threads is not None:
        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    try:
        return job.spec.mechanism.pave(job.robot, job.spec, BoxBudget(job, progress))
    finally:
        numba.set_num_threads(before)


def preview_job(job, plot_cells: tuple[int, int] = PREVIEW_CELLS) -> Any:
    """The live preview's job: ``job`` paved in the arc-distance form over the legs' reach
    box at twice the width ``w`` of one map cell when the box fills a plot of
    ``plot_cells`` = (columns, rows) cells (a cell twice as tall as wide),
    ``w = max((x_hi − x_lo) / columns, (y_hi − y_lo) / (2 rows))``, ε = 2 w: the
    bisection's leaves are (ε/2, ε] wide, so no box is finer than a character cell
    (``None`` when the reach discs do not meet)."""
    x_lo, x_hi, y_lo, y_hi = job.robot.reach_box_cm(job.spec.orientation_rad)
    if x_lo >= x_hi or y_lo >= y_hi:
        return None
    columns, rows = (max(1, cells) for cells in plot_cells)
    precision = 2.0 * max((x_hi - x_lo) / columns, (y_hi - y_lo) / (2 * rows))
    return fine_job(job, precision_cm=precision, form="arc-distance", search_box_cm=None)


def view_preview_job(job, extent: tuple[float, float, float, float], cell_cm: float) -> Any:
    """The live preview's job when a map is shown: ``job`` paved in the arc-distance form
    over the view ``extent`` = (x_lo, x_hi, y_lo, y_hi) cm at ε = 2 ``cell_cm`` (the
    view's cell width: no box finer than a character cell, none coarser than two), so an
    edit redraws the map at the scale and resolution it was looked at."""
    x_lo, x_hi, y_lo, y_hi = extent
    return fine_job(
        job,
        precision_cm=2.0 * cell_cm,
        form="arc-distance",
        search_box_cm=((x_lo, x_hi), (y_lo, y_hi)),
    )


def preview_key(job) -> tuple:
    """What the preview depends on: the robot, the joint limits and the orientation."""
    return (job.robot, job.spec.joint_limits_deg, job.spec.orientation_deg)


class Paved(Message):
    """A re-paving or a preview finished in its worker (``outcome`` ``None``: ``error``)."""

    def __init__(self, purpose: str, job: Any, outcome: Any, error: str = "") -> None:
        super().__init__()
        self.purpose, self.job, self.outcome, self.error = purpose, job, outcome, error


class WorkspacePane(JobPane):
    """Form, precision, orientation, joint limits; the explorable map, the 3-RRR at its
    cursor, the read-out and summary."""

    kind = "workspace"
    _partial_drawn_s = 0.0

    DEFAULT_CSS = """
    #workspace-view { height: 1fr; }
    #workspace-robot { width: 1fr; min-width: 12; }
    #workspace-map { width: 2fr; }
    #workspace-readout, #workspace-legend { height: auto; }
    """

    def __init__(self, *args: Any, **kwargs: Any):
        super().__init__(*args, **kwargs)
        #: The inputs of the last preview (``None`` before the first edit).
        self._preview_key: Any = None
        #: Whether the preview on its way paved the map's view (kept when drawn).
        self._preview_in_view = False
        self._shown_job: Any = None

    def compose_results(self) -> ComposeResult:
        yield Static("Run the bisection (F5) to map the workspace.", id="result-text", markup=False)
        with Horizontal(id="workspace-view"):
            yield MapExplorer(id="workspace-map")
            yield SceneView(id="workspace-robot")
        yield Static("", id="workspace-readout", markup=False)
        yield Static("", id="workspace-legend", markup=False)

    def explorer(self) -> MapExplorer:
        return self.query_one("#workspace-map", MapExplorer)

    def show_progress(self, state: ProgressState) -> None:
        """The running bisection: its stage and bracket, a warning when the estimated box
        count exceeds the budget, and the map of the boxes kept so far (redrawn at most
        every :data:`PARTIAL_MAP_EVERY_S`)."""
        super().show_progress(state)
        text = f"running {state.stage}: {state.detail}"
        if state.warning:
            text = f"warning: {state.warning}\n{text}"
        self.query_one("#result-text", Static).update(text)
        boxes = state.partial.get("boxes_cm")
        now = time.monotonic()
        if boxes is not None and len(boxes) and now - self._partial_drawn_s >= PARTIAL_MAP_EVERY_S:
            self._partial_drawn_s = now
            status = state.partial.get("status")
            if status is None:  # the 5-D stage: kept boxes, none proved inside yet
                status = np.ones(len(boxes), dtype=np.int64)
            self.explorer().kappa = None  # the last result's κ map is not this run's
            self.explorer().accuracy = None
            self.draw_map(boxes, status, "(so far)")

    def draw_map(self, boxes, status, note: str = "", refit: bool = True, **overlays) -> None:
        """Draw boxes on the explorable map (``overlays``: the singular boxes and the
        circle, see ``render_map``)."""
        explorer = self.explorer()
        explorer.show_boxes(np.array(boxes), np.array(status), note, refit, **overlays)
        self.on_map_explorer_moved(MapExplorer.Moved(explorer))  # the legend in this frame

    def render_result(self, job: Job, result: JobResult) -> None:
        self.query_one("#result-text", Static).update(result.summary)
        outcome = result.outcome
        explorer = self.explorer()
        if outcome is None or len(outcome.boxes) == 0:
            explorer.show_text("(no box kept: the workspace is empty at this precision)")
            self.query_one("#workspace-legend", Static).update("")
            return

        refit = self._shown_job is not job
        self._shown_job = job
        self.set_geometry(job, result)
        explorer.kappa = getattr(result, "dexterity", None)  # the κ map (``k``)
        explorer.accuracy = getattr(result, "accuracy", None)  # the error map (``a``)
        boxes, status, drawn = map_content(job, result)  # as the CLI's map: layers too
        self.draw_map(boxes, status, "", refit, **drawn)

    @property
    def explores_3rrr(self) -> bool:
        """Whether the map draws the 3-RRR at its cursor, reads its legs' angles, overlays
        its exact boundary, re-paves the view and previews edits: the kind's robot says so
        (:attr:`~planar_tui.workspace.paving.mechanism.Mechanism.explores`; the other
        parallel robots' panes reuse the map alone)."""
        mechanism = getattr(JOB_KINDS[self.kind].settings, "mechanism", None)
        return bool(mechanism is not None and mechanism.explores)

    # -- the geometry at the cursor -------------------------------------------------------
    def constant_orientation_3rrr(self, job: Any) -> bool:
        """Whether ``job`` is a 3-RRR job at one orientation (what the cursor's drawing,
        read-out, boundary, re-paving and preview need)."""
        return (
            self.explores_3rrr
            and job is not None
            and not isinstance(job.spec.orientation_deg, tuple)
        )

    def set_geometry(self, job: Job, result: JobResult | None) -> None:
        """Give the map the exact boundary and the circle's working-mode test of ``job``."""
        explorer = self.explorer()
        explorer.exact_rings = explorer.in_mode = None
        if not self.constant_orientation_3rrr(job):
            return
        robot, spec = job.robot, job.spec

        def rings() -> list[list[tuple[float, float]]]:
            polygon = spec.mechanism.polygon(robot, spec, 256, False)
            parts = getattr(polygon, "geoms", [polygon])
            found = []
            for part in parts:
                for ring in (part.exterior, *part.interiors):
                    found.append(list(ring.coords))
            return found

        cache: dict[str, Any] = {}

        def cached_rings():
            if "rings" not in cache:
                cache["rings"] = rings()
            return cache["rings"]

        explorer.exact_rings = cached_rings
        singular = None if result is None else getattr(result, "singularity", None)
        if singular is not None:
            elbow = singular.elbow

            def in_mode(point) -> bool:
                legs = spec.mechanism.leg_poses(robot, spec, point, elbow)
                return all(
                    leg is not None and leg[1] == s for leg, s in zip(legs, elbow, strict=True)
                )

            explorer.in_mode = in_mode
            explorer.show_mode = True  # shown with the circle; `m` hides it

    def on_map_explorer_moved(self, message: MapExplorer.Moved) -> None:
        explorer = message.explorer
        width = max(20, self.query_one(".results").content_region.width)
        self.query_one("#workspace-legend", Static).update(explorer.legend(width))
        hint = "" if explorer.has_focus else "  (Tab to the map: arrows, + -, r)"
        self.query_one("#workspace-readout", Static).update(self.readout() + hint)
        job = self._shown_job or self._valid_job()
        drawing = self.query_one("#workspace-robot", SceneView)
        if not self.constant_orientation_3rrr(job):
            drawing.show(None)
            return
        legs = job.spec.mechanism.leg_poses(job.robot, job.spec, explorer.cursor_cm, self._elbow())
        drawing.show(rrr_scene(job.robot, explorer.cursor_cm, job.spec.orientation_rad, legs))

    def _elbow(self):
        singular = None if self.result is None else getattr(self.result, "singularity", None)
        return None if singular is None else singular.elbow

    def readout(self) -> str:
        """``(x, y) = (60.00, 35.00) cm inside  θ = 45.1°, 130.2°, 270.3° (modes +1 -1 +1)``."""
        explorer = self.explorer()
        x, y = explorer.cursor_cm
        singular = explorer.overlays.get("singular")
        status = cell_status((x, y), explorer.boxes, explorer.status, singular)
        text = f"(x, y) = ({x:.2f}, {y:.2f}) cm  {status}"
        job = self._shown_job or self._valid_job()
        if status == "outside" or not self.constant_orientation_3rrr(job):
            return text
        legs = job.spec.mechanism.leg_poses(job.robot, job.spec, (x, y), self._elbow())
        if any(leg is None for leg in legs):
            closed = ", ".join(str(i + 1) for i, leg in enumerate(legs) if leg is None)
            return f"{text}  leg {closed} cannot close within its limits here"
        angles = ", ".join(f"{math.degrees(theta) % 360:.1f}°" for theta, _ in legs)  # type: ignore[misc]
        modes = " ".join(f"{mode:+d}" for _, mode in legs)  # type: ignore[misc]
        return f"{text}  θ = {angles} (modes {modes})"

    def on_descendant_focus(self, event) -> None:
        explorer = self.explorer()
        if len(explorer.boxes):
            self.on_map_explorer_moved(MapExplorer.Moved(explorer))

    def on_descendant_blur(self, event) -> None:
        self.on_descendant_focus(event)

    # -- re-paving the view ------------------------------------------------------------
    def on_map_explorer_repave_requested(self, message: MapExplorer.RepaveRequested) -> None:
        """Pave the visible region again at a finer precision in a worker (``r`` again
        cancels it)."""
        if not self.explores_3rrr:
            self.query_one("#workspace-readout", Static).update(
                "re-paving the view: on the 3-RRR's map (F5 runs this job at its precision)"
            )
            return
        running = [w for w in self.workers if w.group == "repave" and w.is_running]
        if running:
            for worker in running:
                worker.cancel()
            self.query_one("#workspace-readout", Static).update("re-paving cancelled")
            return
        job = self.job
        if job is None or self.result is None or isinstance(job.spec.orientation_deg, tuple):
            return
        x_lo, x_hi, y_lo, y_hi = message.extent
        precision = min(job.spec.precision_cm / 2, (x_hi - x_lo) / REPAVE_CELLS)
        fine = fine_job(job, search_box_cm=((x_lo, x_hi), (y_lo, y_hi)), precision_cm=precision)
        self.query_one("#workspace-readout", Static).update(
            f"re-paving the view at ε = {precision:.3g} cm … (r cancels)"
        )
        self.run_worker(
            lambda: self._pave_in_worker(fine, "repave"),
            group="repave",
            thread=True,
            exclusive=True,
            exit_on_error=False,
        )

    def _pave_in_worker(self, job, purpose: str) -> None:
        """Pave in this worker thread, then post the outcome (or the error) back."""
        from textual.worker import get_current_worker

        worker = get_current_worker()
        try:
            # the preview on one thread: its few boxes per level would wait on a busy
            # machine's second core at each parallel level (0.2 s against 0.01 s, 2 cores
            # at load 3; docs/app.md)
            threads = 1 if purpose == "preview" else None
            outcome = pave(job, lambda: worker.is_cancelled, threads)
        except Exception as error:  # a cancel, or the budget exceeded: said, never raised
            if not worker.is_cancelled:
                self.post_message(Paved(purpose, job, None, f"not paved: {error}"))
            return
        if not worker.is_cancelled:
            self.post_message(Paved(purpose, job, outcome))

    def on_paved(self, message: Paved) -> None:
        if message.outcome is None:
            self.query_one("#workspace-readout", Static).update(message.error)
        elif message.purpose == "repave":
            self._repaved(message.job, message.outcome)
        else:
            self._previewed(message.job, message.outcome)

    def _repaved(self, job, outcome) -> None:
        """Show the fine boxes in the view and the job's boxes outside it."""
        if self.result is None:
            return
        (x_lo, x_hi), (y_lo, y_hi) = job.spec.search_box_cm
        coarse = self.result.outcome
        outside = ~(
            (coarse.boxes[:, 1] > x_lo)
            & (coarse.boxes[:, 0] < x_hi)
            & (coarse.boxes[:, 3] > y_lo)
            & (coarse.boxes[:, 2] < y_hi)
        )
        boxes = np.vstack([coarse.boxes[outside, :4], outcome.boxes[:, :4]])
        status = np.concatenate([coarse.status[outside], outcome.status])
        explorer = self.explorer()
        note = f"view re-paved at ε = {job.spec.precision_cm:.3g} cm"
        explorer.show_boxes(boxes, status, note, refit=False, **explorer.overlays)

    # -- live preview while editing ----------------------------------------------------
    def _valid_job(self) -> Any:
        try:
            return self.bench.job(self.kind, self.index)
        except Exception:  # the validation line and the marked field say why
            return None

    def update_stale(self) -> None:
        super().update_stale()
        self.schedule_preview()

    def schedule_preview(self) -> None:
        """After a valid edit of the robot or the job (not at start), start a coarse map
        at once in a worker (a newer edit cancels it, and a map of an older edit that
        arrives after a newer edit is dropped)."""
        if not self.available() or not self.is_attached:
            return
        job = self._valid_job()
        if not self.constant_orientation_3rrr(job):
            return
        key = preview_key(job)
        first = self._preview_key is None
        if key == self._preview_key:
            return
        self._preview_key = key
        if first or (self.result is not None and self.stale_reason is None):
            return
        for worker in self.workers:
            if worker.group == "preview":
                worker.cancel()
        self.start_preview(job)

    def start_preview(self, job) -> None:
        """Pave the edited job coarsely in a worker: in the map's current view at its
        scale (:func:`view_preview_job`) when a map is shown, else over the legs' reach
        fitted to the pane (:func:`preview_job`)."""
        explorer = self.explorer()
        shown = explorer.content_region.width > 0 and explorer.content_region.height > 0
        self._preview_in_view = shown and explorer.fitted and len(explorer.boxes) > 0
        if self._preview_in_view:
            coarse = view_preview_job(job, explorer.extent(), explorer.cell_cm)
        else:
            coarse = preview_job(job, explorer.plot_size() if shown else PREVIEW_CELLS)
        if coarse is None:
            self.explorer().show_text("(preview: the legs' reach discs do not meet)")
            return
        self.run_worker(
            lambda: self._pave_in_worker(coarse, "preview"),
            group="preview",
            thread=True,
            exclusive=True,
            exit_on_error=False,
        )

    def _previewed(self, job, outcome) -> None:
        """Show the preview unless a current result or a newer edit came meanwhile."""
        if self.result is not None and self.stale_reason is None:
            return
        if self._preview_key != preview_key(job):
            return  # an older edit's map: a newer edit's preview is on its way
        self._shown_job = job
        self.set_geometry(job, None)
        note = f"preview ε = {job.spec.precision_cm:.3g} cm (F5 runs the job)"
        if len(outcome.boxes):  # the view kept when the preview paved it
            self.draw_map(outcome.boxes, outcome.status, note, not self._preview_in_view)
        else:
            self.explorer().show_text(
                f"(preview: empty workspace at ε = {job.spec.precision_cm:.3g} cm)"
            )
