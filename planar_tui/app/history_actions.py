"""The workbench's run history: every finished run kept (:mod:`planar_tui.app.runs`:
jobs, sweeps and optimisations),
result CSVs opened into it (``planar-tui tui --open``, the history's ``o``), and the
history screen (``F10``, :mod:`planar_tui.app.screens.history`)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from planar_tui.app import recent
from planar_tui.app.runs import RunHistory
from planar_tui.errors import PresetError

__all__ = ["HistoryActions"]


class HistoryActions:
    """Mixed into :class:`~planar_tui.app.app.WorkbenchApp` (Textual calls each class's
    own ``on_…`` handler along the MRO, so these run beside the app's)."""

    @property
    def run_history(self) -> RunHistory:
        """The session's runs (made on first use)."""
        history = self.__dict__.get("_run_history")
        if history is None:
            history = self.__dict__["_run_history"] = RunHistory()
        return history

    def on_job_finished(self, message: Any) -> None:
        """A job of the current tab finished: keep it (not a cancelled or failed one)."""
        if message.error is None and not message.cancelled and message.result is not None:
            started = time.time() - message.seconds
            timing = (started, message.seconds)
            self.run_history.add_result(
                message.job, message.result, timing, message.document_sha256
            )

    def on_batch_job_done(self, message: Any) -> None:
        """A job of "run all" finished: keep it."""
        self.run_history.add_result(message.job, message.result)

    def on_sweep_finished(self, message: Any) -> None:
        """A sweep ran to its end (failed points included): keep it."""
        run = message.run
        if message.error is None and not message.cancelled and run is not None:
            failed = f", {run.failed} failed" if run.failed else ""
            started = time.time() - message.seconds
            self.run_history.add_study(
                "sweep",
                run.sweep,
                run,
                f"{len(run.outcomes)} points{failed}",
                (started, message.seconds),
            )

    def on_optimise_finished(self, message: Any) -> None:
        """An optimisation ran to its end: keep it (its evaluations and its optimum)."""
        run = message.run
        if message.error is None and not message.cancelled and run is not None:
            summary = (
                f"{len(run.evaluations)} evaluations, {run.infeasible} infeasible, "
                f"{run.failed} failed"
            )
            timing = (run.started_s, time.time() - run.started_s)
            self.run_history.add_study("optimise", run.optimisation, run, summary, timing)

    def open_results(self, paths: list[Path | str]) -> None:
        """Open result CSVs into the history (``planar-tui tui --open``); the first that
        cannot be read is a :class:`PresetError` (one line, exit code 2, before the
        terminal is taken over)."""
        for path in paths:
            try:
                self.run_history.add_csv(path)
            except ValueError as error:
                raise PresetError(
                    path,
                    "(file)",
                    str(error).removeprefix(f"{path}: "),
                    "a result CSV planar-tui wrote",
                ) from None
            note = recent.remember("results", path)
            if note is not None:  # the app does not run yet: shown when it does
                self.recent_warning = note
        if paths:
            self.__dict__["_history_at_start"] = True

    def on_mount(self) -> None:
        """Results were opened at start: show the history first."""
        if self.__dict__.pop("_history_at_start", False):
            self.call_after_refresh(self.action_history)  # type: ignore[attr-defined]

    def action_history(self) -> None:
        """Show the run history (``F10``)."""
        from planar_tui.app.screens.history import HistoryScreen

        if not isinstance(self.screen, HistoryScreen):  # type: ignore[attr-defined]
            self.push_screen(HistoryScreen(self.run_history))  # type: ignore[attr-defined]
