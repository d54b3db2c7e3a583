"""Provenance sidecars: every CSV planar-tui writes gets ``NAME.csv.json`` beside it.

The sidecar says how the table was made, so a result copied off a cluster can be
opened, compared and reproduced later (``planar-tui tui --open RESULT.csv``): the package
version, the command line, the preset's path and SHA-256 digest (of its bytes), the job's
kind, robot and settings (the preset's keys as TOML values), the seed, the sample count N,
the form and the precision ε where the kind has them, the start time (UTC, ISO 8601) and
the duration in seconds.

One home: :func:`job_provenance` (a job), :func:`study_provenance` (a sweep or an
optimisation), :func:`point_provenance` (one point's tables of a sweep with
``point_outputs``: the point's job as a job's, plus ``point``: the sweep's label, the
point's number and its values by key path), :func:`write_sidecar` (written atomically right after its CSV, by the
same writers, :func:`planar_tui.csvio.write_text_atomic`) and :func:`read_sidecar`. A
sidecar is a planned output like its CSV (:func:`planned_sidecar`): the run plan checks
it before anything runs, by the CSVs' rules (:func:`planar_tui.batch.check_planned`).
The CSV's bytes do not change.
"""

from __future__ import annotations

import dataclasses
import datetime
import hashlib
import json
import os
import shlex
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from planar_tui import __version__, csvio
from planar_tui.reader import NAME_MAX_BYTES, read_bounded_text
from planar_tui.registry import JOB_KINDS
from planar_tui.schema import dump_settings

#: What a sidecar's name adds to its CSV's (``table3.csv`` -> ``table3.csv.json``).
SUFFIX = ".json"

#: Largest sidecar read back (bytes): a job's settings are a preset's table, and a preset
#: is at most :data:`planar_tui.presets.MAX_PRESET_BYTES` (4 MiB) of TOML, which JSON's
#: indented arrays make up to about 4 times longer.
MAX_SIDECAR_BYTES = 16 * 2**20

#: The sidecar format (bumped when a field changes meaning).
FORMAT = 1

#: The settings keys copied to the sidecar's top level when a kind has them: the seed,
#: the sample count N, the form, and the precision ε.
HEADLINE_KEYS = {
    "seed": "seed",
    "samples": "samples",
    "form": "form",
    "precision_cm": "precision_cm",
}


def sidecar_path(csv_path: Path | str) -> Path:
    """The sidecar of ``csv_path``: the same name with ``.json`` appended."""
    path = Path(csv_path)
    return path.with_name(path.name + SUFFIX)


def has_sidecar(csv_path: Path | str) -> bool:
    """Whether ``csv_path`` gets a sidecar: not when ``.json`` would make its name longer
    than a file name may be (255 bytes; the CSV's own name was accepted)."""
    return len(os.fsencode(sidecar_path(csv_path).name)) <= NAME_MAX_BYTES


def preset_digest(path: Path | str) -> str | None:
    """The SHA-256 of the preset file's bytes (hex), ``None`` when it cannot be read."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


#: The command line the CLI parsed (set by :class:`planar_tui.cli.output.Group`: the
#: arguments it was given, also when invoked in-process); ``None``: use ``sys.argv``.
invoked: list[str] | None = None


def command_line() -> str:
    """This process's command line as a shell would take it (``planar-tui run a.toml``)."""
    if invoked is not None:
        return shlex.join(invoked)
    name = Path(sys.argv[0]).name if sys.argv and sys.argv[0] else "planar-tui"
    if name in ("__main__.py", "-c", "-m", ""):
        name = "planar-tui"
    return shlex.join([name, *sys.argv[1:]])


def _utc(epoch_s: float | None) -> str | None:
    if epoch_s is None:
        return None
    moment = datetime.datetime.fromtimestamp(epoch_s, tz=datetime.UTC)
    return moment.isoformat(timespec="seconds")


