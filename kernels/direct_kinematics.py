"""Direct kinematics of planar parallel robots: every real assembly mode (pure numpy).

**Three bases, three distances** (:func:`three_distance_poses`): known points :math:`P_i`
in the plane, platform points :math:`q_i` in the platform frame and distances
:math:`d_i`; find every pose :math:`(x, y, \\varphi)` with

.. math:: |p + R(\\varphi) q_i - P_i| = d_i, \\qquad i = 1, 2, 3.

The 3-RPR (:math:`P_i = A_i`, :math:`d_i = \\rho_i`), the 3-RRR (:math:`P_i` the elbows
:math:`A_i + l_1(\\cos\\theta_i, \\sin\\theta_i)`, :math:`d_i = l_2`) and the 3-PRR
(:math:`P_i` the sliders' joints :math:`B_i + s_i u_i`, :math:`d_i = l_i`) are this problem.

*Elimination* (after Gosselin, Sefrioui and Richard, 1992). With :math:`u = p + R q_1`
(the platform point 1) and :math:`e_i = q_i - q_1`, leg 1 reads
:math:`|u - P_1|^2 = d_1^2`, and legs 2, 3 minus leg 1 are linear in :math:`u`:

.. math:: 2\\,(R e_i - P_i + P_1) \\cdot u = d_i^2 - d_1^2 - |e_i|^2 - |P_i|^2 + |P_1|^2
          + 2 P_i \\cdot R e_i, \\qquad i = 2, 3,

a 2 × 2 system :math:`M(\\varphi) u = r(\\varphi)` whose entries are affine in
:math:`(\\cos\\varphi, \\sin\\varphi)`. Cramer's rule :math:`u = \\operatorname{adj}(M) r /
\\det M` in leg 1 gives

.. math:: F(\\varphi) = |\\operatorname{adj}(M)\\, r - P_1 \\det M|^2 - d_1^2 (\\det M)^2 = 0,

a trigonometric polynomial of degree at most 4 (products of four affine factors), so
:math:`z^4 F` is a polynomial of degree 8 in :math:`z = e^{i\\varphi}`. Its coefficients are
the exact discrete Fourier transform of 16 samples of :math:`F` (no aliasing below
harmonic 8); every real mode is a root on the unit circle. The harmonic 4 cancels
identically (the spurious factor :math:`1 + t^2` of the classic elimination in
:math:`t = \\tan(\\varphi/2)`, i.e. roots at :math:`z = 0, \\infty`), so at most six real
modes remain: the classic sextic. All eight roots come from the companion matrix
(``numpy.roots``), so no real root is missed by a search; each root near the unit circle
gives candidates for :math:`u` (Cramer's rule, and both intersections of circles 1 and 2,
which also covers :math:`\\det M = 0`; those that nearly close all three legs, at least the
best one, :data:`START_MISFIT`), polished by Newton's method on the three equations
and kept when their residual is below ``tolerance`` times the problem's scale. Duplicates
(one pose reached from several candidates) are merged.

**Two circles** (:func:`circle_intersections`): the five-bar's end point at distance
:math:`l_{2,i}` from both elbows :math:`B_i`: two modes, one on each side of
:math:`B_1 B_2` (one when tangent, none when apart).
"""

import numpy as np

#: Samples of :math:`F` for its Fourier coefficients (harmonics 0..4, exactly).
SAMPLES = 16
#: Largest leg misfit :math:`||v_i|^2 - d_i^2|` (unit scale) of a start Newton polishes,
#: beyond the best one at a root.
START_MISFIT = 1e-3


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _rotate(phi, q):
    """:math:`R(\\varphi) q` for a vector of angles ``phi`` (n,) and one point ``q`` (2,)."""
    c, s = np.cos(phi), np.sin(phi)
    return np.stack((c * q[0] - s * q[1], s * q[0] + c * q[1]), axis=-1)


def _linear_system(phi, bases, points, distances):
    """``M`` (n, 2, 2) and ``r`` (n, 2) of legs 2, 3 minus leg 1 at the angles ``phi``."""
    m = np.empty((phi.size, 2, 2))
    r = np.empty((phi.size, 2))
    for row, i in enumerate((1, 2)):
        e = points[i] - points[0]
        re = _rotate(phi, e)
        m[:, row, :] = 2.0 * (re - bases[i] + bases[0])
        r[:, row] = (
            distances[i] ** 2
            - distances[0] ** 2
            - e @ e
            - bases[i] @ bases[i]
            + bases[0] @ bases[0]
            + 2.0 * (re @ bases[i])
        )
    return m, r


def _eliminant(phi, bases, points, distances):
    """:math:`F(\\varphi)` of the module docstring at the angles ``phi``."""
    m, r = _linear_system(phi, bases, points, distances)
    det = m[:, 0, 0] * m[:, 1, 1] - m[:, 0, 1] * m[:, 1, 0]
    ux = m[:, 1, 1] * r[:, 0] - m[:, 0, 1] * r[:, 1] - bases[0, 0] * det
    uy = m[:, 0, 0] * r[:, 1] - m[:, 1, 0] * r[:, 0] - bases[0, 1] * det
    return ux * ux + uy * uy - (distances[0] * det) ** 2


def _residuals(pose, bases, points, distances):
    """Per leg :math:`|p + R q_i - P_i|^2 - d_i^2` and its Jacobian (3, 3) in the pose."""
    x, y, phi = pose
    c, s = np.cos(phi), np.sin(phi)
    rq = np.stack((c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]), 1)
    v = np.array([x, y]) + rq - bases
    f = np.sum(v * v, axis=1) - distances**2
    jac = np.empty((3, 3))
    jac[:, :2] = 2.0 * v
    jac[:, 2] = 2.0 * _cross(rq, v)
    return f, jac


