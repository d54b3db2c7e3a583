"""The serial robot model (paper A, section 2): n links, revolute joints, a vertical plane."""

from __future__ import annotations

from dataclasses import dataclass, field

from planar_tui.presets import TableReader

SERIAL_ROBOT_KEYS = ("name", "gravity_m_s2", "lengths_m", "masses_kg", "inertias_kgm2")


def slender_rod_inertia_kgm2(mass_kg: float, length_m: float) -> float:
    """Moment of inertia of a thin uniform rod about its centre, ``m l² / 12``."""
    return mass_kg * length_m * length_m / 12.0


@dataclass(frozen=True)
class SerialRobot:
    """An n-link planar serial revolute robot (nR-PSM).

    Link ``i`` has length ``lengths_m[i]``, mass ``masses_kg[i]`` and moment of inertia
    ``inertias_kgm2[i]`` about its centre of mass (at mid-link), perpendicular to the plane.
    Gravity ``gravity_m_s2`` points along −y (0 for a horizontal plane).
    """

    lengths_m: tuple[float, ...]
    masses_kg: tuple[float, ...]
    inertias_kgm2: tuple[float, ...] = field(default=())
    gravity_m_s2: float = 9.81
    name: str = ""

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

    def arrays(self):
        """``(lengths_m, masses_kg, inertias_kgm2)`` as contiguous float64 NumPy arrays."""
        import numpy as np

        return (
            np.array(self.lengths_m, dtype=np.float64),
            np.array(self.masses_kg, dtype=np.float64),
            np.array(self.inertias_kgm2, dtype=np.float64),
        )

    def to_table(self) -> dict:
        """The robot as a preset ``[robot]`` table (inertias always written out)."""
        table: dict = {"name": self.name} if self.name else {}
        table |= {
            "gravity_m_s2": self.gravity_m_s2,
            "lengths_m": list(self.lengths_m),
            "masses_kg": list(self.masses_kg),
            "inertias_kgm2": list(self.inertias_kgm2),
        }
        return table


def parse_serial_robot(reader: TableReader) -> SerialRobot:
    """Build a :class:`SerialRobot` from a ``[robot]`` table."""
    lengths = reader.numbers("lengths_m", positive=True)
    n = len(lengths)
    masses = reader.numbers("masses_kg", positive=True, length=n)
    inertias = reader.numbers("inertias_kgm2", (), positive=True, length=n)
    return SerialRobot(
        lengths_m=lengths,
        masses_kg=masses,
        inertias_kgm2=inertias,
        gravity_m_s2=reader.number("gravity_m_s2", 9.81, minimum=0.0),
        name=reader.string("name", ""),
    )
