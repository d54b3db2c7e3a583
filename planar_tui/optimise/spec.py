"""The ``[[optimise]]`` table of a preset, read and checked: which job, which key paths it
varies and over what (``variables``), what it maximises or minimises (columns of the job's
summary figures, one or several), under which ``constraints``, with how many evaluations.

The keys are declared once (:class:`OptimiseTable`, :func:`planar_tui.schema.setting`):
the declaration reads them, names the allowed keys and writes the preset reference
(``docs/gen_reference.py``). Key paths and the job come from the sweep's readers
(:func:`planar_tui.sweep.spec.job_context`, :func:`~planar_tui.sweep.spec.read_key_path`),
with the sweep's one-line errors.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.optimise import TABLE
from planar_tui.optimise.problem import Constraint, Objective, Optimisation, Variable
from planar_tui.presets import Preset
from planar_tui.registry import JOB_KINDS
from planar_tui.schema import (
    REQUIRED,
    TableReader,
    figure_path,
    integer,
    parse_settings,
    relative_path,
    setting,
    setting_keys,
    shown,
    string,
    type_name,
)
from planar_tui.sweep.paths import KeyPath, overlap_problem
from planar_tui.sweep.points import make_point
from planar_tui.sweep.spec import (
    job_context,
    plain_toml,
    read_key_path,
)

ALGORITHMS = ("auto", "ga", "de", "nsga2")
#: Most evaluations an optimisation may have.
MAX_BUDGET = 100_000
_CONSTRAINT = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*(>=|<=|>|<)\s*(\S+)\s*$")
_VARIABLE_DOC = (
    "{ from = A, to = B }, { from = A, to = B, integer = true } or { choices = [...] }; "
    "optionally fixed_sum = { KEY = TOTAL }"
)


def _raw(expected: str):
    """A key read as written (checked by :func:`parse_optimise_table`)."""

    def read(reader, name, default, context, values):
        return reader.raw(name, default, expected)

    return read


@dataclass(frozen=True, kw_only=True)
class OptimiseTable:
    """The keys of an ``[[optimise]]`` table, as written (before the cross-checks)."""

    job: str = setting(
        _raw("a job of the preset, e.g. workspace[2]"),
        type_doc='`"kind"` or `"kind[k]"`',
        doc="the job to optimise (`kind` alone: its first table)",
    )
    variables: dict = setting(
        _raw("a table of key paths"),
        type_doc=f"table of key path → `{_VARIABLE_DOC}`",
        doc="what varies: a number in [from, to], an integer in [from, to], or one of the "
        "choices (a form, an elbow mode); key paths as in `[[sweep]]`; `fixed_sum = { KEY = "
        "TOTAL }` sets another key path to `TOTAL −` the sum of the variables naming it "
        "(a fixed leg length or reach)",
    )
    maximise: Any = setting(
        _raw("a column name or a list of them"),
        default=None,
        default_doc="(or `minimise`)",
        type_doc="column name or list of them",
        doc="the job's summary column(s) to maximise; with `minimise`, two or more "
        "objectives in all give a Pareto set (NSGA-II)",
    )
    minimise: Any = setting(
        _raw("a column name or a list of them"),
        default=None,
        default_doc="(or `maximise`)",
        type_doc="column name or list of them",
        doc="the job's summary column(s) to minimise",
    )
    constraints: Any = setting(
        _raw('a list of "COLUMN >= NUMBER"'),
        default=(),
        type_doc='list of `"COLUMN OP NUMBER"`',
        doc="each held at every accepted design, `OP` one of `>=`, `<=`, `>`, `<` (as "
        "`G ≤ 0` for pymoo); a failed evaluation is infeasible",
    )
    budget: int = setting(
        integer(minimum=1, maximum=MAX_BUDGET),
        default=200,
        type_doc=f"integer 1 … {MAX_BUDGET:,}",
        doc="most evaluations (generations of `population`; the last one cut to fit)",
    )
    population: int = setting(
        integer(minimum=2, maximum=10_000),
        default=20,
        type_doc="integer ≥ 2",
        doc="designs per generation (submitted to the workers at once)",
    )
    algorithm: str = setting(
        string(choices=ALGORITHMS),
        default="auto",
        type_doc="`" + '"`, `"'.join(ALGORITHMS).join('""') + "`",
        doc='`"auto"`: a GA for one objective, NSGA-II for several; `"de"`: '
        "differential evolution (one objective)",
    )
    seed: int = setting(
        integer(minimum=0, maximum=2**32 - 1),
        default=1,
        type_doc="integer ≥ 0",
        doc="the optimiser's seed: the same seed gives the same CSV on any number of workers",
    )
    coarse: dict = setting(
        _raw("a table of key path = value"),
        default=None,
        default_doc="(none)",
        type_doc="table of key path → value",
        doc="settings of the evaluations (e.g. `{ precision_cm = 1.875 }`); the optimum is "
        "re-run at the job's own settings",
    )
    output: str = setting(
        relative_path(),
        default=None,
        default_doc="`PRESET-optimise-K.csv`",
        type_doc="relative path",
        doc="CSV of every evaluation",
    )
    pareto_output: str = setting(
        relative_path(),
        default=None,
        default_doc="`OUTPUT-optimum.csv`",
        type_doc="relative path",
        doc="CSV of the optimum (or the Pareto set) re-run at the job's "
        "own settings, with all its columns",
    )
    plot: str | None = setting(
        figure_path(),
        default=None,
        default_doc="(none)",
        type_doc="relative path ending `.svg`, `.png` or `.pdf`",
        doc="convergence (one objective) or front (two) figure; `--plot FILE` overrides it",
    )


def _quoted(path: str) -> str:
    return f'"{path}"' if any(c in path for c in ".[]") else path


def _read_variable(
    reader: TableReader,
    key: str,
    path: KeyPath,
    entry: Any,
    key_path: Callable[[str, str], KeyPath],
) -> Variable:
    if not isinstance(entry, dict):
        raise reader.error(key, f"is {type_name(entry)}", _VARIABLE_DOC)
    spec = TableReader(
        reader.path, entry, reader.key(key), ("from", "to", "integer", "choices", "fixed_sum")
    )
    if spec.has("choices"):
        if spec.has("from") or spec.has("to") or spec.has("integer") or spec.has("fixed_sum"):
            raise spec.error("choices", "is given with from/to/integer/fixed_sum", _VARIABLE_DOC)
        choices = spec.raw("choices")
        if not isinstance(choices, list) or not choices:
            what = "empty" if choices == [] else type_name(choices)
            raise spec.error("choices", f"is {what}", "a non-empty array of values")
        return Variable(path, choices=tuple(choices))
    whole = spec.boolean("integer", False)
    read = spec.integer if whole else spec.number
    low, high = float(read("from")), float(read("to"))
    if low >= high:
        raise spec.error(
            "to", f"is {shown(entry['to'])}, not above from = {shown(entry['from'])}", "to > from"
        )
    sums = spec.raw("fixed_sum", None)
    if sums is None:
        return Variable(path, float(low), float(high), whole)
    if not isinstance(sums, dict) or not sums:
        raise spec.error(
            "fixed_sum",
            f"is {'empty' if sums == {} else type_name(sums)}",
            "{ KEY = TOTAL }: the key path takes TOTAL − the variable",
        )
    fixed = TableReader(spec.path, sums, spec.key("fixed_sum"), tuple(sums))
    fixed_sum = tuple((key_path(f"{key}.fixed_sum", text), fixed.number(text)) for text in sums)
    if len({(p.table, p.key, p.indices) for p, _ in fixed_sum}) < len(fixed_sum):
        raise spec.error("fixed_sum", "names one key path twice", "each key path once")
    return Variable(path, float(low), float(high), whole, fixed_sum=fixed_sum)


def _columns(reader: TableReader, name: str, value: Any) -> list[str]:
    expected = "a column name of the job's CSV, or a list of them"
    items = value if isinstance(value, list) else [value]
    if not items or not all(isinstance(item, str) and item for item in items):
        raise reader.error(
            name,
            f"is {type_name(value)}" if not isinstance(value, list) else f"is {shown(value)}",
            expected,
        )
    return items


def parse_constraint(reader: TableReader, index: int, text: Any) -> Constraint:
    """``"column OP number"``: a column name, one of ``>=``, ``<=``, ``>``, ``<``, a finite
    number."""
    name = f"constraints[{index}]"
    expected = '"COLUMN OP NUMBER" with OP one of >=, <=, >, < (e.g. "circle_radius_lo_cm >= 3")'
    if not isinstance(text, str):
        raise reader.error(name, f"is {type_name(text)}", expected)
    match = _CONSTRAINT.match(text)
    if match is None:
        raise reader.error(name, f"is {shown(text)}", expected)
    column, operator, number = match.groups()
    try:
        bound = float(number)
    except ValueError:
        bound = math.nan
    if not math.isfinite(bound):
        raise reader.error(name, f"is {shown(text)}: {number!r} is not a finite number", expected)
    return Constraint(text.strip(), column, operator, bound)


def parse_optimise_table(preset: Preset, table: Any, name: str, number: int = 1) -> Optimisation:
    """One ``[[optimise]]`` table (``name`` in messages, e.g. ``optimise[2]``), checked
    against the preset's jobs (:class:`PresetError` otherwise)."""
    path = preset.path
    if not isinstance(table, Mapping):
        raise PresetError(path, name, f"is {type_name(table)}", "a table [[optimise]]")
    table = plain_toml(table)
    reader = TableReader(path, table, name, setting_keys(OptimiseTable))
    keys = parse_settings(OptimiseTable, reader)
    job, tables, defaults = job_context(preset, reader)
    if keys.variables is REQUIRED or not isinstance(keys.variables, dict) or not keys.variables:
        what = "empty" if keys.variables == {} else type_name(keys.variables)
        raise reader.error(
            "variables",
            f"is {what}",
            "a table of key paths, e.g. { orientation_deg = { from = -45, to = 45 } }",
        )
    variables: list[Variable] = []
    seen: dict[tuple, str] = {}

    def key_path(group: str, text: str) -> KeyPath:
        key = f"{group}.{_quoted(text)}"
        parsed = read_key_path(reader, job, tables, defaults, key, text)
        place = (parsed.table, parsed.key, parsed.indices)
        problem = overlap_problem(parsed, seen)
        if problem is not None:
            raise reader.error(key, problem, "each value once, by one key path")
        seen[place] = text
        return parsed

    def sum_path(group: str, text: str) -> KeyPath:
        return read_key_path(reader, job, tables, defaults, f"{group}.{_quoted(text)}", text)

    for text, entry in keys.variables.items():
        parsed = key_path("variables", text)
        variables.append(
            _read_variable(reader, f"variables.{_quoted(text)}", parsed, entry, sum_path)
        )
    totals: dict[tuple, float] = {}
    for variable in variables:
        for target, total in variable.fixed_sum:
            place = (target.table, target.key, target.indices)
            key = f"variables.{_quoted(variable.path.text)}.fixed_sum.{_quoted(target.text)}"
            problem = overlap_problem(target, seen)
            if problem is not None:
                raise reader.error(key, problem, "a key path no variable or coarse setting names")
            if totals.setdefault(place, total) != total:
                raise reader.error(
                    key,
                    f"is {shown(total)}, another total than {shown(totals[place])}",
                    "one total per key path",
                )
    for variable in variables:  # a coarse setting may not name a fixed sum either
        seen.update({(p.table, p.key, p.indices): p.text for p, _ in variable.fixed_sum})
    coarse = []
    if keys.coarse is not None:
        if not isinstance(keys.coarse, dict):
            raise reader.error(
                "coarse",
                f"is {type_name(keys.coarse)}",
                "a table of key path = value, e.g. { precision_cm = 1.875 }",
            )
        coarse = [(key_path("coarse", text), value) for text, value in keys.coarse.items()]
    objectives = []
    for verb, sense in (("maximise", -1), ("minimise", 1)):
        value = getattr(keys, verb)
        if value is not None:
            objectives += [Objective(c, sense) for c in _columns(reader, verb, value)]
    if not objectives:
        raise reader.error(
            "maximise",
            "missing key (and no minimise)",
            "maximise = COLUMN or minimise = COLUMN (a list: a Pareto set)",
        )
    repeated = [
        c for c in {o.column for o in objectives} if sum(o.column == c for o in objectives) > 1
    ]
    if repeated:
        raise reader.error("minimise", f"repeats the objective {repeated[0]}", "each column once")
    if keys.algorithm == "de" and len(objectives) > 1:
        raise reader.error(
            "algorithm",
            f'is "de" with {len(objectives)} objectives',
            '"nsga2" or "auto" for several objectives',
        )
    constraints = keys.constraints
    if not isinstance(constraints, list | tuple):
        raise reader.error(
            "constraints", f"is {type_name(constraints)}", 'a list of "COLUMN OP NUMBER"'
        )
    parsed_constraints = tuple(
        parse_constraint(reader, k, text) for k, text in enumerate(constraints, start=1)
    )
    output = keys.output or f"{path.stem}-optimise-{number}.csv"
    pareto_output = keys.pareto_output or f"{Path(output).with_suffix('')}-optimum.csv"
    if pareto_output == output:
        raise reader.error(
            "pareto_output", f"is {shown(pareto_output)}, the same as output", "another file"
        )
    optimisation = Optimisation(
        preset_path=path,
        name=name,
        job=job,
        document=preset.raw,
        tables=tables,
        defaults=defaults,
        variables=tuple(variables),
        objectives=tuple(objectives),
        constraints=parsed_constraints,
        coarse=tuple(coarse),
        algorithm=keys.algorithm,
        population=keys.population,
        budget=keys.budget,
        seed=keys.seed,
        output=output,
        pareto_output=pareto_output,
        plot=keys.plot,
        source=table,
    )
    check_columns(optimisation)
    _check_corners(optimisation)
    return optimisation


