"""The app's sweeps: F8 runs the current tab's job as a sweep (a dialog asks for the keys
and values, the points are planned and checked by :func:`planar_tui.plan.plan_sweep`), its
outcome opens the sweep screen, whose CSV can be exported."""

from __future__ import annotations

from typing import Any

from planar_tui.app.job_runner import SweepFinished
from planar_tui.app.problems import reason
from planar_tui.app.screens.dialogs import MessageDialog
from planar_tui.app.screens.sweep import SweepDialog, SweepScreen
from planar_tui.errors import PresetError
from planar_tui.provenance import study_provenance
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.sweep.paths import allowed_paths
from planar_tui.sweep.spec import build_sweep, parse_sweeps


class SweepActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp`: its sweep actions and the
    handler of a finished sweep."""

    last_sweep: Any

    # -- sweeps ----------------------------------------------------------------------
    def action_sweep(self) -> None:
        """Run the current tab's job as a sweep: a dialog asks for the keys and values."""
        pane = self.idle_job_pane("A sweep")  # OptimiseActions'
        if pane is None:
            return
        try:
            job = pane.current_job()
            preset = self.workbench.validate()
        except PresetError as error:
            self.revalidate()
            self.notify(reason(error), title="No sweep: fix the preset first", severity="error")
            self.call_later(self.goto_problem, error)
            return
        kind = JOB_KINDS[job.kind]
        paths = allowed_paths(kind.keys, kind.robot_kind, ROBOT_KINDS[kind.robot_kind].keys)

        def build(values: dict, combine: str) -> Any:
            return build_sweep(preset, job.key, values=values, combine=combine)

        def chosen(answer: tuple[Any, int, Any] | None) -> None:
            if answer is None:
                return
            sweep, workers, points = answer
            pane.controls().set_running(True)
            pane.controls().status(f"starting {sweep.point_count} points of {job.key}")
            self.jobs.start_sweep(pane, sweep, workers, points)
            self.refresh_bindings()

        try:  # the preset's own sweep of this job, if it has one
            own = next((s for s in parse_sweeps(preset) if s.job.key == job.key), None)
        except PresetError:  # shown by the CLI's checks; the dialog starts empty
            own = None
        self.push_screen(SweepDialog(job.key, paths, build, own), chosen)

    def on_sweep_finished(self, message: SweepFinished) -> None:
        """A sweep ended: open its screen (a dialog for an error)."""
        self.refresh_bindings()
        if self.exit_if_quitting():
            return
        pane = message.pane
        if pane.is_attached:
            controls = pane.controls()
            controls.set_running(False)
            if message.cancelled:
                kept = 0 if message.run is None else len(message.run.outcomes)
                total = "?" if message.run is None else len(message.run.points)
                controls.status(
                    f"sweep cancelled after {message.seconds:.2f} s; {kept} of "
                    f"{total} points finished (kept)"
                )
            elif message.error is not None:
                controls.status(f"sweep not run: {message.error}")
            else:
                controls.finished()
                run = message.run
                failed = f", {run.failed} failed" if run.failed else ""
                controls.status(
                    f"sweep: {len(run.outcomes)} points{failed} in {message.seconds:.2f} s"
                )
        if message.cancelled:
            self.notify("Sweep cancelled: its finished points are kept.")
            if message.run is not None and message.run.outcomes:
                self.last_sweep = message.run
                self.action_show_sweep()
        elif message.error is not None:
            error = message.error
            text = (
                error.message
                if isinstance(error, PresetError)
                else f"{type(error).__name__}: {error}"
            )
            self.push_screen(MessageDialog("Sweep not run", text))
        else:
            self.last_sweep = message.run
            self.action_show_sweep()

    def action_show_sweep(self) -> None:
        """Show the latest sweep's table and plot."""
        if self.last_sweep is None:
            self.notify("No sweep has run yet (F8 on a job tab starts one).")
            return
        self.push_screen(SweepScreen(self.last_sweep, self.export_sweep))

    def export_sweep(self, run: Any) -> None:
        """Ask for a file and write the sweep CSV there (atomically)."""
        self.export_tables(
            "Export the sweep CSV to",
            self.output_dir / run.sweep.output,
            lambda path: [(path, run.table)],  # OptimiseActions'
            study_provenance("sweep", run.sweep),
        )
