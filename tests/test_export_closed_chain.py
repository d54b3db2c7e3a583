"""The closed-chain export (``export --robot robot3rrr|robot5r --format mjcf``) in the
real engines, against an independent Lagrange model (:mod:`tests.closed_chain_reference`:
body coordinates, the KKT system in numpy, its own inverse kinematics).

* MuJoCo loads both files; the keyframe ``home`` closes every loop (the connect
  constraints' residual is rounding) and is the reference's assembly of that pose.
* MuJoCo's rigid dynamics: along a path, with gravity, ``M q'' + c - S tau`` lies in the
  span of the loop Jacobian's rows (the reference's torques are the file's).
* MuJoCo's forward simulation driven by the reference's torques follows the path within
  the soft equality constraints' error (a horizontal machine: with gravity, open-loop
  feed-forward of a hanging leg diverges like an inverted pendulum, whatever the model);
  stiffening ``solimp`` and the step shrinks the error, so it is the softness.
* Pinocchio parses the same file (its loops as ``CONTACT_3D`` rigid constraint models) and
  ``constraintDynamics`` given the torques returns the path's accelerations to 1e-8.
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import mujoco
import numpy as np
import pinocchio
import pytest

from planar_tui.workspace.fivebar import dynamics as fivebar_dynamics
from planar_tui.workspace.fivebar.robot import Robot5R
from planar_tui.workspace.rrr import dynamics as rrr_dynamics
from planar_tui.workspace.rrr.robot import Robot3RRR
from tests.closed_chain_reference import Machine, quintic
from tests.test_interop_cli import one_error_line

SQRT3 = math.sqrt(3.0)
MASSES_3RRR = {
    "proximal_mass_kg": 0.6,
    "distal_mass_kg": 0.4,
    "platform_mass_kg": 1.5,
    "proximal_inertia_kgm2": 0.005,
    "distal_inertia_kgm2": 0.003,
    "platform_inertia_kgm2": 0.02,
}
MASSES_5R = {
    "proximal_mass_kg": 0.7,
    "distal_mass_kg": 0.5,
    "end_mass_kg": 0.8,
    "proximal_inertia_kgm2": 0.012,
    "distal_inertia_kgm2": 0.013,
}
#: The path's duration (s) and the pose it moves by from home (m, m, rad).
DURATION_S = 1.0
#: (nq, loops, motors) of each export: 2 hinges a leg, and the end body's slides (hinge).
SIZES = {"robot3rrr": (9, 3, 3), "robot5r": (6, 2, 2)}
MOVES = {"robot3rrr": (0.04, 0.03, math.radians(10.0)), "robot5r": (0.05, -0.04, 0.0)}


def preset_text(table: str, gravity: float, masses: bool = True) -> str:
    keys = (MASSES_3RRR if table == "robot3rrr" else MASSES_5R) if masses else {}
    lines = [f"[{table}]", f"gravity_m_s2 = {gravity!r}"]
    lines += [f"{key} = {value!r}" for key, value in keys.items()]
    if table == "robot3rrr":
        lines += ["base_side_cm = 120", "platform_side_cm = 40", "proximal_cm = 30"]
        lines += ["distal_cm = 30"]
    else:
        lines += ["base_separation_cm = 40", "proximal_cm = [45, 45]", "distal_cm = [55, 55]"]
    return "\n".join(lines) + "\n"


def machine(table: str, gravity: float) -> Machine:
    """The reference model of the preset (paper B's layout; the five-bar's A = (∓d/2, 0))."""
    if table == "robot3rrr":
        a, b, m = 1.2, 0.4, MASSES_3RRR
        return Machine(
            np.array([[0.0, 0.0], [a, 0.0], [a / 2, a * SQRT3 / 2]]),
            0.3,
            0.3,
            (1, -1, 1),
            np.array([[0.0, 0.0], [b, 0.0], [b / 2, b]]),
            m["proximal_mass_kg"],
            m["proximal_inertia_kgm2"],
            m["distal_mass_kg"],
            m["distal_inertia_kgm2"],
            m["platform_mass_kg"],
            m["platform_inertia_kgm2"],
            gravity,
            True,
        )
    m = MASSES_5R
    return Machine(
        np.array([[-0.2, 0.0], [0.2, 0.0]]),
        0.45,
        0.55,
        (1, -1),
        np.zeros((2, 2)),
        m["proximal_mass_kg"],
        m["proximal_inertia_kgm2"],
        m["distal_mass_kg"],
        m["distal_inertia_kgm2"],
        m["end_mass_kg"],
        0.0,
        gravity,
        False,
    )


def home_pose(table: str) -> np.ndarray:
    """The documented home pose: the 3-RRR's platform centroid over the base centroid at
    phi = 0; the five-bar's P at x = 0 with leg 1 at sqrt(l1^2 + l2^2) from A1."""
    if table == "robot3rrr":
        return np.array([0.6 - 0.2, 1.2 * SQRT3 / 6 - 0.4 / 3, 0.0])
    return np.array([0.0, math.sqrt(0.45**2 + 0.55**2 - 0.2**2), 0.0])


