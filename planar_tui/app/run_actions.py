"""The app's job runs: Run (the current tab's job), Run all (every job of the preset into a
folder, as ``planar-tui run --out-dir``), Cancel, the progress shown by the UI timer, and
each outcome on its tab (a dialog for an error)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from planar_tui import batch
from planar_tui.app.job_runner import BatchFinished, BatchJobDone, JobFinished
from planar_tui.app.messages import CancelRequested, RunRequested
from planar_tui.app.problems import reason
from planar_tui.app.screens.dialogs import MessageDialog, PathDialog
from planar_tui.app.widgets.panes import JobPane
from planar_tui.errors import PresetError
from planar_tui.plan import plan_run
from planar_tui.registry import JOB_KINDS


class RunActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp`: running, cancelling and
    showing jobs, one or all."""

    def action_run(self) -> None:
        """Run the job of the current tab."""
        self.run_pane_job(self.current_pane())

    def on_run_requested(self, message: RunRequested) -> None:
        """A tab's Run button."""
        self.run_pane_job(message.pane)

    def run_pane_job(self, pane: Any) -> None:
        """Run the job of ``pane`` (a job tab) in the job runner."""
        if not isinstance(pane, JobPane) or not pane.available():
            first = [title for title, name in self.tabs() if name in JOB_KINDS][:3]
            named = " or ".join((", ".join(first[:-1]), first[-1])) if len(first) > 1 else first[0]
            self.notify(f"This tab has no job to run: choose {named}.")
            return
        if self.job_running:
            self.notify("A job is already running (escape cancels it).", severity="warning")
            return
        try:
            job = pane.current_job()  # this job alone: others' problems do not stop it
        except PresetError as error:
            self.revalidate()
            self.notify(reason(error), title="Not run", severity="error")
            self.call_later(self.goto_problem, error)
            return
        self.revalidate()
        pane.run_inputs = pane.inputs()
        pane.controls().set_running(True)
        pane.controls().status(f"starting {job.key}")
        self.jobs.start(pane, job, self.workbench.digest())
        self.refresh_bindings()

    def action_run_all(self) -> None:
        """Run every job of the preset in order into a folder, as ``planar-tui run``."""
        if self.job_running:
            self.notify("A job is already running (escape cancels it).", severity="warning")
            return
        try:
            jobs = self.workbench.validate().jobs
        except PresetError as error:
            self.notify(reason(error), title="Not run", severity="error")
            self.call_later(self.goto_problem, error)
            return
        names = ", ".join(str(p) for plan in batch.plan_outputs(jobs, Path()) for p in plan.paths())
        hint = (
            f"Runs {len(jobs)} jobs in order and writes {names} there, as planar-tui run "
            "--out-dir does.\nEnter: run   Escape: cancel"
        )

        def chosen(answer: str | None) -> None:
            if answer:
                self.run_all(answer)

        self.push_screen(PathDialog("Run all jobs into folder", str(self.output_dir), hint), chosen)

    def run_all(self, out_dir: str | Path) -> bool:
        """Run every job of the preset through the batch service into ``out_dir`` (files
        checked before the first job, each written when its job ends); ``False`` when the
        preset or a path is refused (a dialog says why)."""
        try:
            jobs = self.workbench.validate().jobs
            plan = plan_run(jobs, Path(out_dir), prepare=False)  # each prepared as it runs
        except PresetError as error:
            self.push_screen(MessageDialog("Not run", str(error)))
            return False
        host = self.current_pane()
        if not isinstance(host, JobPane) or not host.available():
            host = self.query_one(f"#pane-{jobs[0].kind}", JobPane)
            self.action_show_tab(jobs[0].kind)
        self.batch_inputs = {pane.id: pane.inputs() for pane in self.query(JobPane)}
        self.batch_dir = Path(out_dir)
        self.remember_output_dir(out_dir)
        host.controls().set_running(True)
        host.controls().status(f"starting {len(jobs)} jobs")
        self.jobs.start_all(host, list(plan.jobs))
        self.refresh_bindings()
        return True

    def on_batch_job_done(self, message: BatchJobDone) -> None:
        """A job of "run all" ended (files written): show it on its tab when selected."""
        job = message.job
        for pane in self.query(f"#pane-{job.kind}").results(JobPane):
            if pane.index == job.index - 1 and pane.is_attached:
                pane.show_result(job, message.result, self.batch_inputs.get(pane.id))
        host = self.jobs.pane
        if host is not None and host.job is not job:
            host.end_live_view()  # not this job's live view: the next job's comes

    def on_batch_finished(self, message: BatchFinished) -> None:
        """ "Run all" ended: say how, on the controls it used."""
        self.refresh_bindings()
        done = len(message.rows)
        for pane in self.job_panes():
            pane.end_live_view()  # no tab keeps a running job's text or partial map
        if message.pane.is_attached:
            controls = message.pane.controls()
            controls.set_running(False)
            where = f"→ {self.batch_dir}"  # the folder first: the line's end may be cut
            if message.cancelled:
                text = f"{where}: cancelled, {done}/{message.total} jobs done"
            elif message.error is not None:
                text = f"{where}: failed after {done}/{message.total} jobs"
            else:
                controls.finished()
                text = f"{where}: {done} jobs in {message.seconds:.1f} s"
            controls.status(text)
            self.notify(f"Run all {text.removeprefix(where + ': ')}; files in {self.batch_dir}")
        if message.error is not None:
            error = message.error
            shown = (
                str(error) if isinstance(error, PresetError) else f"{type(error).__name__}: {error}"
            )
            self.push_screen(MessageDialog("Run all failed", shown))
        self.exit_if_quitting()

    def _refresh_progress(self) -> None:
        """The UI timer: show the running job's latest progress snapshot."""
        if len(self.screen_stack) > 1:
            return  # a dialog is up: redrawing the screen behind it would only slow it down
        state, pane = self.jobs.latest, self.jobs.pane
        if pane is not None and state is not None and self.job_running and pane.is_attached:
            pane.show_progress(state)

    def action_cancel(self) -> None:
        """Ask the running job to stop (the runner stops at its next chunk); the controls
        say ``cancelling…`` until its worker has stopped."""
        if self.jobs.cancel() and self.jobs.pane is not None and self.jobs.pane.is_attached:
            self.jobs.pane.controls().show_cancelling()

    def on_cancel_requested(self, message: CancelRequested) -> None:
        """A tab's Cancel button."""
        self.action_cancel()

    def on_job_finished(self, message: JobFinished) -> None:
        """Show a job's outcome on its tab (a dialog for an error)."""
        pane = message.pane
        self.refresh_bindings()
        if self.exit_if_quitting() or not pane.is_attached:
            return
        controls = pane.controls()
        controls.set_running(False)
        if message.cancelled:
            controls.status(f"cancelled after {message.seconds:.2f} s; nothing written")
            pane.run_ended("was cancelled")
            self.notify("Job cancelled.")
        elif message.error is not None:
            error = message.error
            text = (
                str(error) if isinstance(error, PresetError) else f"{type(error).__name__}: {error}"
            )
            controls.status(f"failed after {message.seconds:.2f} s: {text}")
            pane.run_ended("failed")
            self.push_screen(MessageDialog(f"{message.job.label} failed", text))
        else:
            controls.finished()
            controls.status(f"done in {message.seconds:.2f} s")
            pane.show_result(message.job, message.result, getattr(pane, "run_inputs", None))