@dataclass(frozen=True)
class Provenance:
    """One sidecar's fields (:meth:`to_json` and :meth:`from_json` round-trip)."""

    kind: str
    label: str
    preset_path: str
    preset_sha256: str | None
    settings: Mapping[str, Any]
    robot: Mapping[str, Any] = field(default_factory=dict)
    seed: int | None = None
    samples: int | None = None
    form: str | None = None
    precision_cm: float | None = None
    version: str = ""
    command: str = ""
    started_utc: str | None = None
    duration_s: float | None = None
    point: Mapping[str, Any] | None = None
    format: int = FORMAT

    def to_json(self) -> str:
        """The sidecar's text (JSON, 2-space indent, keys in field order)."""
        return json.dumps(dataclasses.asdict(self), indent=2, default=str) + "\n"

    @classmethod
    def from_json(cls, text: str) -> Provenance:
        """Read a sidecar's text; unknown keys are ignored (a newer version's), missing
        optional ones default; :class:`ValueError` naming the key if it is not a sidecar:
        every known key's type is checked (:data:`FIELD_TYPES`; ``point`` is ``{"sweep":
        text, "number": integer, "values": {key path: value}}``, ``started_utc`` an ISO
        time) and values nest at most :data:`MAX_DEPTH` levels."""
        try:
            data = json.loads(text)
        except RecursionError:
            raise ValueError(f"nested more than {MAX_DEPTH} levels deep") from None
        if not isinstance(data, dict) or not isinstance(data.get("kind"), str):
            raise ValueError("not a planar-tui provenance file (no 'kind')")
        if _depth(data) > MAX_DEPTH:
            raise ValueError(f"nested more than {MAX_DEPTH} levels deep")
        known = {key: value for key, value in data.items() if key in FIELD_TYPES}
        for required in ("label", "preset_path", "settings"):
            known.setdefault(required, {} if required == "settings" else "")
        known.setdefault("preset_sha256", None)
        for key, value in known.items():
            allowed = FIELD_TYPES[key]
            if isinstance(value, bool) or not isinstance(value, allowed):
                names = " or ".join(_JSON_NAMES[t] for t in allowed)
                raise ValueError(
                    f"{key!r} is {_JSON_NAMES.get(type(value), 'a value')}, must be {names}"
                )
        _check_point(known.get("point"))
        _check_time(known.get("started_utc"))
        return cls(**known)


#: Deepest nesting of a sidecar's values (a preset's are a few levels deep).
MAX_DEPTH = 32

#: The JSON types each sidecar key may hold (``kind`` is checked first).
FIELD_TYPES: dict[str, tuple[type, ...]] = {
    "kind": (str,),
    "label": (str,),
    "preset_path": (str,),
    "preset_sha256": (str, type(None)),
    "settings": (dict,),
    "robot": (dict,),
    "seed": (int, type(None)),
    "samples": (int, type(None)),
    "form": (str, type(None)),
    "precision_cm": (int, float, type(None)),
    "version": (str,),
    "command": (str,),
    "started_utc": (str, type(None)),
    "duration_s": (int, float, type(None)),
    "point": (dict, type(None)),
    "format": (int,),
}

_JSON_NAMES = {
    str: "text",
    dict: "an object",
    int: "an integer",
    float: "a number",
    type(None): "null",
    bool: "true or false",
    list: "an array",
}


def _depth(value: Any) -> int:
    """How deep ``value``'s arrays and objects nest (0 for a scalar), level by level
    without recursion; counting stops past :data:`MAX_DEPTH`."""
    level, frontier = 0, [value]
    while level <= MAX_DEPTH:
        containers = [item for item in frontier if isinstance(item, dict | list)]
        if not containers:
            break
        level += 1
        frontier = [
            child
            for item in containers
            for child in (item.values() if isinstance(item, dict) else item)
        ]
    return level


def _check_point(point: Any) -> None:
    """A point's ``{"sweep": text, "number": integer, "values": object}``, or ``None``."""
    if point is None:
        return
    for key, allowed, name in (
        ("sweep", str, "text"),
        ("number", int, "an integer"),
        ("values", dict, "an object"),
    ):
        value = point.get(key)
        if isinstance(value, bool) or not isinstance(value, allowed):
            raise ValueError(f"'point.{key}' must be {name}")


def _check_time(started: str | None) -> None:
    """``started_utc`` is an ISO 8601 time (or ``None``)."""
    if started is None:
        return
    try:
        datetime.datetime.fromisoformat(started).astimezone()
    except (ValueError, OverflowError):
        raise ValueError(f"'started_utc' is {started[:40]!r}, not an ISO 8601 time") from None


def _headline(settings: Mapping[str, Any]) -> dict[str, Any]:
    return {name: settings[key] for key, name in HEADLINE_KEYS.items() if key in settings}