def planar_tui_robot(table: str, gravity: float):
    """The preset's robot as planar-tui parses it (the defaults are the test's layout)."""
    if table == "robot3rrr":
        return Robot3RRR(**MASSES_3RRR, gravity_m_s2=gravity)
    return Robot5R(**MASSES_5R, gravity_m_s2=gravity)


class Path:
    """The quintic from home: the reference's tree coordinates and torques at t, and
    planar-tui's efforts (its path inverse dynamics) at t."""

    def __init__(self, table: str, gravity: float):
        self.machine = machine(table, gravity)
        self.start = home_pose(table)
        self.stop = self.start + np.array(MOVES[table])
        self.robot = planar_tui_robot(table, gravity)
        self.dynamics = rrr_dynamics if table == "robot3rrr" else fivebar_dynamics
        self.mode = SimpleNamespace(elbow=self.machine.elbows, limits_rad=None)

    def at(self, t: float):
        z, zd, zdd = self.machine.state(*quintic(self.start, self.stop, DURATION_S, t))
        return self.machine.tree(z, zd, zdd), self.machine.torques(z, zd, zdd)

    def efforts(self, t: float) -> np.ndarray:
        used = 3 if self.machine.rotates else 2
        states = (value[None, :used] for value in quintic(self.start, self.stop, DURATION_S, t))
        solution = self.dynamics.solve_path(self.robot, self.mode, *states)
        assert solution.status[0] == 0
        return solution.effort[0]


@pytest.fixture
def exported(cli, tmp_path):
    """``export(table, gravity, masses=True)``: the MJCF file ``export`` writes."""

    def export(table: str, gravity: float, masses: bool = True):
        preset = tmp_path / f"{table}-{gravity}.toml"
        preset.write_text(preset_text(table, gravity, masses))
        out = tmp_path / f"{table}-{gravity}.xml"
        result = cli("export", preset, "--robot", table, "--format", "mjcf", "--out", out)
        assert result.exit_code == 0, result.output
        return out

    return export


def loop_residual_m(model, data) -> float:
    mujoco.mj_forward(model, data)
    return float(np.abs(data.efc_pos[: data.ne]).max())


@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
@pytest.mark.parametrize("masses", [True, False])
def test_home_keyframe_closes_the_loops(exported, table, masses):
    model = mujoco.MjModel.from_xml_path(str(exported(table, 9.81, masses)))
    assert (model.nq, model.neq, model.nu) == SIZES[table]
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    assert loop_residual_m(model, data) < 1e-14
    (q, _, _), _ = Path(table, 9.81).at(0.0)
    np.testing.assert_allclose(data.qpos, q, rtol=0, atol=1e-12)
    mujoco.mj_resetData(model, data)  # qpos0 is not assembled: the check can fail
    assert loop_residual_m(model, data) > 0.01


@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
def test_planar_tui_efforts_are_the_reference(table):
    """planar-tui's path inverse dynamics (NOC kernels) against the Lagrange reference."""
    path = Path(table, 9.81)
    for t in np.linspace(0.0, DURATION_S, 11):
        reference = path.at(t)[1]
        np.testing.assert_allclose(
            path.efforts(t), reference, rtol=0, atol=1e-8 * np.abs(reference).max()
        )


