"""The workbench's exports: the result on screen into a folder, named and written as
``planar-tui run --out-dir`` names and writes them (asking before any file is
overwritten), and its figure (``ctrl+l``) beside them; every failure becomes a dialog."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from planar_tui import batch
from planar_tui.app.saving import existing_files
from planar_tui.app.screens.dialogs import ConfirmDialog, MessageDialog, PathDialog
from planar_tui.app.screens.sweep import SweepScreen
from planar_tui.batch import plan_outputs
from planar_tui.errors import OutputFailed, PresetError
from planar_tui.figures import save_result_figure
from planar_tui.plan import plan_run
from planar_tui.provenance import sidecar_path
from planar_tui.sweep.service import output_path, write_figure

if TYPE_CHECKING:
    from planar_tui.app.widgets.panes import JobPane

__all__ = ["ExportActions"]


class ExportActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp` (which provides
    ``output_dir``, ``current_pane``, ``dialog_open`` and Textual's ``App``)."""

    output_dir: Path

    # -- export -----------------------------------------------------------------------
    def action_export(self) -> None:
        """Write the result on screen into a folder, named as the CLI names it (on the
        sweep screen: the sweep CSV into a file)."""
        if isinstance(self.screen, SweepScreen):
            self.screen.action_export()
            return
        if self.dialog_open():
            return
        from planar_tui.app.widgets.panes import JobPane

        pane = self.current_pane()
        if not isinstance(pane, JobPane) or pane.result is None or pane.job is None:
            self.notify("Nothing to export: run a job on this tab first.", severity="warning")
            return
        (plan,) = plan_outputs([pane.job], Path())
        names = ", ".join(str(path) for path in plan.paths())

        def chosen(answer: str | None) -> None:
            if answer:
                self.confirm_export(pane, answer)

        hint = f"Writes {names} there (as planar-tui run --out-dir).\nEnter: write   Escape: cancel"
        self.push_screen(PathDialog("Export to folder", str(self.output_dir), hint), chosen)

    def confirm_export(self, pane: JobPane, out_dir: str | Path) -> None:
        """Export into ``out_dir``, asking first when files there would be overwritten."""
        if pane.job is None:
            return
        try:
            (plan,) = plan_run([pane.job], Path(out_dir), prepare=False).jobs
        except (PresetError, OSError, ValueError) as error:
            self.push_screen(MessageDialog("Not exported", str(error)))
            return

        tables = (plan.main, *plan.extras.values())
        existing = existing_files([*plan.paths(), *map(sidecar_path, tables)])
        if not existing:
            self.export_csv(pane, out_dir)
            return

        def answered(yes: bool | None) -> None:
            if yes:
                self.export_csv(pane, out_dir)

        count = f"{len(existing)} file{'s' if len(existing) > 1 else ''}"
        listing = "\n".join(str(path) for path in existing)
        dialog = ConfirmDialog(
            f"Overwrite {count}?", detail=listing, yes="Overwrite (y)", no="Cancel (n)"
        )
        self.push_screen(dialog, answered)

    # -- figure -----------------------------------------------------------------------
    def figure_path(self, pane: JobPane) -> Path:
        """Where the pane's figure goes: the job's ``plot`` key, else the CSV that Export
        would write into the output folder with the suffix ``.png`` (beside it)."""
        (plan,) = plan_outputs([pane.job], self.output_dir)
        return plan.figure or plan.main.with_suffix(".png")

    def sweep_figure_path(self, run: Any) -> Path:
        """Where a sweep's figure goes: its ``plot`` key in the output folder (as
        ``planar-tui sweep --out-dir`` puts it), else the CSV the sweep screen exports by
        default with the suffix ``.png`` (beside it)."""
        if run.sweep.plot is not None:
            return self.output_dir / run.sweep.plot
        return output_path(run.sweep, self.output_dir).with_suffix(".png")

    def action_figure(self) -> None:
        """Write the figure of the result on screen beside its CSV (``ctrl+l``; on the
        sweep screen, the sweep's figure), asking before it replaces a file; drawn in a
        thread (matplotlib, about a second)."""
        if isinstance(self.screen, SweepScreen):
            run = self.screen.run
            self.confirm_figure(self.sweep_figure_path(run), lambda path: write_figure(run, path))
            return
        if self.dialog_open():
            return
        from planar_tui.app.widgets.panes import JobPane

        pane = self.current_pane()
        if not isinstance(pane, JobPane) or pane.result is None or pane.job is None:
            self.notify("No figure: run a job on this tab first.", severity="warning")
            return
        job, result = pane.job, pane.result

        def save(path: Path) -> Path:
            return save_result_figure(job, result, path)

        self.confirm_figure(self.figure_path(pane), save)

    def confirm_figure(self, path: Path, save: Callable[[Path], Path]) -> None:
        """Write a figure with ``save`` into ``path`` (:meth:`write_figure`), asking first
        when the file exists."""
        if not existing_files([path]):
            self.write_figure(path, save)
            return

        def answered(yes: bool | None) -> None:
            if yes:
                self.write_figure(path, save)

        dialog = ConfirmDialog(
            "Overwrite 1 file?", detail=str(path), yes="Overwrite (y)", no="Cancel (n)"
        )
        self.push_screen(dialog, answered)

    def write_figure(self, path: Path, save: Callable[[Path], Path]) -> None:
        """Draw and write a figure (``save(path)``) in a worker thread; notify the path,
        or show why it failed in a dialog (nothing written)."""
        try:
            batch.check_writable(path, "figure file")
        except PresetError as error:
            self.push_screen(MessageDialog("No figure written", str(error)))
            return

        def draw() -> None:
            try:
                written = save(path)
            except Exception as error:  # any drawing failure: a dialog, never a crash
                message = (
                    str(error)
                    if isinstance(error, OutputFailed)
                    else (f"{path}: cannot write: {error}")
                )
                self.call_from_thread(self.push_screen, MessageDialog("No figure written", message))
                return
            self.call_from_thread(self.notify, f"Wrote {written}", title="Figure")

        self.notify(f"Drawing {path} …", title="Figure")
        self.run_worker(draw, thread=True, group="figure", exit_on_error=False)

    def export_csv(self, pane: JobPane, out_dir: str | Path) -> list[Path]:
        """Write the pane's result into ``out_dir`` exactly as ``planar-tui run --out-dir``
        does: the job's ``output`` CSV and the extra tables its preset names (a workspace's
        ``boxes_output``), through the batch service; nothing on an error (a dialog)."""
        if pane.job is None or pane.result is None:
            return []

        try:
            (plan,) = plan_run([pane.job], Path(out_dir), prepare=False).jobs
            written = batch.write_result(plan, pane.result)
        except (PresetError, OutputFailed, OSError, ValueError) as error:
            self.push_screen(MessageDialog("Not exported", str(error)))
            return []
        self.notify("Wrote " + ", ".join(map(str, written)))
        return written
