"""Finished points saved as they arrive, so an interrupted sweep resumes without
recomputing them.

The checkpoint is ``OUTPUT.checkpoint.jsonl`` beside the sweep's CSV: a first line with
the sweep's fingerprint (:meth:`~planar_tui.sweep.spec.Sweep.fingerprint`) and point
count, then one JSON line per finished point, appended and flushed to disk (``fsync``)
before the next is taken. JSON writes floats in their shortest round-trip form, so a
resumed point's figures are the very numbers computed. A line cut short by a crash is
ignored (that point runs again); any other record that is not a finished point of this
sweep (:func:`record_problem`), or whose digest is not this run's (:func:`record_digest`:
edited by hand, damaged), is dropped with one warning line naming the file and line, and
its point runs again; a checkpoint with another fingerprint (the preset
changed) is replaced, never resumed. The CLI removes the checkpoints of a run's sweeps
once every sweep of the run is done and its CSV written, so ``--resume`` after an
interrupt in a later sweep rebuilds the finished ones from their checkpoints; a run
without ``--resume`` refuses to start over a checkpoint of the same sweep
(:func:`existing_fingerprint`).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Callable, Collection
from dataclasses import asdict
from pathlib import Path
from typing import Any

from planar_tui.csvio import write_text_atomic
from planar_tui.errors import writing
from planar_tui.sweep.worker import FAILED, INFEASIBLE, OK, PointOutcome

SUFFIX = ".checkpoint.jsonl"


def checkpoint_path(output: Path) -> Path:
    """Where the checkpoint of the sweep writing ``output`` lives."""
    return output.with_name(output.name + SUFFIX)


def existing_fingerprint(path: Path) -> str | None:
    """The fingerprint in the checkpoint at ``path``: ``None`` when there is no file,
    ``""`` when its first line names none (unreadable, cut short)."""
    try:
        with open(path, encoding="utf-8") as stream:
            first = stream.readline()
    except FileNotFoundError:
        return None
    except (OSError, UnicodeDecodeError):
        return ""
    try:
        header = json.loads(first)
    except (json.JSONDecodeError, RecursionError):
        return ""
    fingerprint = header.get("fingerprint") if isinstance(header, dict) else None
    return fingerprint if isinstance(fingerprint, str) else ""


#: Most warning lines about dropped records one checkpoint gives (then a count).
MAX_WARNINGS = 5
#: The statuses a finished point may have.
STATUSES = (OK, FAILED, INFEASIBLE)
#: Longest text a record's message or text figure may hold.
MAX_TEXT = 10_000


def _finite(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def record_problem(
    record: Any, total: int, seen: set[int], columns: Callable[[int], Collection[str] | None]
) -> str | None:
    """Why a checkpoint record cannot be a finished point of this sweep, or ``None``: it
    must be an object with exactly :class:`PointOutcome`'s fields, a ``number`` an
    integer in 1..``total`` not seen before, a ``status`` of :data:`STATUSES`, a one-line
    ``message``, finite ``seconds`` >= 0, no ``tables``, and ``figures`` a mapping of the
    kind's own columns (``columns(number)``, where the kind names them; ``None`` where
    not) to finite numbers or one-line text (none for a failed point)."""
    if not isinstance(record, dict):
        return "not a JSON object"
    fields = {"number", "status", "message", "figures", "seconds", "tables"}
    if set(record) != fields:
        odd = sorted(set(record) ^ fields)
        return f"fields {', '.join(odd)} missing or unknown"
    number = record["number"]
    if not isinstance(number, int) or isinstance(number, bool) or not 1 <= number <= total:
        return f"number {shown_value(number)} is not an integer in 1..{total}"
    if number in seen:
        return f"point {number} is recorded twice"
    if record["status"] not in STATUSES:
        return f"status {shown_value(record['status'])} is not one of {', '.join(STATUSES)}"
    message = record["message"]
    if not isinstance(message, str) or "\n" in message or len(message) > MAX_TEXT:
        return "message is not one line of text"
    if not _finite(record["seconds"]) or record["seconds"] < 0:
        return f"seconds {shown_value(record['seconds'])} is not a finite number >= 0"
    if record["tables"] != {}:
        return "tables is not empty"
    figures = record["figures"]
    if not isinstance(figures, dict):
        return f"figures {shown_value(figures)} is not a mapping"
    if record["status"] != OK and figures:
        return (
            "a failed point has figures"
            if record["status"] == FAILED
            else ("an infeasible point has figures")
        )
    known = columns(number) if record["status"] == OK else ()
    for name, value in figures.items():
        if known is not None and name not in known:
            return f"figure {shown_value(name)} is not a column of this job"
        if not (
            _finite(value)
            or (isinstance(value, str) and "\n" not in value and len(value) <= MAX_TEXT)
        ):
            return f"figure {name} = {shown_value(value)} is not a finite number or text"
    if known is not None and record["status"] == OK and set(known) - set(figures):
        return f"figure {sorted(set(known) - set(figures))[0]} is missing"
    return None


def shown_value(value: Any) -> str:
    """A record's value for a message: its JSON text, cut to 40 characters."""
    text = json.dumps(value)
    return text if len(text) <= 40 else text[:37] + "..."


