r"""Source of the fused lane kernel for chains of ``n`` links (:func:`fused_source`).

The general lane kernel (:mod:`kernels.motion_lanes`) runs every loop of the algorithm with
an innermost loop over the lanes, so every intermediate (link vectors, mass-matrix entries,
running sums) goes through memory arrays over the block's robots: about 95 short lane loops
per forward dynamics, each with its set-up and run-time alias checks, and a working set of
about 160 kB per 128-lane block (the L2 cache, not L1). With ``n`` fixed, the forward
dynamics of one robot is straight-line code; written as **one** loop over the lanes whose
body is that code (every link, every mass-matrix entry a scalar), LLVM vectorises the loop as
a whole: nothing but the state, the stage point, the RK4 sums and the parameters touches
memory, and the intermediates live in vector registers (spills go to the stack, in L1). The
step runs one such loop per RK4 stage (the stage point and the weighted sums kept in rows of
the block's state), not one loop with the four forward dynamics inlined: the same run time
(measured), a quarter of the code to compile (about 11 s of CPU instead of 56 s on the
project's machine).

Numba has no compile-time integers, so the unrolled code is generated here as Python source,
once, and checked in (``kernels/motion_lanes_n6.py`` for the 6-link chain of paper A's Table
1; ``tests/test_motion_lanes.py`` checks that the checked-in file is this function's output).
Regenerate after a change with::

    python -c "from planar_tui.kernels.motion_lanes_codegen import fused_source; \
print(fused_source(6, 128), end='')" > kernels/motion_lanes_n6.py

The statements are those of :func:`kernels.motion_lanes._noc_lanes` and
:func:`kernels.motion_lanes.rk4_step_lanes` (which are the scalar kernels'), in the same
order, link by link; only the names change.
"""


def _forward_dynamics(n: int) -> list[str]:
    """Body of ``_fd``: NOC mass matrix + ``LDLᵀ`` of :func:`kernels.motion_lanes._noc_lanes`."""
    lines = [
        *(
            f"length{i}, mass{i}, inertia{i}, tau{i}, q{i}, w{i} = "
            f"length[{i}], mass[{i}], inertia[{i}], tau[{i}], q[{i}], w[{i}]"
            for i in range(n)
        ),
        "beyond = 0",
        "phi = 0.0",
        "rate = 0.0",
        "acc_x = 0.0",
        "acc_y = gravity_m_s2",
        "px = 0.0",
        "py = 0.0",
    ]
    for i in range(n):
        lines += [
            f"phi = phi + q{i}",
            "s, c = sincos(phi)",
            "beyond += abs(phi) > SINCOS_MAX_ABS",
            f"rate = rate + w{i}",
            f"ax{i} = length{i} * c",
            f"ay{i} = length{i} * s",
            "rate_sq = rate * rate",
            f"px{i} = px",
            f"py{i} = py",
            f"fx{i} = mass{i} * (acc_x - 0.5 * rate_sq * ax{i})",
            f"fy{i} = mass{i} * (acc_y - 0.5 * rate_sq * ay{i})",
            f"acc_x -= rate_sq * ax{i}",
            f"acc_y -= rate_sq * ay{i}",
            f"px += ax{i}",
            f"py += ay{i}",
        ]
    lines += [
        "big_fx = 0.0",
        "big_fy = 0.0",
        "bias = 0.0",
        "outer_mass = 0.0",
        "hx = 0.0",
        "hy = 0.0",
        "diagonal = 0.0",
    ]
    for k in range(n - 1, -1, -1):
        lines += [
            f"bias += 0.5 * (ax{k} * fy{k} - ay{k} * fx{k}) + ax{k} * big_fy - ay{k} * big_fx",
            f"big_fx += fx{k}",
            f"big_fy += fy{k}",
            f"alpha{k} = tau{k} - bias",
            f"diagonal += (2.0 * (ax{k} * hx + ay{k} * hy)"
            f" + (outer_mass + 0.25 * mass{k}) * length{k} * length{k} + inertia{k})",
            f"hx += (outer_mass + 0.5 * mass{k}) * ax{k}",
            f"hy += (outer_mass + 0.5 * mass{k}) * ay{k}",
            f"outer_mass += mass{k}",
            f"m{k}_{k} = diagonal",
        ]
        lines += [
            f"m{k}_{j} = diagonal + (px{k} - px{j}) * hx + (py{k} - py{j}) * hy" for j in range(k)
        ]
    for i in range(n):
        for j in range(i):
            lines += [f"m{i}_{j} -= m{i}_{k} * m{j}_{k}" for k in range(j)]
        lines += [f"d = m{i}_{i}", f"y = alpha{i}"]
        for k in range(i):
            lines += [
                f"l_ik = m{i}_{k} * m{k}_{k}",
                f"d -= l_ik * m{i}_{k}",
                f"y -= m{i}_{k} * alpha{k}",
                f"m{i}_{k} = l_ik",
            ]
        lines += ["inv = 1.0 / d", f"m{i}_{i} = inv", f"alpha{i} = y * inv"]
    for i in range(n - 1, -1, -1):
        lines += [f"alpha{k} -= m{i}_{k} * alpha{i}" for k in range(i)]
    return [*lines, f"return ({', '.join(f'alpha{i}' for i in range(n))},), beyond"]


def _tuple(n: int, item: str) -> str:
    """``(item(0), item(1), ...)`` with ``{i}`` in ``item`` the link."""
    return "(" + ", ".join(item.format(i=i) for i in range(n)) + ",)"


