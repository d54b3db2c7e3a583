"""The n-link planar serial revolute robot as a MuJoCo model (built with ``MjSpec``).

Used by the tests (an independent reference engine) and by ``benchmarks/bench_dynamics.py``.
The plane of motion is MuJoCo's x-y plane, gravity points along -y, every joint is a hinge
about z at the proximal end of its link, and link i's frame is offset by ``l_{i-1}`` along
the parent's x axis, so ``qpos`` holds the relative joint angles of paper A.

Each link's inertial frame sits at mid-link with ``diaginertia = (eps, I_i, I_i)``: only
I_zz = I_i enters planar motion; MuJoCo requires the principal moments to satisfy the
triangle inequality (A + B >= C), which a slender rod along x does with I_yy = I_zz and a
tiny I_xx. No damping, armature, friction loss, geoms or contacts.
"""

import numpy as np

# I_xx of every link: tiny but positive (MuJoCo rejects non-positive principal moments).
AXIAL_INERTIA_KGM2 = 1e-10


def chain_model(lengths_m, masses_kg, inertias_kgm2, gravity_m_s2=9.81, timestep_s=1e-4):
    """Compiled ``(mujoco.MjModel, mujoco.MjData)`` of the chain (RK4 integrator, contacts
    disabled), built with ``mujoco.MjSpec`` (an MJCF text nests one ``<body>`` per link and
    MuJoCo's XML parser refuses chains much deeper than 100 links)."""
    import mujoco

    spec = mujoco.MjSpec()
    spec.compiler.degree = False
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.option.gravity = [0.0, -float(gravity_m_s2), 0.0]
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_RK4
    spec.option.timestep = float(timestep_s)
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
    parent = spec.worldbody
    lengths_m = np.asarray(lengths_m, dtype=float)
    for i, (length, mass, inertia) in enumerate(
        zip(lengths_m, masses_kg, inertias_kgm2, strict=True)
    ):
        body = parent.add_body(
            pos=[0.0 if i == 0 else lengths_m[i - 1], 0.0, 0.0],
            mass=float(mass),
            ipos=[0.5 * length, 0.0, 0.0],
            inertia=[AXIAL_INERTIA_KGM2, float(inertia), float(inertia)],
            explicitinertial=True,
        )
        body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0.0, 0.0, 1.0])
        parent = body
    model = spec.compile()
    return model, mujoco.MjData(model)


def set_chain_parameters(model, lengths_m, masses_kg, inertias_kgm2):
    """Overwrite the link parameters of a compiled chain in place (bodies 1..n).

    Updates ``body_pos`` (offset of link i+1 = l_i), ``body_ipos`` (mid-link),
    ``body_mass`` and ``body_inertia``; enough for ``mj_inverse``/``mj_step``, which read
    these arrays on every call.
    """
    n = len(lengths_m)
    model.body_pos[2 : n + 1, 0] = lengths_m[:-1]
    model.body_ipos[1 : n + 1, 0] = 0.5 * np.asarray(lengths_m)
    model.body_mass[1 : n + 1] = masses_kg
    model.body_inertia[1 : n + 1, 1] = inertias_kgm2
    model.body_inertia[1 : n + 1, 2] = inertias_kgm2


def mujoco_inverse(model, data, theta_rad, omega_rad_s, alpha_rad_s2):
    """Joint torques from ``mj_inverse`` at one state."""
    import mujoco

    data.qpos[:] = theta_rad
    data.qvel[:] = omega_rad_s
    data.qacc[:] = alpha_rad_s2
    mujoco.mj_inverse(model, data)
    return data.qfrc_inverse.copy()
