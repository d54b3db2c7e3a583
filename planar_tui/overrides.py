"""Command-line overrides of a job's settings: the one option reader of every kind
(:func:`override_job`, the job's table read again with the options' values in place of
their keys), the variant the changed settings add to the names of the files the preset
names, and the selection of jobs by ``--job``."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.jobkind import Job, Option
from planar_tui.reader import TableReader
from planar_tui.registry import JOB_KINDS
from planar_tui.schema import declared_keys


def job_names(job: Job) -> tuple[str, ...]:
    """The names ``--job`` selects a job by: its table key (``workspace[2]``), its label
    (``paper-b-table3:workspace[2]``) and its output file name (``table3-slope.csv``)."""
    return (job.key, job.label, job.output)


def select_jobs(jobs: Sequence[Job], names: Sequence[str] | None) -> tuple[Job, ...]:
    """The jobs any of ``names`` names (:func:`job_names`), in preset order; every job
    when ``names`` is empty. A name that matches no job is a :class:`PresetError` listing
    the valid keys (labels when the jobs come from several presets)."""
    if not names:
        return tuple(jobs)
    for name in names:
        if not any(name in job_names(job) for job in jobs):
            several = len({job.preset_path for job in jobs}) > 1
            valid = ", ".join(dict.fromkeys(job.label if several else job.key for job in jobs))
            raise PresetError(
                "command line",
                "--job",
                f"is {name!r}, no such job",
                f"one of {valid or '(no job)'}, or a job's output file name",
            )
    return tuple(job for job in jobs if any(name in job_names(job) for name in names))


def with_variant(path: Path, variant: str) -> Path:
    """``path`` with ``variant`` appended to its stem (``a.csv`` -> ``a--form-slope.csv``)."""
    return path.with_name(f"{path.stem}{variant}{path.suffix}") if variant else path


def _option_text(value: Any) -> str:
    """An override's value as it goes into a file name: lists joined by ``+``, floats in
    shortest round-trip form (``0.1171875``, ``0.5``)."""
    if isinstance(value, list | tuple):
        return "+".join(_option_text(item) for item in value)
    return repr(value) if isinstance(value, float) else str(value)


def override_variant(before: Any, after: Any, options: Sequence[Option]) -> str:
    """``--OPTION-VALUE`` for each option that changed a setting from ``before`` to
    ``after`` (``--form-mean-value--precision-0.5``), in the order of ``options``."""
    attributes = {key.name: attribute for attribute, key in declared_keys(type(after))}
    parts = []
    for option in options:
        attribute = attributes[option.key]
        if getattr(before, attribute, None) != getattr(after, attribute, None):
            parts.append(f"--{option.label}-{_option_text(getattr(after, attribute))}")
    return "".join(parts)


class _OverrideReader(TableReader):
    """A job's table (its settings dumped, its ``output``) with the command-line options'
    values in place of their keys, read again by the settings' own readers and checks: a
    problem names the option (``command line: --samples``), the option of the key when one
    set it, else the first option given (the preset alone was valid)."""

    def __init__(self, job: Job, table: dict[str, Any], given: Mapping[str, Option]):
        super().__init__(job.preset_path, table, job.key, tuple(table))
        self.given = given

    def error(self, name: str, problem: str, expected: str | None = None) -> PresetError:
        option = self.given.get(name) or next(iter(self.given.values()))
        return PresetError("command line", option.name, problem, expected)


def _given(value: Any) -> bool:
    return value is not None and value != [] and value != ()


def override_job(job: Job, values: Mapping[str, Any]) -> Job:
    """``job`` with the command-line options of its kind's command applied: ``values`` by
    option name (``--samples``; ``None`` or an empty list keeps the preset's value).

    The one option reader of every kind: each given value replaces its key in the job's
    table, the kind's ``overrides`` hook adjusts the keys that follow it, and the table is
    read again by the settings' own readers and cross-key checks, so an option is checked
    exactly as its key is; a problem is a :class:`PresetError` ``command line: --OPTION``
    (:class:`_OverrideReader`). The job records what changed: its ``variant``
    (:func:`override_variant`) and ``overridden`` (key -> option).
    """
    kind = JOB_KINDS[job.kind]
    options = kind.command.options if kind.command is not None else ()
    given = {option.key: option for option in options if _given(values.get(option.name))}
    if not given:
        return job
    table = {"output": job.output, **kind.dump(job.spec)}
    table.update({key: values[option.name] for key, option in given.items()})
    if kind.overrides is not None:
        table = kind.overrides(table, {key: table[key] for key in given})
    spec = kind.parse(_OverrideReader(job, table, given), job.robot)
    variant = override_variant(job.spec, spec, options)
    overridden = {**job.overridden, **{key: option.name for key, option in given.items()}}
    return dataclasses.replace(job, spec=spec, variant=job.variant + variant, overridden=overridden)


def apply_overrides(jobs: Sequence[Job], values: Mapping[str, Any]) -> tuple[Job, ...]:
    """The jobs with command-line options applied (:func:`override_job`), each checked by
    its kind. A job whose settings an option changed gets the variant
    :func:`override_variant`, so the files the preset names say what was run:
    ``table3-natural--form-mean-value.csv``. An option equal to the preset's value changes
    nothing, names included."""
    return tuple(override_job(job, values) for job in jobs)
