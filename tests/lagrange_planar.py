"""An independent reference for the parallel robots' inverse dynamics: Lagrange multipliers
in full coordinates, solved with numpy (no code of the NOC kernels).

Every body ``b`` has the coordinates ``(x_b, y_b, a_b)`` of its centre of mass and angle,
mass ``m_b`` and inertia ``I_b``; a pin joins the point ``c_i + R(a_i) d_i`` of body ``i``
to ``c_j + R(a_j) d_j`` of body ``j`` (or a fixed point). With the constraint Jacobian
``G`` and ``G q'' = gamma`` (``gamma`` the pins' ``a'^2 R d`` terms), the motion with the
platform's coordinates prescribed and actuator torques ``tau`` on the proximal bodies
(about +z, reacting on the ground) solves the square KKT system

    M q'' - G^T lambda - B tau = Q_gravity,   G q'' = gamma,   P q'' = X''.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def rotate(angle: float, point) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * point[0] - s * point[1], s * point[0] + c * point[1]])


@dataclass
class Pin:
    body: int
    local: tuple[float, float]
    other: int | None  # None: the ground
    other_local: tuple[float, float]  # the ground point when other is None


@dataclass
class System:
    masses: np.ndarray  # (n,)
    inertias: np.ndarray  # (n,)
    pins: list[Pin]
    actuated: list[int]  # the bodies driven by a base motor
    prescribed: list[int]  # coordinate indices prescribed (the platform's)
    gravity: float
    #: Coordinates nothing constrains (a point platform's angle), held at rate zero.
    still: tuple[int, ...] = ()

    def mass_matrix(self) -> np.ndarray:
        diag = np.column_stack([self.masses, self.masses, self.inertias]).ravel()
        return np.diag(diag)

    def constraints(self, q, qd):
        """``(G, gamma)``: the pins' Jacobian and ``G q'' = gamma``."""
        n = len(self.masses)
        rows = []
        gamma = []
        for pin in self.pins:
            g = np.zeros((2, 3 * n))
            rhs = np.zeros(2)
            for body, local, sign in (
                (pin.body, pin.local, 1.0),
                (pin.other, pin.other_local, -1.0),
            ):
                if body is None:
                    continue
                a, ad = q[3 * body + 2], qd[3 * body + 2]
                rd = rotate(a, local)
                g[:, 3 * body : 3 * body + 2] += sign * np.eye(2)
                g[:, 3 * body + 2] += sign * np.array([-rd[1], rd[0]])
                rhs += sign * ad * ad * rd
            rows.append(g)
            gamma.append(rhs)
        return np.vstack(rows), np.concatenate(gamma)

    def residual(self, q) -> float:
        worst = 0.0
        for pin in self.pins:
            p = q[3 * pin.body : 3 * pin.body + 2] + rotate(q[3 * pin.body + 2], pin.local)
            if pin.other is None:
                o = np.asarray(pin.other_local, dtype=float)
            else:
                o = q[3 * pin.other : 3 * pin.other + 2] + rotate(
                    q[3 * pin.other + 2], pin.other_local
                )
            worst = max(worst, float(np.abs(p - o).max()))
        return worst

    def selector(self) -> np.ndarray:
        p = np.zeros((len(self.prescribed), 3 * len(self.masses)))
        for row, index in enumerate(self.prescribed):
            p[row, index] = 1.0
        return p

    def velocities(self, q, platform_rate) -> np.ndarray:
        g, _ = self.constraints(q, np.zeros_like(q))
        p = self.selector()
        still = np.zeros((len(self.still), len(q)))
        still[range(len(self.still)), list(self.still)] = 1.0
        lhs = np.vstack([g, p, still])
        rhs = np.concatenate([np.zeros(len(g)), platform_rate, np.zeros(len(self.still))])
        return np.linalg.solve(lhs, rhs)

    def torques(self, q, qd, platform_acceleration) -> tuple[np.ndarray, np.ndarray]:
        """``(tau, q'')`` of the KKT system (module docstring)."""
        n = len(self.masses)
        g, gamma = self.constraints(q, qd)
        p = self.selector()
        b = np.zeros((3 * n, len(self.actuated)))
        for column, body in enumerate(self.actuated):
            b[3 * body + 2, column] = 1.0
        gravity = np.zeros(3 * n)
        gravity[1::3] = -self.masses * self.gravity
        m, c, k = 3 * n, len(g), len(self.actuated)
        lhs = np.zeros((m + c + len(p), m + c + k))
        lhs[:m, :m] = self.mass_matrix()
        lhs[:m, m : m + c] = -g.T
        lhs[:m, m + c :] = -b
        lhs[m : m + c, :m] = g
        lhs[m + c :, :m] = p
        rhs = np.concatenate([gravity, gamma, platform_acceleration])
        solution = np.linalg.solve(lhs, rhs)
        return solution[m + c :], solution[:m]

    def energy(self, q, qd) -> float:
        kinetic = 0.5 * qd @ self.mass_matrix() @ qd
        return float(kinetic + self.gravity * self.masses @ q[1::3])


