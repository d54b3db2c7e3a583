"""The serial robot model (paper A, section 2): n links, revolute joints, a vertical plane."""

from __future__ import annotations

from dataclasses import dataclass

from planar_tui.jobkind import RobotKind
from planar_tui.schema import number, numbers, setting, string


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
        numbers(positive=True),
        type_doc="n positive numbers",
        doc="link lengths (n ≥ 1 sets the number of links)",
    )
    masses_kg: tuple[float, ...] = setting(
        numbers(positive=True, length="lengths_m"),
        type_doc="n positive numbers",
        doc="link masses",
    )
    inertias_kgm2: tuple[float, ...] = setting(
        numbers(positive=True, length="lengths_m"),
        default=(),
        default_doc="`m l²/12`",
        type_doc="n positive numbers",
        doc="moments of inertia about each link's centre of mass",
    )
    gravity_m_s2: float = setting(
        number(minimum=0.0),
        default=9.81,
        type_doc="number ≥ 0",
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


ROBOT_KIND = RobotKind("robot", SerialRobot)
