r"""An independent Lagrange model of the 3-RRR and the five-bar, for the closed-chain
export's tests: full (body) coordinates, one rigid body per link and the end body, joints
as constraints, multipliers from the KKT system solved with numpy.

Body ``b`` has the coordinates :math:`z_b = (x_b, y_b, a_b)` of its centre of mass and its
angle, the mass matrix :math:`\mathrm{diag}(m_b, m_b, I_b)` and the gravity force
:math:`(0, -m_b g, 0)`. A pin between body ``j``'s point :math:`s_j` and body ``k``'s point
:math:`s_k` (in body frames, from the centres of mass) is :math:`\Phi = r_j + R_j s_j - r_k
- R_k s_k = 0` (``k`` the ground: a fixed point), its Jacobian rows :math:`(I, E R_j s_j)`
and :math:`-(I, E R_k s_k)` (:math:`E` the quarter turn), and :math:`\Phi_z \ddot z =
\gamma = R_j s_j \dot a_j^2 - R_k s_k \dot a_k^2`. The inverse dynamics solves
:math:`M \ddot z - Q = B\tau + \Phi_z^T\lambda` for the actuator torques :math:`\tau`
(about +z on each proximal link) and :math:`\lambda`.

The path: a quintic rest-to-rest pose :math:`p(t) = p_0 + s(t/T)(p_1 - p_0)`,
:math:`s(u) = 10u^3 - 15u^4 + 6u^5`; each leg's elbow by its own circle intersection.
Nothing here imports planar-tui.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

QUARTER_TURN = np.array([[0.0, -1.0], [1.0, 0.0]])


def rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


@dataclass(frozen=True)
class Machine:
    """A parallel robot in SI units: legs ``(A_i, l1, l2, elbow sign)``, end-body points
    ``q_i`` (from its centre of mass), masses and gravity; ``rotates``: the end body has
    an orientation coordinate (the 3-RRR's platform)."""

    bases: np.ndarray
    l1: float
    l2: float
    elbows: tuple[int, ...]
    points: np.ndarray
    m1: float
    i1: float
    m2: float
    i2: float
    m_end: float
    i_end: float
    gravity: float
    rotates: bool

    @property
    def n(self) -> int:
        return len(self.bases)

    # body order: proximal 1..n, distal 1..n, end body
    def pins(self):
        """``(body j, s_j, body k or None for the ground, s_k or the ground point)``."""
        n, h1, h2 = self.n, 0.5 * self.l1, 0.5 * self.l2
        for i in range(n):
            yield i, np.array([-h1, 0.0]), None, self.bases[i]
            yield i, np.array([h1, 0.0]), n + i, np.array([-h2, 0.0])
            yield n + i, np.array([h2, 0.0]), 2 * n, self.points[i]

    def mass_matrix(self) -> np.ndarray:
        n = self.n
        masses = [(self.m1, self.i1)] * n + [(self.m2, self.i2)] * n + [(self.m_end, self.i_end)]
        return np.diag([v for m, i in masses for v in (m, m, i)])

    def constraints(self, z: np.ndarray, zd: np.ndarray):
        """``(Phi, Phi_z, gamma)`` at ``z`` with rates ``zd``."""
        rows = 2 * len(list(self.pins()))
        phi, jac, gamma = np.zeros(rows), np.zeros((rows, z.size)), np.zeros(rows)
        for row, (j, sj, k, sk) in enumerate(self.pins()):
            r = slice(2 * row, 2 * row + 2)
            arm_j = rotation(z[3 * j + 2]) @ sj
            phi[r] += z[3 * j : 3 * j + 2] + arm_j
            jac[r, 3 * j : 3 * j + 2] = np.eye(2)
            jac[r, 3 * j + 2] = QUARTER_TURN @ arm_j
            gamma[r] += arm_j * zd[3 * j + 2] ** 2
            if k is None:
                phi[r] -= sk
                continue
            arm_k = rotation(z[3 * k + 2]) @ sk
            phi[r] -= z[3 * k : 3 * k + 2] + arm_k
            jac[r, 3 * k : 3 * k + 2] = -np.eye(2)
            jac[r, 3 * k + 2] = -QUARTER_TURN @ arm_k
            gamma[r] -= arm_k * zd[3 * k + 2] ** 2
        return phi, jac, gamma

    def positions(self, pose) -> np.ndarray:
        """Body coordinates at the end-body pose ``(x, y, phi)`` (circle intersections)."""
        n = self.n
        z = np.zeros(3 * (2 * n + 1))
        centre = np.array(pose[:2])
        z[6 * n : 6 * n + 3] = (*centre, pose[2])
        for i in range(n):
            c = centre + rotation(pose[2]) @ self.points[i]
            d = c - self.bases[i]
            rho = np.linalg.norm(d)
            cos_beta = (rho**2 + self.l1**2 - self.l2**2) / (2 * self.l1 * rho)
            theta = math.atan2(d[1], d[0]) + self.elbows[i] * math.acos(cos_beta)
            b = self.bases[i] + self.l1 * np.array([math.cos(theta), math.sin(theta)])
            distal = math.atan2(c[1] - b[1], c[0] - b[0])
            z[3 * i : 3 * i + 3] = (*(0.5 * (self.bases[i] + b)), theta)
            z[3 * (n + i) : 3 * (n + i) + 3] = (*(0.5 * (b + c)), distal)
        return z

    def state(self, pose, rate, acceleration):
        """``(z, zd, zdd)`` of the end body's pose and its two derivatives."""
        z = self.positions(pose)
        end = slice(6 * self.n, 6 * self.n + 3)
        free = np.r_[0 : 6 * self.n]
        zd, zdd = np.zeros_like(z), np.zeros_like(z)
        zd[end], zdd[end] = rate, acceleration
        _, jac, _ = self.constraints(z, zd)
        # square for the 3-RRR; the five-bar's end angle (a point's) is in no constraint
        zd[free] = np.linalg.lstsq(jac[:, free], -jac[:, end] @ zd[end], rcond=None)[0]
        _, _, gamma = self.constraints(z, zd)
        zdd[free] = np.linalg.lstsq(jac[:, free], gamma - jac[:, end] @ zdd[end], rcond=None)[0]
        return z, zd, zdd

    def torques(self, z, zd, zdd) -> np.ndarray:
        """The actuator torques of the KKT system (module docstring)."""
        n = self.n
        _, jac, _ = self.constraints(z, zd)
        selector = np.zeros((z.size, n))
        for i in range(n):
            selector[3 * i + 2, i] = 1.0
        weights = np.zeros(z.size)
        weights[1::3] = -self.gravity * np.diag(self.mass_matrix())[1::3]
        unknowns = np.linalg.lstsq(
            np.hstack([selector, jac.T]), self.mass_matrix() @ zdd - weights, rcond=None
        )[0]
        return unknowns[:n]

    def tree(self, z, zd, zdd):
        """The exported model's coordinates ``theta_i, psi_i, ..., x, y(, phi)``, their
        rates and accelerations."""
        n = self.n
        matrix = np.zeros((2 * n + 2 + self.rotates, z.size))
        for i in range(n):
            matrix[2 * i, 3 * i + 2] = 1.0
            matrix[2 * i + 1, 3 * (n + i) + 2] = 1.0
            matrix[2 * i + 1, 3 * i + 2] = -1.0
        for column in range(2 + self.rotates):
            matrix[2 * n + column, 6 * n + column] = 1.0
        q = matrix @ z
        q[1 : 2 * n : 2] = np.remainder(q[1 : 2 * n : 2] + math.pi, 2 * math.pi) - math.pi
        return q, matrix @ zd, matrix @ zdd


def quintic(start, stop, duration: float, t: float):
    """The pose, its rate and acceleration at ``t`` on the rest-to-rest quintic."""
    u = t / duration
    s = 10 * u**3 - 15 * u**4 + 6 * u**5
    ds = (30 * u**2 - 60 * u**3 + 30 * u**4) / duration
    dds = (60 * u - 180 * u**2 + 120 * u**3) / duration**2
    delta = np.asarray(stop, float) - np.asarray(start, float)
    return start + s * delta, ds * delta, dds * delta
