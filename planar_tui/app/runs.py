"""The session's run history: every finished run, and result CSVs opened from files
(plain data, no Textual here; the screen is :mod:`planar_tui.app.screens.history`).

A run keeps what made it (its :class:`~planar_tui.provenance.Provenance`: preset digest,
kind, robot, settings, seed, N, form, ε, start time and duration) and its main table.
A CSV opened from a file (``planar-tui tui --open RESULT.csv``, the history's ``o``) reads
its provenance sidecar (``RESULT.csv.json``); without one, the kind is inferred from the
header (as ``planar-tui plot`` does) and the run says so (:attr:`Run.note`). A sweep's
point CSV (``point_outputs``) opens as its job's run, labelled by the sweep and the point's
number, its values in the detail.
"""

from __future__ import annotations

import datetime
from collections.abc import Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.dispatch import recognise
from planar_tui.figures.table import read_csv
from planar_tui.provenance import Provenance, job_provenance, read_sidecar, study_provenance

#: The job kind of each table kind :func:`planar_tui.figures.dispatch.recognise` names.
TABLE_KINDS = {
    "sensitivity": "sensitivity",
    "motion uncertainty indices": "motion_uncertainty",
    "motion uncertainty band": "motion_uncertainty",
    "workspace summary": "workspace",
    "workspace boxes": "workspace boxes",
    "simulate": "simulate",
    "torques": "torques",
    "sweep": "sweep",
}

#: What a run without a sidecar says.
NO_SIDECAR = "no provenance sidecar: kind inferred from the CSV header, settings unknown"


@dataclass
class Run:
    """One run in the history: ``number`` (1, 2 … in the session), its ``kind`` (a job
    kind, ``"sweep"``, ``"optimise"`` or ``"workspace boxes"``), its ``table`` (the main
    CSV), what made it (``provenance``; ``None`` when opened without a sidecar), where it
    came from (``source``: ``"this session"`` or the CSV's path), its one-line
    ``summary``, a ``note`` (what is unknown) and, for a run of this session, its typed
    ``result`` and extra tables (a workspace's ``boxes``)."""

    number: int
    kind: str
    label: str
    table: CsvTable
    provenance: Provenance | None
    source: str = "this session"
    summary: str = ""
    note: str = ""
    result: Any = None
    extra_tables: dict[str, CsvTable] = field(default_factory=dict)

    @property
    def settings(self) -> dict[str, Any]:
        return dict(self.provenance.settings) if self.provenance is not None else {}

    def headline(self) -> dict[str, str]:
        """The history's columns: time, seed, N, form/ε, preset digest (8 hex), or ``-``."""
        p = self.provenance

        def shown(value: Any) -> str:
            return "-" if value is None else str(value)

        started = p.started_utc if p is not None else None
        time_text = "-" if started is None else _local_time(started)
        return {
            "time": time_text,
            "seed": shown(p.seed if p else None),
            "N": shown(p.samples if p else None),
            "form": shown(p.form if p else None),
            "ε (cm)": shown(p.precision_cm if p else None),
            "preset": "-" if p is None or not p.preset_sha256 else p.preset_sha256[:8],
        }

    def describe(self) -> str:
        """Several lines: the run, where it came from, its provenance and settings."""
        lines = [f"#{self.number} {self.kind}: {self.label}"]
        p = self.provenance
        if p is None:
            lines.append(self.note or NO_SIDECAR)
        else:
            lines.append(
                "settings: " + ", ".join(f"{k} = {_toml(v)}" for k, v in p.settings.items())
            )
            if p.point:  # one point's tables of a sweep (point_outputs)
                values = ", ".join(f"{k} = {_toml(v)}" for k, v in p.point["values"].items())
                lines.append(f"point {p.point['number']} of {p.point['sweep']}: {values}")
            if self.note:
                lines.append(self.note)
        if self.summary:
            lines.append(f"result: {self.summary}")
        lines.append(
            f"table: {len(self.table.rows)} rows × {len(self.table.header)} columns"
            f" · source: {self.source}"
        )
        if p is not None:
            lines += [
                f"started: {p.started_utc or '-'}   duration: "
                + ("-" if p.duration_s is None else f"{p.duration_s:.3f} s"),
                f"preset: {p.preset_path} (sha256 {p.preset_sha256 or 'unknown'})",
                f"command: {p.command or '-'}   version: {p.version or '-'}",
            ]
            if p.robot:
                lines.append("robot: " + ", ".join(f"{k} = {_toml(v)}" for k, v in p.robot.items()))
        return "\n".join(lines)


def _toml(value: Any) -> str:
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return str(value)


