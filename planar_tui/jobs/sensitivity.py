"""The ``[sensitivity]`` job: Sobol'/eFAST sensitivity of the joint torques (paper A, §3)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.jobs.base import JobKind
from planar_tui.model import SerialRobot
from planar_tui.presets import TableReader

METHODS = ("sobol", "efast")
PERCENT_OF = ("ST", "S1")
#: eFAST needs N > 4 M² with M = 4 (SALib ``fast_sampler``).
EFAST_MIN_SAMPLES = 65


@dataclass(frozen=True)
class SensitivitySpec:
    """Settings of one sensitivity job (SI units; see ``docs/sensitivity.md``).

    ``posture`` is the solved :class:`~planar_tui.sensitivity.postures.Posture`;
    ``posture_request`` what the preset asked for (``"singular"``, ``"isotropic"`` or
    angles in degrees). ``efast_samples`` None means "match the Sobol' cost".
    """

    posture_request: Any
    posture: Any
    speeds_rad_s: tuple[float, ...]
    alpha_rad_s2: float
    tolerance_length_mm: float
    tolerance_mass_g: float
    tolerance_inertia_kgm2: float | None
    methods: tuple[str, ...]
    samples: int
    efast_samples: int | None
    seed: int
    percent_of: str
    isotropy_tolerance: float

    @property
    def tolerance_length_m(self) -> float:
        """Half-width of every length's uniform range, in metres."""
        return self.tolerance_length_mm * 1e-3

    @property
    def tolerance_mass_kg(self) -> float:
        """Half-width of every mass's uniform range, in kilograms."""
        return self.tolerance_mass_g * 1e-3


def _is_power_of_two(value: int) -> bool:
    return value >= 1 and value & (value - 1) == 0


def check_samples(error, methods, samples: int, efast_samples: int | None) -> None:
    """Sobol' N must be a power of two >= 8; eFAST N must exceed 4 M² = 64."""
    if "sobol" in methods and not (_is_power_of_two(samples) and samples >= 8):
        raise error("samples", f"is {samples}, not a power of two >= 8", "8, 16, ... 8192, ...")
    if "efast" in methods and efast_samples is not None and efast_samples < EFAST_MIN_SAMPLES:
        raise error("efast_samples", f"is {efast_samples}", "an integer > 4 M² = 64 (M = 4)")


def _posture(reader: TableReader, robot: SerialRobot, isotropy_tolerance: float):
    from planar_tui.sensitivity.postures import (
        NoIsotropicPosture,
        explicit_posture,
        isotropic_posture,
        singular_posture,
    )

    value = reader.raw("posture", "singular")
    n = robot.n_links
    if isinstance(value, list):
        angles = reader.numbers("posture", length=n)
        return angles, explicit_posture(angles, robot.lengths_m)
    request = reader.string("posture", "singular", choices=("singular", "isotropic"))
    if request == "singular":
        return request, singular_posture(n)
    try:
        return request, isotropic_posture(robot.lengths_m, isotropy_tolerance)
    except NoIsotropicPosture as error:
        raise reader.error(
            "posture", f"robot has {error}", "a robot with an isotropic posture"
        ) from None


