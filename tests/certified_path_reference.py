"""An independent reference for the certified-path tests: the legs' inverse kinematics in
closed form (vectorised over times), κ by central finite differences of it, a continuous
failure margin (>= 0: valid) and its first root by scipy's ``brentq``."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Legs:
    """A robot with RR legs: base joints, platform points (platform frame; zeros for the
    five-bar), link lengths, elbow signs, joint limits (rad) and L (cm; 0: no orientation)."""

    bases: np.ndarray
    points: np.ndarray
    l1: np.ndarray
    l2: np.ndarray
    elbow: np.ndarray
    limits: np.ndarray
    length_cm: float

    def angles(self, pose):
        """``(theta, cos_beta)`` (n, legs) at poses (n, 2 or 3): theta = alpha + s beta
        (NaN where the leg cannot close)."""
        pose = np.atleast_2d(pose)
        phi = pose[:, 2:3] if pose.shape[1] == 3 else np.zeros((len(pose), 1))
        c, s = np.cos(phi), np.sin(phi)
        qx, qy = self.points[:, 0], self.points[:, 1]
        vx = pose[:, :1] + c * qx - s * qy - self.bases[:, 0]
        vy = pose[:, 1:2] + s * qx + c * qy - self.bases[:, 1]
        rho = np.hypot(vx, vy)
        cos_beta = (rho**2 + self.l1**2 - self.l2**2) / (2.0 * self.l1 * rho)
        with np.errstate(invalid="ignore"):
            beta = np.arccos(cos_beta)
        return np.arctan2(vy, vx) + self.elbow * beta, cos_beta

    def kappa(self, pose, h=1e-6):
        """κ of d theta / d(x, y, L phi) by central differences, (n,)."""
        pose = np.atleast_2d(pose)
        d = pose.shape[1]
        columns = []
        for j in range(d):
            step = np.zeros(d)
            step[j] = h
            plus, minus = self.angles(pose + step)[0], self.angles(pose - step)[0]
            diff = np.angle(np.exp(1j * (plus - minus))) / (2.0 * h)
            columns.append(diff / self.length_cm if j == 2 else diff)
        matrices = np.stack(columns, axis=2)
        kappa = np.full(len(pose), np.inf)  # a step past a leg's reach: singular there
        finite = np.isfinite(matrices).all(axis=(1, 2))
        sigma = np.linalg.svd(matrices[finite], compute_uv=False)
        with np.errstate(divide="ignore"):
            kappa[finite] = np.where(sigma[:, -1] > 0, sigma[:, 0] / sigma[:, -1], np.inf)
        return kappa

    def margins(self, pose, kappa_max):
        """``{"leg", "joint_limit", "kappa"}`` margins (n,), each >= 0 where that test
        holds: reach 1 - |cos beta|, the least joint's angle inside its limits (rad),
        (kappa_max - κ) / kappa_max."""
        theta, cos_beta = self.angles(pose)
        reach = (1.0 - np.abs(cos_beta)).min(axis=1)
        lo, hi = self.limits[:, 0], self.limits[:, 1]
        t = lo + np.mod(theta - lo, 2.0 * np.pi)
        inside = np.minimum(t - lo, hi - t)
        outside = -np.minimum(t - hi, lo + 2.0 * np.pi - t)
        joint = np.where(t <= hi, inside, outside).min(axis=1)
        joint = np.where(reach >= 0.0, joint, np.inf)
        valid = (reach >= 0.0) & (joint >= 0.0)
        kappa = np.zeros(len(valid))
        if valid.any():
            kappa[valid] = self.kappa(np.atleast_2d(pose)[valid])
        return {"leg": reach, "joint_limit": joint, "kappa": (kappa_max - kappa) / kappa_max}


def path_poses(start, stop, duration_s, times):
    """The quintic's poses (cm, cm[, rad]) at ``times``: s = 10 tau^3 - 15 tau^4 + 6 tau^5,
    written here again (not the package's)."""
    tau = np.asarray(times, dtype=float)[:, None] / duration_s
    s = 10.0 * tau**3 - 15.0 * tau**4 + 6.0 * tau**5
    start = np.asarray(start, dtype=float)
    return start + (np.asarray(stop, dtype=float) - start) * s


def first_failure(legs, start, stop, duration_s, kappa_max, samples=20_000):
    """``(t_star, reason)``: the first root of the least margin after the dense samples'
    first failing one (brentq between it and the sample before), or ``(None, "")`` when
    every sample is valid."""
    from scipy.optimize import brentq

    times = np.linspace(0.0, duration_s, samples + 1)

    def least(t):
        m = legs.margins(path_poses(start, stop, duration_s, np.atleast_1d(t)), kappa_max)
        return np.minimum(np.minimum(m["leg"], m["joint_limit"]), m["kappa"])

    worst = least(times)
    bad = np.flatnonzero(worst < 0.0)
    if not len(bad):
        return None, ""
    k = int(bad[0])
    if k == 0:
        t_star = 0.0
    else:
        t_star = brentq(lambda t: float(least(t)[0]), times[k - 1], times[k], xtol=1e-12)
    after = min(duration_s, t_star + 1e-9 * duration_s)
    m = legs.margins(path_poses(start, stop, duration_s, np.array([after])), kappa_max)
    return t_star, min(m, key=lambda name: float(m[name][0]))


def check_certificate(certificate, legs, start, stop, kappa_max, verdict, reason, samples):
    """A 1-s path's certificate against the reference: the verdict; a ``yes`` path has every
    dense sample valid; a ``no`` path's bracket holds the first crossing (brentq), is at
    most T/1000 wide and names its ``reason``; the largest κ over the certified part, sampled
    densely, lies in the peak's bracket (within 1e-7 for the finite differences), which is
    at most 1 % wide."""
    t_star, found = first_failure(legs, start, stop, 1.0, kappa_max, samples)
    assert certificate.certified == verdict
    if verdict == "yes":
        assert t_star is None
        until = 1.0
    else:
        assert certificate.failure_lo_s - 1e-9 <= t_star <= certificate.failure_hi_s + 1e-9
        assert certificate.failure_hi_s - certificate.failure_lo_s <= 1e-3
        assert certificate.reason == found == reason
        until = certificate.failure_lo_s
    if until == 0.0:  # failing at the start: no certified part, no peak
        assert math.isnan(certificate.kappa_peak_lo) and math.isnan(certificate.kappa_peak_hi)
        return
    times = np.linspace(0.0, until, samples + 1)
    sampled = legs.kappa(path_poses(start, stop, 1.0, times)).max()
    assert certificate.kappa_peak_lo <= sampled * (1.0 + 1e-7)
    assert certificate.kappa_peak_hi >= sampled * (1.0 - 1e-7)
    assert certificate.kappa_peak_hi <= certificate.kappa_peak_lo * 1.01


@dataclass(frozen=True)
class PrismaticLegs:
    """A 3-RPR: base joints, platform points (platform frame), leg-length limits (cm) and
    L (cm); its actuated coordinates are the legs' lengths."""

    bases: np.ndarray
    points: np.ndarray
    limits: np.ndarray
    length_cm: float

    def lengths(self, pose):
        """The legs' lengths (n, 3) at poses (n, 3)."""
        pose = np.atleast_2d(pose)
        c, s = np.cos(pose[:, 2:3]), np.sin(pose[:, 2:3])
        qx, qy = self.points[:, 0], self.points[:, 1]
        vx = pose[:, :1] + c * qx - s * qy - self.bases[:, 0]
        vy = pose[:, 1:2] + s * qx + c * qy - self.bases[:, 1]
        return np.hypot(vx, vy)

    def kappa(self, pose, h=1e-6):
        """κ of d rho / d(x, y, L phi) by central differences, (n,)."""
        pose = np.atleast_2d(pose)
        columns = []
        for j in range(3):
            step = np.zeros(3)
            step[j] = h
            diff = (self.lengths(pose + step) - self.lengths(pose - step)) / (2.0 * h)
            columns.append(diff / self.length_cm if j == 2 else diff)
        sigma = np.linalg.svd(np.stack(columns, axis=2), compute_uv=False)
        with np.errstate(divide="ignore"):
            return np.where(sigma[:, -1] > 0, sigma[:, 0] / sigma[:, -1], np.inf)

    def margins(self, pose, kappa_max):
        """As :meth:`Legs.margins`: every leg closes (``leg`` always 1), its length inside
        its limits (cm), (kappa_max - κ) / kappa_max."""
        rho = self.lengths(pose)
        joint = np.minimum(rho - self.limits[:, 0], self.limits[:, 1] - rho).min(axis=1)
        kappa = np.zeros(len(joint))
        valid = joint >= 0.0
        if valid.any():
            kappa[valid] = self.kappa(np.atleast_2d(pose)[valid])
        return {
            "leg": np.ones(len(joint)),
            "joint_limit": joint,
            "kappa": (kappa_max - kappa) / kappa_max,
        }


@dataclass(frozen=True)
class SliderLegs:
    """A 3-PRR: slider lines (origins, unit directions), strokes (cm), distal lengths,
    slider modes, platform points (platform frame) and L (cm); its actuated coordinates are
    the sliders' strokes s = w.u + sigma sqrt(l^2 - (w.n)^2), w = C - B."""

    origins: np.ndarray
    directions: np.ndarray
    strokes: np.ndarray
    distal: np.ndarray
    modes: np.ndarray
    points: np.ndarray
    length_cm: float

    def parts(self, pose):
        """``(s, q)`` (n, 3): the strokes (NaN where q < 0) and q = l^2 - h^2."""
        pose = np.atleast_2d(pose)
        c, s = np.cos(pose[:, 2:3]), np.sin(pose[:, 2:3])
        qx, qy = self.points[:, 0], self.points[:, 1]
        wx = pose[:, :1] + c * qx - s * qy - self.origins[:, 0]
        wy = pose[:, 1:2] + s * qx + c * qy - self.origins[:, 1]
        ux, uy = self.directions[:, 0], self.directions[:, 1]
        h = -uy * wx + ux * wy
        q = self.distal**2 - h**2
        with np.errstate(invalid="ignore"):
            return wx * ux + wy * uy + self.modes * np.sqrt(q), q

    def kappa(self, pose, h=1e-6):
        """κ of d s / d(x, y, L phi) by central differences, (n,)."""
        pose = np.atleast_2d(pose)
        columns = []
        for j in range(3):
            step = np.zeros(3)
            step[j] = h
            diff = (self.parts(pose + step)[0] - self.parts(pose - step)[0]) / (2.0 * h)
            columns.append(diff / self.length_cm if j == 2 else diff)
        matrices = np.stack(columns, axis=2)
        kappa = np.full(len(pose), np.inf)
        finite = np.isfinite(matrices).all(axis=(1, 2))
        sigma = np.linalg.svd(matrices[finite], compute_uv=False)
        with np.errstate(divide="ignore"):
            kappa[finite] = np.where(sigma[:, -1] > 0, sigma[:, 0] / sigma[:, -1], np.inf)
        return kappa

    def margins(self, pose, kappa_max):
        """As :meth:`Legs.margins`: q / l^2 (the leg closes), the least slider's stroke
        margin (cm), (kappa_max - κ) / kappa_max."""
        stroke, q = self.parts(pose)
        reach = (q / self.distal**2).min(axis=1)
        joint = np.minimum(stroke - self.strokes[:, 0], self.strokes[:, 1] - stroke)
        joint = np.where(reach >= 0.0, joint.min(axis=1), np.inf)
        valid = (reach >= 0.0) & (joint >= 0.0)
        kappa = np.zeros(len(valid))
        if valid.any():
            kappa[valid] = self.kappa(np.atleast_2d(pose)[valid])
        return {"leg": reach, "joint_limit": joint, "kappa": (kappa_max - kappa) / kappa_max}


def shrink_kappa(monkeypatch, mechanism):
    """The mutation: ``mechanism``'s path box test with its κ enclosure shrunk by 1 % (the
    lower end raised, the upper end lowered)."""
    original = type(mechanism).path_box_test

    def shrunk(self, robot, spec):
        test = original(self, robot, spec)

        def shrunk_test(boxes):
            verdict, reason, kappa = test(boxes)
            return verdict, reason, kappa * [1.01, 1.0 / 1.01]

        return shrunk_test

    monkeypatch.setattr(type(mechanism), "path_box_test", shrunk)
