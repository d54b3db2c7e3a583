"""MJCF builder: the n-link planar serial revolute robot as a MuJoCo model.

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


def chain_mjcf(lengths_m, masses_kg, inertias_kgm2, gravity_m_s2=9.81, timestep_s=1e-4):
    """MJCF text of the planar chain (RK4 integrator, contacts disabled)."""
    lengths_m = np.asarray(lengths_m, dtype=float)
    bodies_open = []
    for i, (length, mass, inertia) in enumerate(
        zip(lengths_m, masses_kg, inertias_kgm2, strict=True)
    ):
        offset = 0.0 if i == 0 else lengths_m[i - 1]
        bodies_open.append(
            f'<body name="link{i + 1}" pos="{offset:.17g} 0 0">'
            f'<joint name="joint{i + 1}" type="hinge" axis="0 0 1" pos="0 0 0"'
            ' damping="0" armature="0" frictionloss="0"/>'
            f'<inertial pos="{0.5 * length:.17g} 0 0" mass="{mass:.17g}"'
            f' diaginertia="{AXIAL_INERTIA_KGM2:.17g} {inertia:.17g} {inertia:.17g}"/>'
        )
    chain = "".join(bodies_open) + "</body>" * len(bodies_open)
    return (
        '<mujoco model="planar-chain">'
        '<compiler angle="radian" inertiafromgeom="false"/>'
        f'<option gravity="0 {-gravity_m_s2:.17g} 0" integrator="RK4" timestep="{timestep_s:.17g}">'
        '<flag contact="disable"/>'
        "</option>"
        f"<worldbody>{chain}</worldbody>"
        "</mujoco>"
    )


def chain_model(lengths_m, masses_kg, inertias_kgm2, gravity_m_s2=9.81, timestep_s=1e-4):
    """Compiled ``(mujoco.MjModel, mujoco.MjData)`` of :func:`chain_mjcf`."""
    import mujoco

    model = mujoco.MjModel.from_xml_string(
        chain_mjcf(lengths_m, masses_kg, inertias_kgm2, gravity_m_s2, timestep_s)
    )
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