def elbow_point(a, c, l1: float, l2: float, sign: int) -> np.ndarray:
    """The elbow ``B`` of a leg from ``A`` to ``C`` by two circles' intersection, on the
    left of ``A -> C`` for ``sign = 1``."""
    a, c = np.asarray(a, dtype=float), np.asarray(c, dtype=float)
    v = c - a
    rho = float(np.hypot(*v))
    along = (rho * rho + l1 * l1 - l2 * l2) / (2.0 * rho)
    height = math.sqrt(l1 * l1 - along * along)
    u = v / rho
    return a + along * u + sign * height * np.array([-u[1], u[0]])


@dataclass
class Leg:
    base: tuple[float, float]
    point: tuple[float, float]  # on the platform, platform frame
    l1: float
    l2: float
    sign: int


def rr_system(legs, link_masses, link_inertias, platform, gravity, dimension=3):
    """Bodies: per leg proximal then distal, last the platform (``platform`` = mass,
    inertia); pins: base, elbow, platform point; the platform's first ``dimension``
    coordinates prescribed (2: a point platform, whose angle is free and untouched)."""
    masses, inertias, pins = [], [], []
    n = 2 * len(legs)
    for i, leg in enumerate(legs):
        prox, dist = 2 * i, 2 * i + 1
        masses += [link_masses[0], link_masses[1]]
        inertias += [link_inertias[0], link_inertias[1]]
        pins.append(Pin(prox, (-leg.l1 / 2, 0.0), None, leg.base))
        pins.append(Pin(dist, (-leg.l2 / 2, 0.0), prox, (leg.l1 / 2, 0.0)))
        pins.append(Pin(dist, (leg.l2 / 2, 0.0), n, leg.point))
    masses.append(platform[0])
    inertias.append(platform[1])
    return System(
        np.array(masses),
        np.array(inertias),
        pins,
        [2 * i for i in range(len(legs))],
        [3 * n + k for k in range(dimension)],
        gravity,
        tuple(range(3 * n + dimension, 3 * n + 3)),
    )


def rr_coordinates(legs, pose) -> np.ndarray:
    """Full coordinates at the platform pose ``(x, y, phi)`` in each leg's mode."""
    x, y, phi = pose
    q = []
    for leg in legs:
        a = np.asarray(leg.base, dtype=float)
        c = np.array([x, y]) + rotate(phi, leg.point)
        b = elbow_point(a, c, leg.l1, leg.l2, leg.sign)
        theta = math.atan2(b[1] - a[1], b[0] - a[0])
        psi = math.atan2(c[1] - b[1], c[0] - b[0])
        q += [*((a + b) / 2), theta, *((b + c) / 2), psi]
    return np.array([*q, x, y, phi])
