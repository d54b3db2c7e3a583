"""Uncertainty quantification shared by the sensitivity and motion job kinds.

One home for what both kinds read, check and override about their sampling: the methods
(:data:`METHODS`, one entry each: a new method is one :class:`Method` line), the reader
of a ``methods`` key, the sample-count rules of each method's design, the seed's range,
the tolerance keys and their check against the robot's nominal values, and the
command-line options that override them (``--method``, ``--samples``, ``--seed``).

Every input ``x_i`` is uniform on ``[nominal_i − δ, nominal_i + δ]`` (δ the key's
tolerance); a design of N base samples over D inputs has :func:`design_rows` rows.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol

from planar_tui.errors import PresetError
from planar_tui.jobkind import Option
from planar_tui.schema import TableReader, integer, number, setting, shown

#: Largest seed: eFAST's bootstrap draws with ``np.random.RandomState(seed)``, which takes
#: 32-bit seeds (SALib's Sobol' sampling would take any).
SEED_MAX = 2**32 - 1
#: eFAST's interference factor M (paper A, Saltelli et al. 1999).
EFAST_HARMONICS = 4
#: eFAST needs N > 4 M² (SALib ``fast_sampler``).
EFAST_MIN_SAMPLES = 4 * EFAST_HARMONICS**2 + 1


def _power_of_two_from_8(samples: int) -> str | None:
    """Sobol' (Saltelli's scheme on a Sobol' sequence): N a power of two ≥ 8."""
    return None if samples >= 8 and samples & (samples - 1) == 0 else "not a power of two >= 8"


def _above_4m2(samples: int) -> str | None:
    """eFAST: N > 4 M² = 64 (M = 4)."""
    return None if samples >= EFAST_MIN_SAMPLES else "not above 4 M² = 64"


def _at_least_16(samples: int) -> str | None:
    """PCE: N ≥ 16 model runs (its LOO error then says whether they were enough)."""
    return None if samples >= 16 else "below 16"


@dataclass(frozen=True)
class Method:
    """One sampling method: ``rows(D, N)`` its design's rows (robots or model runs) for D
    inputs and base size N; ``samples_problem(N)`` what is wrong with N (``None`` when
    fine), ``samples_expected`` the allowed values; ``indices`` whether it computes
    sensitivity indices (else it only samples, as Monte Carlo)."""

    name: str
    title: str
    rows: Callable[[int, int], int]
    samples_problem: Callable[[int], str | None]
    samples_expected: str
    indices: bool = True


#: Every method, by preset name.
METHODS: dict[str, Method] = {
    "montecarlo": Method(
        "montecarlo", "Monte Carlo", lambda d, n: n, lambda n: None, "an integer >= 1", False
    ),
    "sobol": Method(
        "sobol", "Sobol'", lambda d, n: n * (d + 2), _power_of_two_from_8, "8, 16, 32, 64, ..."
    ),
    "efast": Method(
        "efast", "eFAST", lambda d, n: n * d, _above_4m2, "an integer > 4 M² = 64 (M = 4)"
    ),
    "pce": Method("pce", "PCE", lambda d, n: n, _at_least_16, "an integer >= 16"),
}


def design_rows(method: str, num_vars: int, samples: int) -> int:
    """Rows of a design: N (Monte Carlo, PCE), N (D + 2) (Sobol', no second order), N D
    (eFAST)."""
    return METHODS[method].rows(num_vars, samples)


def choices_text(allowed: Iterable[str]) -> str:
    """``one of "sobol", "efast" or a non-empty list of them``."""
    return "one of " + ", ".join(f'"{a}"' for a in allowed) + " or a non-empty list of them"


def read_choices(allowed: tuple[str, ...]) -> Callable[..., tuple[str, ...]]:
    """A setting reader of one of ``allowed`` or a non-empty list of them (a single string
    is a one-item list), duplicates dropped, in the given order."""
    expected = choices_text(allowed)

    def read(
        reader: TableReader, name: str, default: tuple[str, ...], robot: object, values: object
    ) -> tuple[str, ...]:
        chosen = reader.raw(name, list(default))
        if isinstance(chosen, str):
            chosen = [chosen]
        if not isinstance(chosen, list) or not chosen:
            raise reader.error(name, f"is {shown(chosen)}", expected)
        for item in chosen:
            if item not in allowed:
                raise reader.error(name, f"has {shown(item)}", expected)
        return tuple(dict.fromkeys(chosen))

    return read