def parse_sensitivity(reader: TableReader, robot: SerialRobot) -> SensitivitySpec:
    """Validate a ``[sensitivity]`` table against its robot."""
    speed = reader.raw("speed_rad_s", 1.0)
    speeds = (
        reader.numbers("speed_rad_s")
        if isinstance(speed, list)
        else (reader.number("speed_rad_s", 1.0),)
    )
    tol_l_mm = reader.number("tolerance_length_mm", 1.0, positive=True)
    tol_m_g = reader.number("tolerance_mass_g", 1.0, positive=True)
    for name, tolerance, nominal, unit in (
        ("tolerance_length_mm", tol_l_mm, min(robot.lengths_m) * 1e3, "mm"),
        ("tolerance_mass_g", tol_m_g, min(robot.masses_kg) * 1e3, "g"),
    ):
        if tolerance >= nominal:
            raise reader.error(
                name,
                f"is {tolerance:g} {unit}, not below the smallest nominal value "
                f"{nominal:g} {unit} (samples would be non-physical)",
                f"0 < tolerance < {nominal:g}",
            )
    tol_i = None
    if reader.boolean("vary_inertias", False):
        tol_i = reader.number("tolerance_inertia_kgm2", positive=True)
        if tol_i >= min(robot.inertias_kgm2):
            raise reader.error(
                "tolerance_inertia_kgm2",
                f"is {tol_i:g}, not below the smallest inertia",
                f"0 < tolerance < {min(robot.inertias_kgm2):g}",
            )
    elif reader.has("tolerance_inertia_kgm2"):
        raise reader.error(
            "tolerance_inertia_kgm2", "is set but vary_inertias is false", "vary_inertias = true"
        )
    methods_raw = reader.raw("methods", ["sobol", "efast"])
    if not isinstance(methods_raw, list) or not methods_raw:
        raise reader.error("methods", f"is {methods_raw!r}", 'a list of "sobol", "efast"')
    for method in methods_raw:
        if method not in METHODS:
            raise reader.error("methods", f"has {method!r}", 'a list of "sobol", "efast"')
    methods = tuple(dict.fromkeys(methods_raw))
    samples = reader.integer("samples", 8192, minimum=1)
    efast_samples = (
        reader.integer("efast_samples", None, minimum=1) if reader.has("efast_samples") else None
    )
    check_samples(reader.error, methods, samples, efast_samples)
    isotropy_tolerance = reader.number("isotropy_tolerance", 0.01, positive=True)
    request, posture = _posture(reader, robot, isotropy_tolerance)
    return SensitivitySpec(
        posture_request=request,
        posture=posture,
        speeds_rad_s=speeds,
        alpha_rad_s2=reader.number("alpha_rad_s2", 0.0),
        tolerance_length_mm=tol_l_mm,
        tolerance_mass_g=tol_m_g,
        tolerance_inertia_kgm2=tol_i,
        methods=methods,
        samples=samples,
        efast_samples=efast_samples,
        seed=reader.integer("seed", 42, minimum=1),
        percent_of=reader.string("percent_of", "ST", choices=PERCENT_OF),
        isotropy_tolerance=isotropy_tolerance,
    )


def with_overrides(spec: SensitivitySpec, *, methods=None, samples=None, seed=None):
    """The spec with command-line overrides (``--method``, ``--samples``, ``--seed``)."""

    def error(name, problem, expected):
        return PresetError("command line", f"--{name.replace('_', '-')}", problem, expected)

    changes: dict[str, Any] = {}
    if methods:
        for method in methods:
            if method not in METHODS:
                raise error("method", f"is {method!r}", "sobol or efast")
        changes["methods"] = tuple(dict.fromkeys(methods))
    if samples is not None:
        changes["samples"] = samples
    if seed is not None:
        if seed < 1:
            raise error("seed", f"is {seed}", "an integer >= 1 (SALib treats 0 as no seed)")
        changes["seed"] = seed
    updated = dataclasses.replace(spec, **changes)
    check_samples(error, updated.methods, updated.samples, updated.efast_samples)
    return updated


def dump_sensitivity(spec: SensitivitySpec) -> dict:
    """The settings as a ``[sensitivity]`` table."""
    request = spec.posture_request
    table = {
        "posture": list(request) if isinstance(request, tuple) else request,
        "speed_rad_s": spec.speeds_rad_s[0]
        if len(spec.speeds_rad_s) == 1
        else list(spec.speeds_rad_s),
        "alpha_rad_s2": spec.alpha_rad_s2,
        "tolerance_length_mm": spec.tolerance_length_mm,
        "tolerance_mass_g": spec.tolerance_mass_g,
        "methods": list(spec.methods),
        "samples": spec.samples,
        "seed": spec.seed,
        "percent_of": spec.percent_of,
        "isotropy_tolerance": spec.isotropy_tolerance,
    }
    if spec.efast_samples is not None:
        table["efast_samples"] = spec.efast_samples
    if spec.tolerance_inertia_kgm2 is not None:
        table |= {"vary_inertias": True, "tolerance_inertia_kgm2": spec.tolerance_inertia_kgm2}
    return table


SENSITIVITY = JobKind(
    name="sensitivity",
    robot_kind="robot",
    keys=(
        "posture",
        "speed_rad_s",
        "alpha_rad_s2",
        "tolerance_length_mm",
        "tolerance_mass_g",
        "vary_inertias",
        "tolerance_inertia_kgm2",
        "methods",
        "samples",
        "efast_samples",
        "seed",
        "percent_of",
        "isotropy_tolerance",
    ),
    parse=parse_sensitivity,
    dump=dump_sensitivity,
    runner="planar_tui.sensitivity.runner:run_sensitivity",
    summary="Sobol'/eFAST sensitivity of the joint torques to lengths and masses",
    render="planar_tui.sensitivity.render:show_sensitivity",
)