@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
def test_mujoco_rigid_dynamics_are_the_reference(exported, table):
    """With gravity: the reference's torques make ``M q'' + c`` a loop reaction."""
    model = mujoco.MjModel.from_xml_path(str(exported(table, 9.81)))
    model.opt.jacobian = mujoco.mjtJacobian.mjJAC_DENSE
    data = mujoco.MjData(model)
    path = Path(table, 9.81)
    full = np.zeros((model.nv, model.nv))
    motors = np.zeros((model.nv, model.nu))  # each motor's gear on its joint's dof
    motors[model.jnt_dofadr[model.actuator_trnid[:, 0]], range(model.nu)] = model.actuator_gear[
        :, 0
    ]
    for t in np.linspace(0.0, DURATION_S, 7):
        (q, v, a), tau = path.at(t)
        data.qpos[:], data.qvel[:] = q, v
        mujoco.mj_forward(model, data)
        mujoco.mj_fullM(model, data, full)
        generalised = full @ a + data.qfrc_bias - motors @ tau
        loops = data.efc_J.reshape(-1, model.nv)[: data.ne]
        reaction = np.linalg.lstsq(loops.T, generalised, rcond=None)[0]
        scale = np.abs(full @ a + data.qfrc_bias).max()
        assert np.abs(loops.T @ reaction - generalised).max() < 1e-10 * scale


def follow(model, path: Path) -> tuple[float, float]:
    """Drive the model from the path's start with planar-tui's efforts (held over each
    step); the largest platform position error (m) and loop residual (m) at the steps."""
    data = mujoco.MjData(model)
    (data.qpos[:], _, _), _ = path.at(0.0)
    legs = 2 * model.nu
    position, loop = 0.0, 0.0
    steps = round(DURATION_S / model.opt.timestep)
    for step in range(steps + 1):
        (q, _, _), _ = path.at(min(data.time, DURATION_S))
        mujoco.mj_forward(model, data)
        error = np.abs(data.qpos[legs : legs + 2] - q[legs : legs + 2]).max()
        position = max(position, float(error))
        loop = max(loop, float(np.abs(data.efc_pos[: data.ne]).max()))
        if step < steps:
            data.ctrl[:] = path.efforts(data.time)
            mujoco.mj_step(model, data)
    return position, loop


@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
def test_mujoco_follows_the_path_within_its_softness(exported, table):
    """The file as written (2 ms Euler steps, MuJoCo's default solref/solimp): within
    1 mm of the path (a 50 or 64 mm move; measured: 3-RRR 0.59 mm, five-bar 0.012 mm),
    the loops open by less than 1 cm (measured 8.4 mm and 0.025 mm)."""
    model = mujoco.MjModel.from_xml_path(str(exported(table, 0.0)))
    position, loop = follow(model, Path(table, 0.0))
    print(f"{table}: default softness, {position * 1e3:.3g} mm off, loops {loop * 1e3:.3g} mm")
    assert position < 1e-3
    assert loop < 1e-2


@pytest.mark.slow
@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
def test_stiffer_constraints_follow_closer(exported, table):
    """The error is the softness: with solimp 0.999-0.9999 and 0.5 ms steps the platform
    stays within 5 µm of the path (measured: 3-RRR 1.3 µm, five-bar 0.8 µm)."""
    model = mujoco.MjModel.from_xml_path(str(exported(table, 0.0)))
    model.eq_solimp[:, :3] = (0.999, 0.9999, 0.001)
    model.opt.timestep = 5e-4
    position, loop = follow(model, Path(table, 0.0))
    print(f"{table}: stiff, {position * 1e6:.3g} um off, loops {loop * 1e6:.3g} um")
    assert position < 5e-6
    assert loop < 1e-3


@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
def test_pinocchio_constraint_dynamics_returns_the_path(exported, table):
    """Pinocchio reads the loops as CONTACT_3D rigid constraints (their z rows are zero in
    a planar motion: the proximal solver's mu > 0 handles the redundancy)."""
    model, constraints = pinocchio.buildModelAndLegacyConstraintsFromMJCF(
        str(exported(table, 9.81))
    )
    assert [c.type for c in constraints] == [pinocchio.ContactType.CONTACT_3D] * SIZES[table][1]
    model.gravity.linear = np.array([0.0, -9.81, 0.0])  # MJCF's <option> is not read
    data = pinocchio.Data(model)
    datas = pinocchio.StdVec_RigidConstraintData()
    for constraint in constraints:
        datas.append(constraint.createData())
    settings = pinocchio.ProximalSettings(1e-14, 1e-10, 100)
    path = Path(table, 9.81)
    actuated = np.arange(0, 2 * len(constraints), 2)
    for t in np.linspace(0.0, DURATION_S, 11):
        (q, v, a), _ = path.at(t)
        efforts = np.zeros(model.nv)
        efforts[actuated] = path.efforts(t)
        pinocchio.initConstraintDynamics(model, data, constraints, datas)
        result = pinocchio.constraintDynamics(
            model, data, q, v, efforts, constraints, datas, settings
        )
        assert np.abs(result - a).max() <= 1e-8 * max(np.abs(a).max(), 1.0)


