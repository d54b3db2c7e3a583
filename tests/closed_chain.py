"""A reference for the parallel robots' inverse dynamics: Lagrange multipliers in full
coordinates (plain numpy), independent of the Natural Orthogonal Complement's kernels.

Every body has the coordinates ``(x, y, theta)`` of its centre of mass and its angle; the
joints are holonomic constraints :math:`\\Phi(q) = 0` with the Jacobian :math:`\\Phi_q` and
the acceleration right-hand side :math:`\\gamma` of :math:`\\Phi_q\\ddot q = \\gamma`, from
the rigid-body rule :math:`\\ddot P = \\ddot c + \\ddot\\theta\\,k\\times R s -
\\dot\\theta^2 R s` for a body point :math:`P = c + R(\\theta) s`. Given the platform's
pose, rate and acceleration, the rates and accelerations of all bodies solve
:math:`[\\Phi_q; D]\\dot q = [0; \\dot X]` and :math:`[\\Phi_q; D]\\ddot q = [\\gamma;
\\ddot X]` (``D`` selects the platform); the actuator efforts ``f`` and the constraint
forces :math:`\\lambda` then solve the Lagrange equations

.. math:: M\\ddot q - Q_g = \\Phi_q^T\\lambda + B^T f,

``B`` the gradients of the actuated coordinates (virtual work :math:`f\\,\\delta\\rho`).
"""

from __future__ import annotations

import numpy as np


def rotate(theta: float, s) -> np.ndarray:
    c, n = np.cos(theta), np.sin(theta)
    return np.array([c * s[0] - n * s[1], n * s[0] + c * s[1]])


def perp(v) -> np.ndarray:
    return np.array([-v[1], v[0]])


class Chain:
    """Bodies (mass, inertia, coordinates, rates) and constraint rows."""

    def __init__(self) -> None:
        self.masses: list[float] = []
        self.inertias: list[float] = []
        self.q: list[float] = []
        self.rows: list[object] = []  # callables (q, qd) -> (jacobian rows, gamma)

    def body(self, mass: float, inertia: float, centre, theta: float) -> int:
        self.masses.append(mass)
        self.inertias.append(inertia)
        self.q.extend([centre[0], centre[1], theta])
        return len(self.masses) - 1

    @property
    def size(self) -> int:
        return 3 * len(self.masses)

    def point(self, q, b, s):
        """A body point, its Jacobian (2, size) and its quadratic acceleration term."""
        x, y, theta = q[3 * b : 3 * b + 3]
        rs = rotate(theta, s)
        jac = np.zeros((2, self.size))
        jac[:, 3 * b : 3 * b + 2] = np.eye(2)
        jac[:, 3 * b + 2] = perp(rs)
        return np.array([x, y]) + rs, jac, rs

    def coincide(self, a, sa, b=None, sb=None, fixed=None):
        """Point ``sa`` of body ``a`` at point ``sb`` of body ``b`` (or at ``fixed``)."""

        def rows(q, qd):
            pa, ja, ra = self.point(q, a, sa)
            gamma = qd[3 * a + 2] ** 2 * ra
            if b is None:
                return ja, gamma, pa - fixed
            pb, jb, rb = self.point(q, b, sb)
            return ja - jb, gamma - qd[3 * b + 2] ** 2 * rb, pa - pb

        self.rows.append(rows)

    def same_angle(self, a, b=None, angle=0.0):
        """Body ``a``'s angle equals body ``b``'s (or ``angle``)."""

        def rows(q, qd):
            jac = np.zeros((1, self.size))
            jac[0, 3 * a + 2] = 1.0
            value = q[3 * a + 2] - angle
            if b is not None:
                jac[0, 3 * b + 2] = -1.0
                value = q[3 * a + 2] - q[3 * b + 2]
            return jac, np.zeros(1), np.array([value])

        self.rows.append(rows)

    def on_line(self, a, sa, b=None, sb=None, fixed=None, direction=None):
        """Point ``sa`` of body ``a`` on the line through point ``sb`` of body ``b`` along
        ``b``'s local x axis (or through ``fixed`` along ``direction``)."""

        def rows(q, qd):
            pa, ja, ra = self.point(q, a, sa)
            qa = -(qd[3 * a + 2] ** 2) * ra
            if b is None:
                n = perp(direction)
                return (n @ ja)[None], np.array([-n @ qa]), np.array([n @ (pa - fixed)])
            pb, jb, rb = self.point(q, b, sb)
            theta, omega = q[3 * b + 2], qd[3 * b + 2]
            e, n = rotate(theta, (1.0, 0.0)), rotate(theta, (0.0, 1.0))
            d, dd = pa - pb, (ja - jb) @ qd
            jac = n @ (ja - jb)
            jac[3 * b + 2] -= d @ e
            quadratic = n @ (qa + omega**2 * rb) - 2.0 * omega * (dd @ e) - omega**2 * (d @ n)
            return jac[None], np.array([-quadratic]), np.array([d @ n])

        self.rows.append(rows)

    def constraints(self, q, qd):
        parts = [rows(q, qd) for rows in self.rows]
        return (
            np.vstack([p[0] for p in parts]),
            np.concatenate([p[1] for p in parts]),
            np.concatenate([p[2] for p in parts]),
        )

    def mass_matrix(self) -> np.ndarray:
        return np.diag(
            np.ravel([[m, m, i] for m, i in zip(self.masses, self.inertias, strict=True)])
        )

    def solve(self, platform, rate, acceleration, actuators, gravity):
        """Rates, accelerations (full coordinates), actuator efforts and the constraint
        residual, the platform the body ``platform``; ``actuators(q)`` gives ``B`` (m, size)."""
        q = np.array(self.q)
        d = np.zeros((3, self.size))
        d[:, 3 * platform : 3 * platform + 3] = np.eye(3)
        jac, _, residual = self.constraints(q, np.zeros(self.size))
        qd = np.linalg.solve(np.vstack([jac, d]), np.concatenate([np.zeros(len(jac)), rate]))
        jac, gamma, _ = self.constraints(q, qd)
        qdd = np.linalg.solve(np.vstack([jac, d]), np.concatenate([gamma, acceleration]))
        weight = np.ravel([[0.0, -m * gravity, 0.0] for m in self.masses])
        b = actuators(q)
        unknowns = np.linalg.solve(np.hstack([jac.T, b.T]), self.mass_matrix() @ qdd - weight)
        return qd, qdd, unknowns[len(jac) :], float(np.max(np.abs(residual)))

    def energy(self, qd, gravity) -> float:
        """Kinetic plus potential energy at the rates ``qd`` (positions: ``self.q``)."""
        q = np.array(self.q)
        heights = q[1::3]
        return 0.5 * qd @ self.mass_matrix() @ qd + gravity * np.dot(self.masses, heights)