def _rows(n: int, group: int) -> str:
    """Row offset of link ``{i}`` of the state's ``group``-th group of ``n`` rows."""
    return f"({group * n} + {{i}}) * LANES + lane" if group else "{i} * LANES + lane"


def _stage(n: int) -> list[str]:
    """Body of the lane loop of one RK4 stage of ``rk4_step_{n}``
    (:func:`kernels.motion_lanes.rk4_step_lanes`): the forward dynamics at the stage point,
    its rates and accelerations added to the weighted sums, the next stage point."""
    angle, rate, point_angle, point_rate, sum_rate, sum_acc = (_rows(n, g) for g in range(6))
    lines = [
        f"length = {_tuple(n, 'params[{i} * LANES + lane]')}",
        f"mass = {_tuple(n, f'params[({n} + {{i}}) * LANES + lane]')}",
        f"inertia = {_tuple(n, f'params[({2 * n} + {{i}}) * LANES + lane]')}",
        f"v = {_tuple(n, f'state[{point_rate}]')}",
        f"a, b = _fd(length, mass, inertia, tau, gravity_m_s2, {_tuple(n, f'state[{point_angle}]')}, v)",
        "beyond += b",
    ]
    for i in range(n):
        lines += [
            f"state[{sum_rate}] += weight * v[{{i}}]".format(i=i),
            f"state[{sum_acc}] += weight * a[{{i}}]".format(i=i),
            f"state[{point_angle}] = state[{angle}] + factor * v[{{i}}]".format(i=i),
            f"state[{point_rate}] = state[{rate}] + factor * a[{{i}}]".format(i=i),
        ]
    return lines


def _start(n: int) -> list[str]:
    """Body of the lane loop before the stages: the first stage point is the state, the
    sums are zero."""
    angle, rate, point_angle, point_rate, sum_rate, sum_acc = (_rows(n, g) for g in range(6))
    lines = []
    for i in range(n):
        lines += [
            f"state[{point_angle}] = state[{angle}]".format(i=i),
            f"state[{point_rate}] = state[{rate}]".format(i=i),
            f"state[{sum_rate}] = 0.0".format(i=i),
            f"state[{sum_acc}] = 0.0".format(i=i),
        ]
    return lines


def _update(n: int) -> list[str]:
    """Body of the lane loop after the stages: the state advanced by ``h/6`` times the sums."""
    angle, rate, _, _, sum_rate, sum_acc = (_rows(n, g) for g in range(6))
    lines = []
    for i in range(n):
        lines += [
            f"state[{angle}] += sixth * state[{sum_rate}]".format(i=i),
            f"state[{rate}] += sixth * state[{sum_acc}]".format(i=i),
        ]
    return lines


def fused_source(n: int, lanes: int) -> str:
    """Python source of the module ``kernels/motion_lanes_n{n}.py`` (module docstring)."""
    fd = "\n".join("    " + line for line in _forward_dynamics(n))
    start = "\n".join("        " + line for line in _start(n))
    stage, update = ("\n".join("            " + line for line in f(n)) for f in (_stage, _update))
    return f'''# ruff: noqa
# fmt: off
"""Fused lane kernel of the {n}-link chain: GENERATED by
:func:`kernels.motion_lanes_codegen.fused_source` ({n}, {lanes}); do not edit, regenerate."""

from ._jit import kernel
from .lane_trig import SINCOS_MAX_ABS, sincos

#: Lanes of the block (:data:`kernels.motion_lanes.LANES`, tested equal).
LANES = {lanes}
#: Rows of :func:`rk4_step_{n}`'s state.
STATE_ROWS = {6 * n}


@kernel(inline=True)
def _fd(length, mass, inertia, tau, gravity_m_s2, q, w):
    """Joint accelerations of one robot (tuples of its {n} links) and how many of its absolute
    angles are past :data:`~kernels.lane_trig.SINCOS_MAX_ABS`: the statements of
    :func:`kernels.motion_lanes._noc_lanes` for one lane, unrolled."""
{fd}


@kernel(fma=True)
def rk4_step_{n}(params, gravity_m_s2, tau_Nm, state, step_s):
    """One RK4 step of the block (:func:`kernels.motion_lanes.rk4_step_lanes`, unrolled) in
    place on the angles and rates x of ``state``, stage by stage: k_s = f(x + c_s h k_(s-1)),
    S = sum of b_s k_s, x + h/6 S, with c = (0, 1/2, 1/2, 1) and b = (1, 2, 2, 1) (the sums in
    the general step's order, the same doubles up to FMA contraction), in
    one loop over the lanes per stage, whose body is the forward dynamics of one robot.
    ``params`` (3·{n}·LANES); ``state`` (STATE_ROWS·LANES): rows of the angles, the rates,
    the stage point's angles and rates, the sums of the stage rates and accelerations
    ({n} rows each). Returns the number of angles past
    :data:`~kernels.lane_trig.SINCOS_MAX_ABS`; then the angles and rates are left as they
    were (the caller redoes the step with the general kernel)."""
    half = 0.5 * step_s
    sixth = step_s / 6.0
    tau = {_tuple(n, "tau_Nm[{i}]")}
    for lane in range(LANES):
{start}
    beyond = 0
    for stage in range(4):
        factor = step_s if stage == 2 else half  # c of the next stage
        weight = 2.0 if stage == 1 or stage == 2 else 1.0  # b of this one
        for lane in range(LANES):
{stage}
    if beyond == 0:
        for lane in range(LANES):
{update}
    return beyond
'''