@pytest.mark.parametrize(
    ("table", "arguments", "expected"),
    [
        (
            "robot3rrr",
            ("--robot", "robot3rrr", "--format", "urdf"),
            "error: command line: --format: is 'urdf': URDF has no closed loops and "
            "[robot3rrr] is a closed chain (expected mjcf",
        ),
        (
            "robot3rrr",
            ("--robot", "robot5r", "--format", "mjcf"),
            "[robot5r]: missing (expected a [robot5r] table",
        ),
        (
            "robot5r",
            ("--robot", "robot5r", "--format", "step"),
            "error: command line: --format: is 'step' (expected mjcf or urdf)",
        ),
    ],
)
def test_bad_closed_chain_exports_are_one_line(cli, tmp_path, table, arguments, expected):
    preset = tmp_path / "robot.toml"
    preset.write_text(preset_text(table, 9.81))
    result = cli("export", preset, *arguments, "--out", tmp_path / "robot.out")
    assert expected in one_error_line(result)
    assert sorted(path.name for path in tmp_path.iterdir()) == ["robot.toml"]


def test_a_home_pose_out_of_reach_is_one_line(cli, tmp_path):
    preset = tmp_path / "short.toml"
    preset.write_text("[robot3rrr]\nproximal_cm = 5\ndistal_cm = 5\n")
    result = cli(
        "export", preset, "--robot", "robot3rrr", "--format", "mjcf", "--out", tmp_path / "x.xml"
    )
    assert "[robot3rrr]: leg 1 cannot reach the home pose" in one_error_line(result)


@pytest.mark.parametrize("table", ["robot3rrr", "robot5r"])
def test_importing_a_closed_chain_is_refused(cli, exported, table):
    model = exported(table, 9.81)
    line = one_error_line(cli("import", model))
    assert "<equality>: closed loops or couplings are not a serial chain" in line


def test_the_home_keyframe_is_the_path_jobs_start(cli, tmp_path):
    """A preset with a path job exports its start: ``from_pose`` in the job's ``elbow``."""
    out = tmp_path / "path.xml"
    result = cli("export", "path-3rrr", "--robot", "robot3rrr", "--format", "mjcf", "--out", out)
    assert result.exit_code == 0, result.output
    model = mujoco.MjModel.from_xml_path(str(out))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    assert loop_residual_m(model, data) < 1e-14
    start = np.array([0.36, 0.05, math.radians(-2.0)])  # the preset's from_pose = [36, 5, -2]
    reference = replace(machine("robot3rrr", 9.81), elbows=(1, -1, -1))
    (q, _, _) = reference.tree(*reference.state(start, np.zeros(3), np.zeros(3)))
    np.testing.assert_allclose(data.qpos, q, rtol=0, atol=1e-12)


def test_a_five_bar_exports_in_its_working_mode(tmp_path, cli):
    preset = tmp_path / "mode.toml"
    preset.write_text(preset_text("robot5r", 0.0) + 'working_mode = "-+"\n')
    out = tmp_path / "mode.xml"
    result = cli("export", preset, "--robot", "robot5r", "--format", "mjcf", "--out", out)
    assert result.exit_code == 0, result.output
    model = mujoco.MjModel.from_xml_path(str(out))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    assert loop_residual_m(model, data) < 1e-14
    reference = replace(machine("robot5r", 0.0), elbows=(-1, 1))
    (q, _, _) = reference.tree(*reference.state(home_pose("robot5r"), np.zeros(3), np.zeros(3)))
    np.testing.assert_allclose(data.qpos, q, rtol=0, atol=1e-12)
