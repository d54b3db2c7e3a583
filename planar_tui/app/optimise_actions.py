"""The app's optimisations: the palette's "Run optimisation" runs the preset's
``[[optimise]]`` table of the current tab's job (checked as the CLI checks it,
:func:`planar_tui.optimise.spec.parse_optimisations`) in this process; the optimise screen
opens with its first generation and follows it; its CSVs can be exported."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from planar_tui import csvio
from planar_tui.app.job_runner import GenerationDone, OptimiseFinished
from planar_tui.app.screens.dialogs import MessageDialog, PathDialog
from planar_tui.app.screens.optimise import OptimiseScreen
from planar_tui.app.widgets.panes import JobPane
from planar_tui.batch import check_writable
from planar_tui.errors import PresetError
from planar_tui.optimise.spec import parse_optimisations
from planar_tui.provenance import has_sidecar, sidecar_path, study_provenance, write_sidecar


class OptimiseActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp`: its optimisation actions and
    the handlers of a generation and of the end."""

    last_optimisation: Any = None

    def idle_job_pane(self, what: str) -> JobPane | None:
        """The current tab's job pane when no job runs (``what`` varies its job: a sweep,
        an optimisation); ``None`` with a notice why not."""
        pane = self.current_pane()
        if not isinstance(pane, JobPane) or not pane.available():
            self.notify(f"{what} varies a job: choose a job tab first.", severity="warning")
            return None
        if self.job_running:
            self.notify("A job is already running (escape cancels it).", severity="warning")
            return None
        return pane

    def action_optimise(self) -> None:
        """Run the preset's optimisation of the current tab's job."""
        pane = self.idle_job_pane("An optimisation")
        if pane is None:
            return
        try:
            job = pane.current_job()
            found = [
                o for o in parse_optimisations(self.workbench.validate()) if o.job.kind == job.kind
            ]
        except PresetError as error:
            self.push_screen(MessageDialog("No optimisation", error.message))
            return
        if not found:
            self.notify(
                f"The preset has no [[optimise]] table for a {job.kind} job.", severity="warning"
            )
            return
        optimisation = found[0]
        self.last_optimisation = None
        pane.controls().set_running(True)
        pane.controls().status(f"optimising: {optimisation.label}")
        self.jobs.start_optimise(pane, optimisation)
        self.refresh_bindings()

    def on_generation_done(self, message: GenerationDone) -> None:
        """A generation is back: open the optimise screen on the first, update it after."""
        first = self.last_optimisation is None
        self.last_optimisation = message.run
        if isinstance(self.screen, OptimiseScreen):
            self.screen.update_run(message.run)
        elif first:
            self.action_show_optimisation()

    def on_optimise_finished(self, message: OptimiseFinished) -> None:
        """The optimisation ended (or was cancelled, its evaluations kept): say so."""
        self.refresh_bindings()
        if self.exit_if_quitting():
            return
        pane = message.pane
        run = message.run
        if pane.is_attached:
            pane.controls().set_running(False)
            if message.error is not None:
                pane.controls().status(f"optimisation not run: {message.error}")
            elif run is not None:
                done = "cancelled" if message.cancelled else "done"
                pane.controls().status(
                    f"optimisation {done}: {len(run.evaluations)} "
                    f"evaluations, {run.infeasible} infeasible, "
                    f"{run.failed} failed"
                )
        if message.error is not None:
            error = message.error
            text = (
                error.message
                if isinstance(error, PresetError)
                else (f"{type(error).__name__}: {error}")
            )
            self.push_screen(MessageDialog("Optimisation not run", text))
            return
        if run is not None:
            self.last_optimisation = run
            if isinstance(self.screen, OptimiseScreen):
                self.screen.update_run(run)
            else:
                self.action_show_optimisation()

    def action_show_optimisation(self) -> None:
        """Show the latest optimisation's evaluations and plot."""
        if self.last_optimisation is None:
            self.notify("No optimisation has run yet (the palette's Run optimisation).")
            return
        self.push_screen(OptimiseScreen(self.last_optimisation, self.export_optimisation))

    def export_optimisation(self, run: Any) -> None:
        """Ask for a file: the evaluations' CSV there, the optimum's beside it
        (``NAME-optimum.csv``)."""

        def tables(path: Path) -> list[tuple[Path, Any]]:
            return [
                (path, run.table),
                (path.with_name(f"{path.stem}-optimum.csv"), run.optimum_table),
            ]

        self.export_tables(
            "Export the evaluations CSV to",
            self.output_dir / run.optimisation.output,
            tables,
            study_provenance("optimise", run.optimisation),
        )

    def export_tables(
        self,
        title: str,
        default: Path,
        tables: Callable[[Path], list[tuple[Path, Any]]],
        record: Any,
    ) -> None:
        """Ask for a file (``title``, ``default``) and write ``tables(path)``, each
        ``(file, CsvTable)``, atomically, each with its provenance sidecar (``record``,
        :mod:`planar_tui.provenance`), every file checked first (a sweep's CSV, an
        optimisation's two)."""

        def chosen(answer: str | None) -> None:
            if not answer:
                return
            written = tables(Path(answer))
            try:
                for path, _ in written:
                    check_writable(path)
                    if has_sidecar(path):
                        check_writable(sidecar_path(path), "provenance file")
                for path, table in written:
                    csvio.write_csv_atomic(path, table)
                    write_sidecar(path, record)
            except (PresetError, OSError) as error:
                self.push_screen(MessageDialog("Not exported", str(error)))
                return
            self.notify("Wrote " + " and ".join(str(path) for path, _ in written))

        self.push_screen(PathDialog(title, str(default)), chosen)