def _local_time(iso: str) -> str:
    """``HH:MM:SS`` of an ISO time in this machine's zone (the date too if not today)."""
    try:
        moment = datetime.datetime.fromisoformat(iso).astimezone()
    except ValueError:
        return iso
    today = datetime.datetime.now().astimezone().date()
    return moment.strftime("%H:%M:%S" if moment.date() == today else "%Y-%m-%d %H:%M")


def table_kind(table: CsvTable) -> str | None:
    """The kind of a result table by its header (:func:`planar_tui.figures.dispatch.
    recognise`), as a job kind (:data:`TABLE_KINDS`), or ``"optimise"`` (``evaluation``
    first, ``status, message`` last); ``None`` if not recognised."""
    found = recognise(table.header)
    if (
        found is None
        and table.header[:1] == ("evaluation",)
        and table.header[-2:]
        == (
            "status",
            "message",
        )
    ):
        return "optimise"  # an optimisation's evaluations or optimum (drawn by its screen)
    return None if found is None else TABLE_KINDS.get(found, found)


class RunHistory:
    """Every run of the session, oldest first (numbered from 1)."""

    def __init__(self) -> None:
        self.runs: list[Run] = []

    def __iter__(self) -> Iterator[Run]:
        return iter(self.runs)

    def __len__(self) -> int:
        return len(self.runs)

    def _add(self, **fields: Any) -> Run:
        run = Run(number=len(self.runs) + 1, **fields)
        self.runs.append(run)
        return run

    def add_result(
        self,
        job: Any,
        result: Any,
        timing: tuple[float, float] | None = None,
        document_sha256: str | None = None,
    ) -> Run:
        """Keep a finished job of this session (``timing``: start epoch s, duration s;
        ``document_sha256``: the digest of the edited document it ran from, kept instead
        of the file's, which no longer says what ran)."""
        provenance = job_provenance(job, timing)
        if document_sha256 is not None:
            provenance = replace(provenance, preset_sha256=document_sha256)
        return self._add(
            kind=job.kind,
            label=job.label,
            table=result.table,
            provenance=provenance,
            summary=result.summary,
            result=result,
            extra_tables=dict(result.extra_tables),
        )

    def add_study(
        self,
        kind: str,
        study: Any,
        result: Any,
        summary: str,
        timing: tuple[float, float] | None = None,
    ) -> Run:
        """Keep a finished sweep or optimisation of this session (``kind`` ``"sweep"`` or
        ``"optimise"``; ``study`` its :class:`~planar_tui.sweep.spec.Sweep` or
        :class:`~planar_tui.optimise.problem.Optimisation`, ``result`` its run: the table it
        writes, and an optimisation's optimum as the extra table ``optimum``)."""
        extra = {"optimum": result.optimum_table} if kind == "optimise" else {}
        return self._add(
            kind=kind,
            label=study.label,
            table=result.table,
            provenance=study_provenance(kind, study, timing),
            summary=summary,
            result=result,
            extra_tables=extra,
        )

    def add_csv(self, path: Path | str) -> Run:
        """Open a result CSV into the history, with its sidecar if it has one (else the
        kind inferred from the header, and :data:`NO_SIDECAR` as its note);
        :class:`ValueError` (the message names the file) when it cannot be read or is no
        result planar-tui writes."""
        path = Path(path)
        try:
            table = read_csv(path)
        except (OSError, UnicodeDecodeError, ValueError) as error:
            reason = getattr(error, "strerror", None) or str(error)
            raise ValueError(f"{path}: cannot be read: {reason}") from None
        record = read_sidecar(path)
        inferred = table_kind(table)
        if record is None and inferred is None:
            raise ValueError(f"{path}: not a result CSV planar-tui writes (header not recognised)")
        kind = record.kind if record is not None else str(inferred)
        note = "" if record is not None else NO_SIDECAR
        if record is not None and inferred not in (None, kind):
            kind_ok = record.kind in ("sweep", "optimise") or inferred == "workspace boxes"
            if not kind_ok:
                note = f"note: the sidecar says {record.kind}, the header looks like {inferred}"
        label = record.label if record is not None else path.stem
        if record is not None and record.point:
            label = f"{record.point['sweep']} point {record.point['number']}"
        summary = f"{len(table.rows)} rows from {path.name}"
        return self._add(
            kind=kind,
            label=label,
            table=table,
            provenance=record,
            source=str(path),
            summary=summary,
            note=note,
        )

    def of_kind(self, kind: str) -> list[Run]:
        return [run for run in self.runs if run.kind == kind]

    def partner(self, run: Run) -> Run | None:
        """The run to compare ``run`` with by default: the latest other run of its kind."""
        others = [other for other in self.of_kind(run.kind) if other is not run]
        return others[-1] if others else None
