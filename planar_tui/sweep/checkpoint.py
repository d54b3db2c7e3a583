"""Finished points saved as they arrive, so an interrupted sweep resumes without
recomputing them.

The checkpoint is ``OUTPUT.checkpoint.jsonl`` beside the sweep's CSV: a first line with
the sweep's fingerprint (:meth:`~planar_tui.sweep.spec.Sweep.fingerprint`) and point
count, then one JSON line per finished point, appended and flushed to disk (``fsync``)
before the next is taken. JSON writes floats in their shortest round-trip form, so a
resumed point's figures are the very numbers computed. A line cut short by a crash is
ignored (that point runs again); a checkpoint with another fingerprint (the preset
changed) is replaced, never resumed. The CLI removes the checkpoints of a run's sweeps
once every sweep of the run is done and its CSV written, so ``--resume`` after an
interrupt in a later sweep rebuilds the finished ones from their checkpoints; a run
without ``--resume`` refuses to start over a checkpoint of the same sweep
(:func:`existing_fingerprint`).
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict
from pathlib import Path

from planar_tui.csvio import write_text_atomic
from planar_tui.sweep.worker import PointOutcome

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
    except json.JSONDecodeError:
        return ""
    fingerprint = header.get("fingerprint") if isinstance(header, dict) else None
    return fingerprint if isinstance(fingerprint, str) else ""


def read_finished(path: Path, fingerprint: str, total: int) -> dict[int, PointOutcome]:
    """The finished points of a checkpoint of this sweep (by number); empty when there is
    none, or it belongs to another sweep."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (FileNotFoundError, UnicodeDecodeError):
        return {}
    try:
        header = json.loads(lines[0]) if lines else {}
    except json.JSONDecodeError:
        return {}
    if header.get("fingerprint") != fingerprint or header.get("points") != total:
        return {}
    finished = {}
    for line in lines[1:]:
        try:
            record = json.loads(line)
            outcome = PointOutcome(**record)
        except (json.JSONDecodeError, TypeError):
            continue  # a line cut short: the point runs again
        if 1 <= outcome.number <= total:
            finished[outcome.number] = outcome
    return finished


class CheckpointWriter:
    """Appends finished points to a checkpoint (started afresh, or continued on resume)."""

    def __init__(self, path: Path, fingerprint: str, total: int, finished: dict):
        self.path = path
        if not finished:
            header = json.dumps({"fingerprint": fingerprint, "points": total})
            write_text_atomic(path, header)
        else:  # keep the finished points, drop a line a crash may have cut short
            records = [json.dumps({"fingerprint": fingerprint, "points": total})]
            records += [_record(finished[n]) for n in sorted(finished)]
            write_text_atomic(path, "\n".join(records))
        self._stream = open(path, "a", encoding="utf-8")  # noqa: SIM115 (closed by close())

    def add(self, outcome: PointOutcome, sync: bool = True) -> None:
        """Save one finished point (its tables are not kept: they are written already):
        flushed to the system, and to disk unless ``sync`` is false (a caller that
        syncs a batch at once, :meth:`sync`: an optimisation's generation)."""
        self._stream.write(_record(outcome) + "\n")
        self._stream.flush()
        if sync:
            self.sync()

    def sync(self) -> None:
        """Write what was added to disk (``fsync``)."""
        os.fsync(self._stream.fileno())

    def close(self) -> None:
        self._stream.close()


def _record(outcome: PointOutcome) -> str:
    record = asdict(outcome)
    record["tables"] = {}
    return json.dumps(record)