def _made(
    kind: str,
    label: str,
    preset: Path,
    settings: Mapping[str, Any],
    robot: Mapping[str, Any],
    timing: tuple[float, float] | None,
) -> Provenance:
    started, seconds = timing if timing is not None else (None, None)
    return Provenance(
        kind=kind,
        label=label,
        preset_path=str(Path(preset).absolute()),
        preset_sha256=preset_digest(preset),
        settings=dict(settings),
        robot=dict(robot),
        version=__version__,
        command=command_line(),
        started_utc=_utc(started),
        duration_s=None if seconds is None else round(seconds, 6),
        **_headline(settings),
    )


def job_provenance(job: Any, timing: tuple[float, float] | None = None) -> Provenance:
    """The provenance of one job's tables (a :class:`~planar_tui.jobkind.Job` or a prepared
    one): its kind's settings and robot dumped as TOML values; ``timing`` is ``(start
    epoch s, duration s)`` when known."""
    settings = JOB_KINDS[job.kind].dump(job.spec)
    try:
        robot = dump_settings(job.robot)
    except (TypeError, AttributeError):  # a robot model without declared keys
        robot = {}
    return _made(job.kind, job.label, job.preset_path, settings, robot, timing)


def study_provenance(
    kind: str, study: Any, timing: tuple[float, float] | None = None
) -> Provenance:
    """The provenance of a sweep's or an optimisation's table (``kind`` ``"sweep"`` or
    ``"optimise"``): its table as written in the preset, and its base job's kind and
    settings (under ``job_kind`` and ``job_settings``); the seed, N, form and ε are the
    base job's (an optimiser's own ``seed`` stays in ``settings``)."""
    base = job_provenance(study.job)
    settings = {
        **dict(study.source),
        "job_kind": study.job.kind,
        "job_settings": dict(base.settings),
    }
    made = _made(kind, study.label, study.preset_path, settings, base.robot, timing)
    return dataclasses.replace(
        made, seed=base.seed, samples=base.samples, form=base.form, precision_cm=base.precision_cm
    )


def point_provenance(
    sweep: Any, point: Any, timing: tuple[float, float] | None = None
) -> Provenance:
    """The provenance of one point's CSV tables (``point_outputs``) of ``sweep`` (a
    :class:`~planar_tui.sweep.spec.Sweep`): the point's job (the sweep's base job with the
    point's values applied) as :func:`job_provenance` has it, and ``point`` = ``{"sweep":
    label, "number": n, "values": {key path: value}}``."""
    values = {
        path.text: value.item() if hasattr(value, "item") else value  # NumPy scalars unwrapped
        for path, value in zip(sweep.paths, point.values, strict=True)
    }
    return dataclasses.replace(
        job_provenance(point.job, timing),
        point={"sweep": sweep.label, "number": point.number, "values": values},
    )


def write_sidecar(csv_path: Path | str, record: Provenance) -> Path | None:
    """Write ``record`` beside ``csv_path`` atomically (temp file + rename); ``None``
    (nothing written) when the CSV's name leaves no room for one (:func:`has_sidecar`)."""

    if not has_sidecar(csv_path):
        return None
    return csvio.write_text_atomic(sidecar_path(csv_path), record.to_json())


def read_sidecar(csv_path: Path | str) -> Provenance | None:
    """The sidecar of ``csv_path``; ``None`` when there is none, :class:`ValueError` when
    it exists but cannot be read as one: not a regular file, larger than
    :data:`MAX_SIDECAR_BYTES` (neither is read), or not a sidecar
    (:meth:`Provenance.from_json`)."""
    path = sidecar_path(csv_path)
    try:
        text = read_bounded_text(path, MAX_SIDECAR_BYTES, "a provenance file")
    except FileNotFoundError:
        return None
    except (OSError, UnicodeDecodeError) as error:
        raise ValueError(f"{path}: cannot be read: {error}") from None
    try:
        return Provenance.from_json(text)
    except (ValueError, TypeError) as error:
        raise ValueError(f"{path}: {error}") from None


def planned_sidecar(planned: Any) -> list[Any]:
    """The sidecar of a planned CSV (a :class:`planar_tui.batch.PlannedFile`, not imported:
    the batch layer is above this one), planned too (checked as its CSV is); none when
    the CSV gets none (:func:`has_sidecar`)."""
    if not has_sidecar(planned.path):
        return []
    return [
        dataclasses.replace(
            planned,
            path=sidecar_path(planned.path),
            writer=f"{planned.writer} provenance",
            what="provenance file",
            probe=None,
        )
    ]
