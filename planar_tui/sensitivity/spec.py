"""The ``[sensitivity]`` job's settings: its preset keys, their readers and cross-key
checks, the sample sizes per method and the resource estimate that refuses a job too large
to run."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui import uq
from planar_tui.dynamics.robot import SerialRobot
from planar_tui.limits import memory_problem, time_problem
from planar_tui.schema import (
    TableReader,
    boolean,
    integer,
    number,
    per_link,
    plot_setting,
    setting,
    shown,
    string,
)
from planar_tui.sensitivity.path import PathSpec

METHODS = ("sobol", "efast", "pce")
#: The methods a job runs unless its preset says otherwise (paper A's two).
DEFAULT_METHODS = ("sobol", "efast")
PERCENT_OF = ("ST", "S1")
#: Rough cost of one model run (an inverse dynamics, batched): 0.3 µs + 20 ns per link.
MODEL_RUN_SECONDS = (3e-7, 2e-8)


def _read_speeds(reader: TableReader, name, default, robot, values) -> tuple[float, ...]:
    """One speed (a number) or a sweep (a list of numbers)."""
    if isinstance(reader.raw(name, 1.0), list):
        return reader.numbers(name)
    return (reader.number(name, 1.0),)


def _dump_speeds(speeds: tuple[float, ...]) -> Any:
    return speeds[0] if len(speeds) == 1 else list(speeds)


def _read_posture_request(reader: TableReader, name, default, robot, values) -> Any:
    """``"singular"``, ``"isotropic"`` or n joint angles in degrees."""
    if isinstance(reader.raw(name, default), list):
        return reader.numbers(name, length=robot.n_links)
    return reader.string(name, default, choices=("singular", "isotropic"))


per_link(_read_posture_request, "list")  # when it lists angles


#: Most path steps (each is one batched inverse dynamics of every design row).
MAX_PATH_STEPS = 1000


def _read_path(reader: TableReader, name, default, robot, values) -> PathSpec | None:
    """``{ to_deg = [n angles], duration_s = T, steps = K }`` or absent."""
    table = reader.raw(name, None)
    if table is None:
        return None
    expected = "{ to_deg = [n angles in degrees], duration_s = T > 0, steps = K >= 1 }"
    if not isinstance(table, dict):
        raise reader.error(name, f"is {shown(table)}", expected)
    inner = TableReader(reader.path, table, reader.key(name), ("to_deg", "duration_s", "steps"))
    return PathSpec(
        inner.numbers("to_deg", length=robot.n_links),
        inner.number("duration_s", positive=True),
        inner.integer("steps", minimum=1, maximum=MAX_PATH_STEPS),
    )


def _dump_path(path: PathSpec | None) -> Any:
    if path is None:
        return None
    return {"to_deg": list(path.to_deg), "duration_s": path.duration_s, "steps": path.steps}


@dataclass(frozen=True, kw_only=True)
class SensitivitySpec:
    """Settings of one sensitivity job (see ``docs/sensitivity.md``).

    ``posture_request`` is what the preset asked for (key ``posture``);
    :func:`~planar_tui.sensitivity.runner.prepare_sensitivity` solves it
    (:class:`~planar_tui.sensitivity.runner.SensitivityPrepared`).
    ``efast_samples`` None means "match the Sobol' cost".
    """

    posture_request: Any = setting(
        _read_posture_request,
        name="posture",
        default="singular",
        type_doc='`"singular"`, `"isotropic"` or n angles in degrees',
        doc="singular = all joint angles 0; isotropic = the posture minimising the Jacobian "
        "condition number (2R closed form; 3R with orientation row and characteristic "
        "length); a robot without one is refused, naming the minimum reached",
    )
    speeds_rad_s: tuple[float, ...] = setting(
        _read_speeds,
        name="speed_rad_s",
        default=(1.0,),
        default_doc="`1.0`",
        dump=_dump_speeds,
        type_doc="number or list",
        doc="the joint speed of every joint; a list is a sweep (Figs 5-6)",
    )
    alpha_rad_s2: float = setting(
        number(), default=0.0, type_doc="number", doc="the joint acceleration of every joint"
    )
    path: PathSpec | None = setting(
        _read_path,
        default=None,
        default_doc="(none)",
        dump=_dump_path,
        type_doc="`{ to_deg = [...], duration_s = T, steps = K }`",
        doc="torques along a quintic rest-to-rest path from the posture to `to_deg` instead "
        "of one state (speed and acceleration then come from the path): indices of the peak "
        "absolute torque and the RMS torque of each joint (the table) and of each torque at "
        "every step "
        f"(`-path.csv`); at most {MAX_PATH_STEPS} steps",
    )
    tolerance_length_mm: float = uq.tolerance_setting("mm", "half-width of every length's range")
    tolerance_mass_g: float = uq.tolerance_setting("g", "half-width of every mass's range")
    vary_inertias: bool = setting(
        boolean(), default=False, type_doc="boolean", doc="add the inertias as inputs"
    )
    tolerance_inertia_kgm2: float | None = setting(
        number(positive=True),
        default=None,
        default_doc="(needs `vary_inertias`)",
        type_doc="number > 0",
        doc="half-width of every inertia's range",
    )
    methods: tuple[str, ...] = uq.methods_setting(
        METHODS,
        default=DEFAULT_METHODS,
        default_doc='`["sobol", "efast"]`',
        doc="estimators (Sobol', eFAST: SALib samples, jitted analysis equal to SALib's; "
        "pce: polynomial chaos, indices from its coefficients)",
    )
    samples: int = setting(
        integer(minimum=1),
        default=8192,
        type_doc="power of two ≥ 8",
        doc="Sobol' base N (N·(D+2) model runs, D inputs)",
    )
    efast_samples: int | None = setting(
        integer(minimum=1),
        default=None,
        default_doc="same cost as Sobol'",
        type_doc="integer > 64",
        doc="eFAST N per input (M = 4)",
    )
    pce_samples: int | None = uq.pce_samples_setting("model runs")
    pce_max_loo_error: float = uq.pce_max_loo_setting(
        "largest accepted PCE leave-one-out error (relative); above it the job fails",
    )
    allow_failed_runs: float = uq.allow_failed_runs_setting(
        "fraction of model runs that may fail (non-finite torques) and be dropped from "
        "a PCE fit; any failure fails Sobol' and eFAST",
    )
    seed: int = uq.seed_setting("seed of sampling and bootstrap (SALib treats 0 as no seed)")
    percent_of: str = setting(
        string(choices=PERCENT_OF),
        default="ST",
        type_doc='`"ST"` or `"S1"`',
        doc="index normalised to the `percent` column (the paper's: total)",
    )
    isotropy_tolerance: float = setting(
        number(positive=True),
        default=0.01,
        type_doc="number > 0",
        doc='largest accepted `κ − 1` for `"isotropic"`',
    )
    plot: str | None = plot_setting()

    @staticmethod
    def check(values: dict[str, Any], reader: TableReader, robot: SerialRobot) -> dict[str, Any]:
        """Tolerances below the nominal values and sample sizes (cheap: the posture is
        solved by
        :func:`~planar_tui.sensitivity.runner.prepare_sensitivity`, before the job runs)."""
        tolerance_inertia = values["tolerance_inertia_kgm2"]
        if values["vary_inertias"] and tolerance_inertia is None:
            raise reader.error("tolerance_inertia_kgm2", "missing key", "a positive number")
        if not values["vary_inertias"] and tolerance_inertia is not None:
            raise reader.error(
                "tolerance_inertia_kgm2",
                "is set but vary_inertias is false",
                "vary_inertias = true",
            )
        uq.check_tolerances(values, reader, robot)
        spec = SensitivitySpec(**values)
        uq.check_samples(reader.error, spec.methods, spec.sample_keys())
        check_resources(reader.error, spec, robot)
        return values

    def sample_keys(self) -> uq.SampleSizes:
        """Each method's sample-count key and value (eFAST's ``None``: matching Sobol')."""
        return {
            "sobol": ("samples", self.samples),
            "efast": ("efast_samples", self.efast_samples),
            "pce": ("pce_samples", self.pce_samples),
        }

    @property
    def tolerance_length_m(self) -> float:
        """Half-width of every length's uniform range, in metres."""
        return self.tolerance_length_mm * 1e-3

    @property
    def tolerance_mass_kg(self) -> float:
        """Half-width of every mass's uniform range, in kilograms."""
        return self.tolerance_mass_g * 1e-3

    @property
    def inertia_tolerance_kgm2(self) -> float | None:
        """Half-width of every inertia's range when the inertias vary, else ``None``."""
        return self.tolerance_inertia_kgm2 if self.vary_inertias else None


