"""Baselines shared by the benchmarks: the same inverse dynamics without Numba, and the
planar chain as a Pinocchio model (the ``bench`` extra)."""

import numpy as np


def numpy_newton_euler(lengths, masses, inertias, gravity, theta, omega, alpha):
    """Vectorised over samples (S, n), looping over links: the same recursion in NumPy."""
    phi, rate, accel = np.cumsum(theta), np.cumsum(omega), np.cumsum(alpha)
    ux, uy = np.cos(phi), np.sin(phi)
    bx = -accel * uy - rate**2 * ux
    by = accel * ux - rate**2 * uy
    n = lengths.shape[1]
    fx, fy = np.empty_like(lengths), np.empty_like(lengths)
    ax = np.zeros(lengths.shape[0])
    ay = np.full(lengths.shape[0], gravity)
    for i in range(n):
        fx[:, i] = masses[:, i] * (ax + 0.5 * lengths[:, i] * bx[i])
        fy[:, i] = masses[:, i] * (ay + 0.5 * lengths[:, i] * by[i])
        ax = ax + lengths[:, i] * bx[i]
        ay = ay + lengths[:, i] * by[i]
    tau = np.empty_like(lengths)
    big_fx = np.zeros_like(ax)
    big_fy = np.zeros_like(ax)
    moment = np.zeros_like(ax)
    for i in range(n - 1, -1, -1):
        hx, hy = 0.5 * lengths[:, i] * ux[i], 0.5 * lengths[:, i] * uy[i]
        moment = moment + inertias[:, i] * accel[i] + hx * fy[:, i] - hy * fx[:, i]
        moment = moment + 2.0 * (hx * big_fy - hy * big_fx)
        big_fx = big_fx + fx[:, i]
        big_fy = big_fy + fy[:, i]
        tau[:, i] = moment
    return tau


def import_pinocchio():
    """``pinocchio`` (package ``pin``). Its wheels put the module under a ``cmeel.prefix``
    folder that a ``cmeel.pth`` file adds to ``sys.path``; a virtual environment that sees
    ``pin`` through another environment's site-packages (not processed for ``.pth``
    files) imports ``cmeel_pth`` first to do the same."""
    try:
        import pinocchio
    except ImportError:
        import cmeel_pth  # noqa: F401
        import pinocchio
    return pinocchio


def pinocchio_chain(lengths_m, masses_kg, inertias_kgm2, gravity_m_s2):
    """``(model, data)`` of the planar chain in Pinocchio: revolute-z joints, joint i+1 at
    ``l_i`` along link i's x axis, link i's centre of mass at mid-link with
    ``I_zz = I_i`` (``I_xx`` tiny, ``I_yy = I_i`` as in ``benchmarks/mujoco_model.py``), gravity
    ``(0, -g, 0)``."""
    pin = import_pinocchio()
    model = pin.Model()
    parent = 0
    for i, (length, mass, inertia) in enumerate(
        zip(lengths_m, masses_kg, inertias_kgm2, strict=True)
    ):
        offset = 0.0 if i == 0 else float(lengths_m[i - 1])
        placement = pin.SE3(np.eye(3), np.array([offset, 0.0, 0.0]))
        joint = model.addJoint(parent, pin.JointModelRZ(), placement, f"joint{i + 1}")
        body = pin.Inertia(
            float(mass),
            np.array([0.5 * float(length), 0.0, 0.0]),
            np.diag([1e-10, float(inertia), float(inertia)]),
        )
        model.appendBodyToJoint(joint, body, pin.SE3.Identity())
        parent = joint
    model.gravity.linear = np.array([0.0, -float(gravity_m_s2), 0.0])
    return model, model.createData()