def rpr_chain(bases, points, pose, body) -> tuple[Chain, object]:
    """The 3-RPR in full coordinates: platform (body 0), per leg a cylinder turning about
    ``A_i`` (centre ``c`` from it) and a piston (centre ``c_p`` back from ``B_i``) sharing
    its angle, its centre on the cylinder's axis, its end at the platform joint."""
    mc, ic, cc, mp, ip, cp, m, inertia = body[:8]
    chain = Chain()
    platform = chain.body(m, inertia, pose[:2], pose[2])
    pistons = []
    for a, q in zip(np.asarray(bases), np.asarray(points), strict=True):
        v = np.array(pose[:2]) + rotate(pose[2], q) - a
        e, psi = v / np.linalg.norm(v), np.arctan2(v[1], v[0])
        cylinder = chain.body(mc, ic, a + cc * e, psi)
        piston = chain.body(mp, ip, a + v - cp * e, psi)
        chain.coincide(cylinder, (-cc, 0.0), fixed=a)
        chain.same_angle(piston, cylinder)
        chain.on_line(piston, (0.0, 0.0), cylinder, (-cc, 0.0))
        chain.coincide(piston, (cp, 0.0), platform, q)
        pistons.append((piston, a))

    def actuators(qs):
        rows = []
        for piston, a in pistons:
            point, jac, _ = chain.point(qs, piston, (cp, 0.0))
            rows.append((point - a) / np.linalg.norm(point - a) @ jac)
        return np.array(rows)

    return chain, actuators


def prr_chain(bases, angles, points, links, modes, pose, body) -> tuple[Chain, object]:
    """The 3-PRR in full coordinates: platform (body 0), per leg a slider on its rail
    (angle fixed at 0) and a link from the slider to the platform joint."""
    ms, ml, il, m, inertia = body[:5]
    chain = Chain()
    platform = chain.body(m, inertia, pose[:2], pose[2])
    sliders = []
    for b, t, q, link, sigma in zip(
        np.asarray(bases), angles, np.asarray(points), links, modes, strict=True
    ):
        u = np.array([np.cos(t), np.sin(t)])
        c = np.array(pose[:2]) + rotate(pose[2], q)
        g = c - b
        stroke = g @ u + sigma * np.sqrt(link**2 - (g[0] * u[1] - g[1] * u[0]) ** 2)
        s = b + stroke * u
        slider = chain.body(ms, 0.0, s, 0.0)
        rod = chain.body(ml, il, 0.5 * (s + c), np.arctan2(c[1] - s[1], c[0] - s[0]))
        chain.same_angle(slider, angle=0.0)
        chain.on_line(slider, (0.0, 0.0), fixed=b, direction=u)
        chain.coincide(rod, (-0.5 * link, 0.0), slider, (0.0, 0.0))
        chain.coincide(rod, (0.5 * link, 0.0), platform, q)
        sliders.append((slider, u))

    def actuators(qs):
        rows = np.zeros((3, chain.size))
        for row, (slider, u) in enumerate(sliders):
            rows[row, 3 * slider : 3 * slider + 2] = u
        return rows

    return chain, actuators