def _check_corners(optimisation: Optimisation) -> None:
    """Refuse, before anything runs, variables or coarse settings no design could take:
    the designs at the variables' lower ends, upper ends and middles are parsed like
    preset jobs (with the coarse settings, and without: the certified re-run)."""
    for coarse in (True, False):
        sweep = optimisation.sweep(coarse)
        for number, values in enumerate(corner_designs(optimisation), start=1):
            make_point(sweep, number, optimisation.point_values(values, coarse))


def corner_designs(optimisation: Optimisation) -> list[tuple[Any, ...]]:
    """The designs at the variables' lower ends, upper ends and middles."""
    variables = optimisation.variables
    corners = [tuple(v.decode(v.bounds[k]) for v in variables) for k in (0, 1)]
    corners.append(tuple(v.decode(sum(v.bounds) / 2) for v in variables))
    return corners


def parse_optimisations(preset: Preset) -> tuple[Optimisation, ...]:
    """The preset's ``[[optimise]]`` tables (or one ``[optimise]`` table), checked."""
    value = preset.raw.get(TABLE)
    if value is None:
        return ()
    if isinstance(value, list):
        return tuple(
            parse_optimise_table(preset, table, f"{TABLE}[{k}]", k)
            for k, table in enumerate(value, start=1)
        )
    return (parse_optimise_table(preset, value, TABLE, 1),)


def check_columns(optimisation: Optimisation) -> None:
    """Refuse objectives or constraints naming no column of the job's figures, where its
    kind declares them without running (``figure_names``)."""
    names_of = getattr(JOB_KINDS[optimisation.job.kind], "figure_names", None)
    if names_of is None:
        return
    names = tuple(names_of(optimisation.job))
    for column in optimisation.columns:
        if column not in names:
            raise PresetError(
                optimisation.preset_path,
                optimisation.name,
                f"names the column {column!r}, not one of the job's",
                "one of " + ", ".join(names),
            )