def resource_estimate(spec: SensitivitySpec, robot: SerialRobot) -> tuple[float, float]:
    """Rough peak memory (bytes) and computing time (s) of a job: the unit designs (drawn
    and cached), one output matrix per method and speed, the Sobol' bootstrap's
    resample indices and counts (N × 1000 each), and one model run per design row and
    speed."""
    from planar_tui.sensitivity.estimators import NUM_RESAMPLES

    n = robot.n_links
    num_vars = (3 if spec.vary_inertias else 2) * n
    sizes = sample_sizes(spec, num_vars)
    rows = {method: uq.design_rows(method, num_vars, sizes[method]) for method in spec.methods}
    speeds = len(spec.speeds_rad_s)
    memory = sum(r * (2 * num_vars + speeds * n + 2 * n) * 8.0 for r in rows.values())
    if "sobol" in spec.methods:
        memory += 2.0 * spec.samples * NUM_RESAMPLES * 8
    per_run = MODEL_RUN_SECONDS[0] + MODEL_RUN_SECONDS[1] * n
    return memory, sum(rows.values()) * speeds * per_run


def check_resources(error: uq.ErrorFactory, spec: SensitivitySpec, robot: SerialRobot) -> None:
    """Refuse a job whose estimated memory or time exceeds :mod:`planar_tui.limits`."""
    memory, seconds = resource_estimate(spec, robot)
    problem = memory_problem(memory) or time_problem(seconds)
    if problem is not None:
        raise error(
            "samples",
            f"{robot.n_links} links, {len(spec.speeds_rad_s)} speed(s), samples = "
            f"{shown(spec.samples)}: {problem}",
            "fewer samples, links or speeds",
        )


def sample_sizes(spec: SensitivitySpec, num_vars: int) -> dict[str, int]:
    """N per method: the Sobol' base N, eFAST's (given, or matching the Sobol' cost), the
    PCE's model runs (given, or :func:`~planar_tui.sensitivity.pce.default_pce_samples`)."""
    from planar_tui.sensitivity.engine import default_efast_samples
    from planar_tui.sensitivity.pce import default_pce_samples

    efast = spec.efast_samples or default_efast_samples(spec.samples, num_vars)
    return {
        "sobol": spec.samples,
        "efast": efast,
        "pce": spec.pce_samples or default_pce_samples(num_vars),
    }
