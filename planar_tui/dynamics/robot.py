"""The serial robot model (paper A, section 2): n links, revolute joints, a vertical plane."""

from __future__ import annotations

from dataclasses import dataclass

from planar_tui.jobkind import RobotKind
from planar_tui.schema import number, numbers, setting, string

#: Bounds of every length, mass and inertia (SI), and the largest gravity: the dynamics
#: multiply up to six such values, which then stay within double precision's range
#: (1e-308 … 1e308); outside it a model of a robot is NaN or infinite, not a result.
SCALE_MIN = 1e-50
SCALE_MAX = 1e50


def _physical(length: str | None = None):
    return numbers(positive=True, length=length, minimum=SCALE_MIN, maximum=SCALE_MAX)


def slender_rod_inertia_kgm2(mass_kg: float, length_m: float) -> float:
    """Moment of inertia of a thin uniform rod about its centre, ``m l² / 12``."""
    return mass_kg * length_m * length_m / 12.0


@dataclass(frozen=True)
class SerialRobot:
    """An n-link planar serial revolute robot (nR-PSM), the ``[robot]`` table.

    Link ``i`` has length ``lengths_m[i]``, mass ``masses_kg[i]`` and moment of inertia
    ``inertias_kgm2[i]`` about its centre of mass (at mid-link), perpendicular to the plane.
    Gravity ``gravity_m_s2`` points along −y (0 for a horizontal plane).
    """

    lengths_m: tuple[float, ...] = setting(
        _physical(),
        type_doc="n numbers in [1e-50, 1e50]",
        doc="link lengths (n ≥ 1 sets the number of links)",
    )
    masses_kg: tuple[float, ...] = setting(
        _physical("lengths_m"),
        type_doc="n numbers in [1e-50, 1e50]",
        doc="link masses",
    )
    inertias_kgm2: tuple[float, ...] = setting(
        _physical("lengths_m"),
        default=(),
        default_doc="`m l²/12`",
        type_doc="n numbers in [1e-50, 1e50]",
        doc="moments of inertia about each link's centre of mass",
    )
    gravity_m_s2: float = setting(
        number(minimum=0.0, maximum=SCALE_MAX),
        default=9.81,
        type_doc="number in [0, 1e50]",
        doc="gravity, pointing along −y",
    )
    name: str = setting(string(), default="", type_doc="string", doc="a label")

    def __post_init__(self):
        if not self.inertias_kgm2:
            rods = tuple(map(slender_rod_inertia_kgm2, self.masses_kg, self.lengths_m))
            object.__setattr__(self, "inertias_kgm2", rods)
        if not (len(self.lengths_m) == len(self.masses_kg) == len(self.inertias_kgm2) >= 1):
            raise ValueError("lengths, masses and inertias need one value per link")

    @property
    def n_links(self) -> int:
        """Number of links (and joints) n."""
        return len(self.lengths_m)

    @property
    def label(self) -> str:
        """The robot's name, or ``nR`` when it has none."""
        return self.name or f"{self.n_links}R"

    def arrays(self):
        """``(lengths_m, masses_kg, inertias_kgm2)`` as contiguous float64 NumPy arrays."""
        import numpy as np

        return (
            np.array(self.lengths_m, dtype=np.float64),
            np.array(self.masses_kg, dtype=np.float64),
            np.array(self.inertias_kgm2, dtype=np.float64),
        )


ROBOT_KIND = RobotKind(
    "robot",
    SerialRobot,
    example="[robot]\nlengths_m = [0.3, 0.2]\nmasses_kg = [1.0, 0.8]\n",
    app_default={
        "name": "2R, paper A Table 3",
        "gravity_m_s2": 9.81,
        "lengths_m": [0.303, 0.214],
        "masses_kg": [1.126, 0.796],
        "inertias_kgm2": [0.129, 0.045],
    },
)


def rk4_step_seconds(n_links: int) -> float:
    """Rough time of one RK4 step (four forward dynamics) on this project's machine:
    0.5 µs per link, plus 1 ns per link cubed for the NOC mass matrix + ``LDLᵀ`` of chains
    shorter than ``kernels.aba_planar.ABA_MIN_LINKS`` (7; longer ones take the O(n)
    articulated-body recursion). Measured: 4 µs at n = 6, 0.16 ms at n = 400, 0.4 ms at
    n = 1000."""
    return 5e-7 * n_links + (1e-9 * n_links**3 if n_links < 7 else 0.0)