def record_digest(fingerprint: str, record: dict[str, Any]) -> str:
    """A record's digest: SHA-256 (hex) of the run's fingerprint, a newline and the
    record's JSON without its ``digest``, keys sorted. It ties the record to this run:
    one edited by hand, damaged, or copied from another run's checkpoint does not match."""
    body = {key: value for key, value in record.items() if key != "digest"}
    text = fingerprint + "\n" + json.dumps(body, sort_keys=True)
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()


def digest_problem(record: dict[str, Any], digest: Any, fingerprint: str) -> str | None:
    """Why ``digest`` (read with ``record``, then taken out of it) is not
    :func:`record_digest`'s, or ``None``."""
    if digest != record_digest(fingerprint, record):
        return "its digest is not this run's: edited, damaged or from another run"
    return None


def read_finished(
    path: Path,
    fingerprint: str,
    total: int,
    columns: Callable[[int], Collection[str] | None] = lambda number: None,
    warn: Callable[[str], None] = lambda text: None,
) -> dict[int, PointOutcome]:
    """The finished points of a checkpoint of this sweep (by number); empty when there is
    none, or it belongs to another sweep. A record that fails :func:`record_problem` is
    dropped with one ``warn`` line naming the file and line (that point runs again); a
    line cut short by a crash (the last one) is dropped silently."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return {}
    try:
        header = json.loads(lines[0]) if lines else {}
    except (json.JSONDecodeError, RecursionError):
        header = None
    if not isinstance(header, dict):
        warn(f"{path}:1: not a checkpoint header: every point runs")
        return {}
    if header.get("fingerprint") != fingerprint or header.get("points") != total:
        return {}
    finished: dict[int, PointOutcome] = {}
    dropped = 0
    for number, line in enumerate(lines[1:], start=2):
        try:
            record = json.loads(line)
        except (json.JSONDecodeError, RecursionError):
            if number == len(lines):
                continue  # the last line, cut short by a crash: the point runs again
            record, problem = None, "not JSON"
        else:
            digest = record.pop("digest", None) if isinstance(record, dict) else None
            problem = record_problem(record, total, set(finished), columns) or digest_problem(
                record, digest, fingerprint
            )
        if problem is not None:
            dropped += 1
            if dropped <= MAX_WARNINGS:
                warn(f"{path}:{number}: record dropped ({problem}): its point runs again")
            continue
        outcome = PointOutcome(**record)
        finished[outcome.number] = outcome
    if dropped > MAX_WARNINGS:
        warn(f"{path}: {dropped - MAX_WARNINGS} more records dropped: their points run again")
    return finished


class CheckpointWriter:
    """Appends finished points to a checkpoint (started afresh, or continued on resume); a
    write that fails is :class:`~planar_tui.errors.OutputFailed` on the checkpoint."""

    def __init__(self, path: Path, fingerprint: str, total: int, finished: dict):
        self.path = path
        self.fingerprint = fingerprint
        with writing(path):
            if not finished:
                header = json.dumps({"fingerprint": fingerprint, "points": total})
                write_text_atomic(path, header)
            else:  # keep the finished points, drop a line a crash may have cut short
                records = [json.dumps({"fingerprint": fingerprint, "points": total})]
                records += [_record(finished[n], fingerprint) for n in sorted(finished)]
                write_text_atomic(path, "\n".join(records))
            self._stream = open(path, "a", encoding="utf-8")  # noqa: SIM115 (closed by close())

    def add(self, outcome: PointOutcome, sync: bool = True) -> None:
        """Save one finished point (its tables are not kept: they are written already):
        flushed to the system, and to disk unless ``sync`` is false (a caller that
        syncs a batch at once, :meth:`sync`: an optimisation's generation)."""
        with writing(self.path):
            self._stream.write(_record(outcome, self.fingerprint) + "\n")
            self._stream.flush()
            if sync:
                os.fsync(self._stream.fileno())

    def sync(self) -> None:
        """Write what was added to disk (``fsync``)."""
        with writing(self.path):
            os.fsync(self._stream.fileno())

    def close(self) -> None:
        self._stream.close()


def _record(outcome: PointOutcome, fingerprint: str) -> str:
    record = asdict(outcome)
    record["tables"] = {}
    record["digest"] = record_digest(fingerprint, record)
    return json.dumps(record)
