"""Baselines shared by the benchmarks: the same inverse dynamics without Numba, and the
planar chain as a Pinocchio model (the ``bench`` extra)."""

import math

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


#: Pinocchio's velocity indices of the 3-RRR's actuated joints (:func:`pinocchio_3rrr`).
ACTUATED_3RRR = [0, 3, 5]


def pinocchio_3rrr(robot):
    """``(pin, model, data, constraint models, constraint datas)``: three RR legs, leg 1's
    distal link carrying the platform (a revolute joint at C1), legs 2 and 3 closed at C2,
    C3 by point constraints; gravity (0, -g, 0). Joints are added depth first (the
    platform right after leg 1), as Pinocchio's algorithms need every subtree's velocity
    indices contiguous; ``q`` is ``(theta_1, psi_1 - theta_1, phi - psi_1, theta_2,
    psi_2 - theta_2, theta_3, psi_3 - theta_3)``."""
    pin = import_pinocchio()
    model = pin.Model()
    l1, l2 = robot.proximal_cm / 100, robot.distal_cm / 100

    def link(parent, placement, mass, inertia, length):
        joint = model.addJoint(parent, pin.JointModelRZ(), placement, f"joint{model.njoints}")
        body = pin.Inertia(mass, np.array([length / 2, 0, 0]), np.diag([1e-10, inertia, inertia]))
        model.appendBodyToJoint(joint, body, pin.SE3.Identity())
        return joint

    distal = []
    platform = 0
    for leg, (ax, ay) in enumerate(robot.base_joints_cm()):
        base = pin.SE3(np.eye(3), np.array([ax / 100, ay / 100, 0.0]))
        proximal = link(0, base, robot.proximal_mass_kg, robot.proximal_inertia_kgm2, l1)
        elbow = pin.SE3(np.eye(3), np.array([l1, 0, 0]))
        distal.append(link(proximal, elbow, robot.distal_mass_kg, robot.distal_inertia_kgm2, l2))
        if leg == 0:
            tip = pin.SE3(np.eye(3), np.array([l2, 0, 0]))
            mass, inertia = robot.platform_mass_kg, robot.platform_inertia_kgm2
            platform = link(distal[0], tip, mass, inertia, 0.0)
    model.gravity.linear = np.array([0.0, -robot.gravity_m_s2, 0.0])
    data = model.createData()
    constraints = pin.StdVec_RigidConstraintModel()
    for leg in (1, 2):
        qx, qy = robot.platform_points_cm()[leg]
        constraints.append(
            pin.RigidConstraintModel(
                pin.ContactType.CONTACT_3D,
                model,
                distal[leg],
                pin.SE3(np.eye(3), np.array([l2, 0, 0])),
                platform,
                pin.SE3(np.eye(3), np.array([qx / 100, qy / 100, 0])),
                pin.ReferenceFrame.LOCAL,
            )
        )
    datas = pin.StdVec_RigidConstraintData()
    for c in constraints:
        datas.append(c.createData())
    pin.initConstraintDynamics(model, data, constraints, datas)
    return pin, model, data, constraints, datas


def joint_state_3rrr(robot, pose, rate, theta, theta_rate):
    """Pinocchio's ``(q, v)``: relative angles (theta_i, psi_i - theta_i) per leg and the
    platform's phi - psi_1, psi and its rate from the leg's geometry."""
    l1, l2 = robot.proximal_cm / 100, robot.distal_cm / 100
    x, y, phi = pose
    xd, yd, phid = rate
    c, s = math.cos(phi), math.sin(phi)
    q, v, psis = [], [], []
    for i, ((ax, ay), (qx, qy)) in enumerate(
        zip(robot.base_joints_cm(), robot.platform_points_cm(), strict=True)
    ):
        rx, ry = (c * qx - s * qy) / 100, (s * qx + c * qy) / 100
        th, thd = theta[i], theta_rate[i]
        ux = x + rx - ax / 100 - l1 * math.cos(th)
        uy = y + ry - ay / 100 - l1 * math.sin(th)
        psi = math.atan2(uy, ux)
        # C' - l1 thd e_perp(th) = l2 psid e_perp(psi)
        wx = xd - phid * ry + l1 * thd * math.sin(th)
        wy = yd + phid * rx - l1 * thd * math.cos(th)
        psid = (-wx * math.sin(psi) + wy * math.cos(psi)) / l2
        q += [th, psi - th]
        v += [thd, psid - thd]
        psis.append((psi, psid))
    q.insert(2, phi - psis[0][0])
    v.insert(2, phid - psis[0][1])
    return np.array(q), np.array(v)