def methods_setting(allowed: tuple[str, ...], default: tuple[str, ...], **key: Any) -> Any:
    """The ``methods`` key: a subset of ``allowed`` (:data:`METHODS` names)."""
    names = ", ".join(f'`"{a}"`' for a in allowed)
    return setting(
        read_choices(allowed), default=default, type_doc=f"{names} or a list of them", **key
    )


def seed_setting(doc: str) -> Any:
    """The ``seed`` key: an integer in [1, :data:`SEED_MAX`] (SALib treats 0 as no seed)."""
    return setting(
        integer(minimum=1, maximum=SEED_MAX),
        default=42,
        type_doc="integer in [1, 2³² − 1]",
        doc=doc,
    )


def tolerance_setting(unit: str, doc: str) -> Any:
    """A tolerance key (``mm`` of every length, ``g`` of every mass): the half-width δ of
    the uniform range about each nominal value."""
    return setting(
        number(positive=True),
        default=1.0,
        type_doc=f"0 < number < smallest {'length' if unit == 'mm' else 'mass'}",
        doc=doc,
    )


class Robot(Protocol):
    """What the tolerance checks read of a serial robot."""

    @property
    def lengths_m(self) -> tuple[float, ...]: ...
    @property
    def masses_kg(self) -> tuple[float, ...]: ...
    @property
    def inertias_kgm2(self) -> tuple[float, ...]: ...


def check_tolerances(values: Mapping[str, Any], reader: TableReader, robot: Robot) -> None:
    """Every tolerance below the smallest nominal value it spreads (else samples would be
    non-physical): ``tolerance_length_mm``, ``tolerance_mass_g`` and, when set,
    ``tolerance_inertia_kgm2``."""
    for name, nominal, unit in (
        ("tolerance_length_mm", min(robot.lengths_m) * 1e3, "mm"),
        ("tolerance_mass_g", min(robot.masses_kg) * 1e3, "g"),
        ("tolerance_inertia_kgm2", min(robot.inertias_kgm2), "kg m²"),
    ):
        value = values.get(name)
        if value is not None and value >= nominal:
            raise reader.error(
                name,
                f"is {value:g} {unit}, not below the smallest nominal value {nominal:g} {unit}",
                f"0 < tolerance < {nominal:g}",
            )


ErrorFactory = Callable[[str, str, str], PresetError]
#: The sample count of each method a job runs: method -> (its key, N); N ``None`` when
#: derived (eFAST matching the Sobol' cost), not checked.
SampleSizes = Mapping[str, tuple[str, int | None]]


def check_samples(error: ErrorFactory, methods: Collection[str], sizes: SampleSizes) -> None:
    """Each method's sample count within its rule (:attr:`Method.samples_problem`); a bad
    one is ``error(key, "is N, PROBLEM (METHOD)", expected)``."""
    for name in methods:
        key, samples = sizes.get(name, ("samples", None))
        method = METHODS[name]
        problem = None if samples is None else method.samples_problem(samples)
        if problem is not None:
            raise error(key, f"is {samples}, {problem} ({method.title})", method.samples_expected)


def sampling_options(methods: tuple[str, ...], samples_help: str) -> tuple[Option, ...]:
    """The command-line options that override the sampling keys (``--method``,
    ``--samples``, ``--seed``), read and checked as the keys are
    (:func:`planar_tui.overrides.override_job`)."""
    names = ", ".join(methods[:-1]) + f" or {methods[-1]}"
    return (
        Option(
            "--method",
            "methods",
            f"{names} (repeatable); overrides `methods`.",
            many=True,
            short="-m",
        ),
        Option("--samples", "samples", f"{samples_help}; overrides `samples`.", int),
        Option("--seed", "seed", "Seed >= 1; overrides `seed`.", int),
    )


def pce_samples_setting(what: str) -> Any:
    """The ``pce_samples`` key: the PCE's model runs (or robots), ``None`` for
    :func:`~planar_tui.sensitivity.pce.default_pce_samples` of the job's D inputs."""
    return setting(
        integer(minimum=1),
        default=None,
        default_doc="`max(128, 64 D)`",
        type_doc="integer ≥ 16",
        doc=f"PCE {what} (768 for D = 12 inputs)",
    )


def pce_max_loo_setting(doc: str) -> Any:
    """The ``pce_max_loo_error`` key: the largest accepted PCE leave-one-out error."""
    return setting(number(positive=True), default=0.01, type_doc="number > 0", doc=doc)


def allow_failed_runs_setting(doc: str) -> Any:
    """The ``allow_failed_runs`` key: the fraction of runs a PCE may drop."""
    return setting(
        number(minimum=0.0, maximum=1.0), default=0.0, type_doc="0 ≤ number ≤ 1", doc=doc
    )