def _polish(pose, bases, points, distances, iterations=30):
    """Newton's method on the three leg equations (least squares where singular), at unit
    scale: stops once a step is below 1e-14 (quadratic convergence: the next one would be
    below rounding)."""
    pose = np.array(pose, dtype=np.float64)
    for _ in range(iterations):
        f, jac = _residuals(pose, bases, points, distances)
        step = np.linalg.lstsq(jac, -f, rcond=None)[0]
        pose += step
        if np.max(np.abs(step)) <= 1e-14:
            break
    return pose


def circle_intersections(a, ra, b, rb):
    """The points at distance ``ra`` from ``a`` and ``rb`` from ``b`` (2,): an array (m, 2),
    ``m`` = 2 (left of ``a -> b`` first), 1 (tangent, to a relative 1e-12) or 0."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    d = float(np.hypot(*(b - a)))
    if d == 0.0:
        return np.empty((0, 2))
    along = (ra * ra - rb * rb + d * d) / (2.0 * d)
    h2 = ra * ra - along * along
    scale = max(ra, rb, d) ** 2
    if h2 < -1e-12 * scale:
        return np.empty((0, 2))
    e = (b - a) / d
    foot, normal = a + along * e, np.array([-e[1], e[0]])
    if h2 <= 1e-12 * scale:
        return foot[None, :]
    h = np.sqrt(h2)
    return np.stack((foot + h * normal, foot - h * normal))


def three_distance_poses(bases, points, distances, tolerance=1e-9):
    """Every real pose ``(x, y, phi_rad)`` with :math:`|p + R(\\varphi) q_i - P_i| = d_i`.

    ``bases`` (3, 2) the known points :math:`P_i`, ``points`` (3, 2) the platform points
    :math:`q_i` (platform frame), ``distances`` (3,): an array (m, 3), ``m <= 6``, sorted by
    :math:`\\varphi \\in (-\\pi, \\pi]`. A pose is kept when every leg's
    :math:`||v_i| - d_i|` is below ``tolerance`` times the problem's scale.
    """
    bases = np.asarray(bases, dtype=np.float64)
    points = np.asarray(points, dtype=np.float64)
    distances = np.asarray(distances, dtype=np.float64)
    scale = float(max(np.max(np.abs(bases)), np.max(np.abs(points)), np.max(distances), 1e-300))
    # Work at unit scale (the polynomial's coefficients span scale**8).
    bases, points, distances = bases / scale, points / scale, distances / scale
    phi = 2.0 * np.pi * np.arange(SAMPLES) / SAMPLES
    harmonics = np.fft.fft(_eliminant(phi, bases, points, distances)) / SAMPLES
    # z^4 F(z) = sum_k c_k z^(k + 4), c_k = harmonics[k mod SAMPLES], k = -4..4.
    coefficients = np.array([harmonics[k % SAMPLES] for k in range(4, -5, -1)])
    size = np.max(np.abs(coefficients))
    if size == 0.0:  # F vanishes identically: a degenerate (architecture-singular) robot
        return np.empty((0, 3))
    roots = np.roots(coefficients / size)
    near = roots[np.abs(np.abs(roots) - 1.0) < 1e-3]
    poses = []
    for angle in np.angle(near):
        for pose in _candidates(angle, bases, points, distances):
            pose = _polish(pose, bases, points, distances)
            f, _ = _residuals(pose, bases, points, distances)
            error = np.abs(np.sqrt(np.maximum(f + distances**2, 0.0)) - distances)
            if np.all(np.isfinite(pose)) and np.max(error) <= tolerance:
                pose[2] = np.angle(np.exp(1j * pose[2]))
                if not any(_same(pose, other) for other in poses):
                    poses.append(pose)
    out = np.array(sorted(poses, key=lambda pose: pose[2])).reshape(-1, 3)
    out[:, :2] *= scale
    return out


def _same(a, b):
    """Two unit-scale poses equal to 1e-7 (angles compared around the circle)."""
    return bool(
        np.max(np.abs(a[:2] - b[:2])) < 1e-7 and abs(np.angle(np.exp(1j * (a[2] - b[2])))) < 1e-7
    )


def _candidates(angle, bases, points, distances):
    """Starting poses at one root ``angle``: Cramer's ``u`` and both circle intersections."""
    phi = np.array([angle])
    m, r = _linear_system(phi, bases, points, distances)
    rq1 = _rotate(phi, points[0])[0]
    starts = []
    det = np.linalg.det(m[0])
    if abs(det) > 1e-12:
        starts.append(np.linalg.solve(m[0], r[0]))
    p2 = bases[1] - _rotate(phi, points[1] - points[0])[0]
    starts.extend(circle_intersections(bases[0], distances[0], p2, distances[1]))
    poses = [np.array([u[0] - rq1[0], u[1] - rq1[1], angle]) for u in starts]
    # Keep the starts that nearly close leg 3 too (the far circle intersection does not),
    # at least the best one, each once: Newton then polishes few.
    misfit = [np.max(np.abs(_residuals(p, bases, points, distances)[0])) for p in poses]
    kept: list = []
    for k in np.argsort(misfit):
        if kept and misfit[k] > START_MISFIT:
            break
        if all(np.max(np.abs(poses[k] - other)) > 1e-9 for other in kept):
            kept.append(poses[k])
    return kept
