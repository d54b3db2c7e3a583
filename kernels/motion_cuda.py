r"""The batched RK4 of :mod:`kernels.motion_rk4` as a CUDA kernel: one thread per robot.

The device functions are the very Python functions of :func:`kernels.motion_rk4.scale_row`,
:func:`kernels.rk4.rk4_step` and :func:`kernels.aba_planar.forward_dynamics_rows_auto` (the
NOC :func:`kernels.dynamics._forward_dynamics_rows` for short chains, the O(n)
:func:`kernels.aba_planar.aba_rows` from :data:`~kernels.aba_planar.ABA_MIN_LINKS` links on: a
long chain needs no (n, n) matrix per robot), compiled
for the GPU (their globals rebound to the device versions), so the GPU runs the same
algorithm: thread s scales design row s into its parameters (on the GPU: only the unit
design crosses the bus, not the (S, 3, n) parameters), then takes ``n_steps`` RK4 steps.
Work arrays are slices of per-robot device arrays. Importing this module imports
``numba.cuda`` (``numba-cuda``, the ``cuda`` extra); ``NUMBA_ENABLE_CUDASIM=1`` before that
import runs it on numba's CUDA simulator (the tests do).
"""

import types

from numba import cuda

from . import aba_planar, dynamics, motion_rk4, rk4


def _device(dispatcher, **rebind):
    """A CUDA device function compiled from ``dispatcher``'s Python function, with the
    globals named in ``rebind`` replaced (calls to other kernels -> their device versions)."""
    function = dispatcher.py_func
    scope = dict(function.__globals__)
    scope.update(rebind)
    clone = types.FunctionType(
        function.__code__, scope, function.__name__, function.__defaults__, function.__closure__
    )
    return cuda.jit(device=True)(clone)


_forward_dynamics_rows = _device(dynamics._forward_dynamics_rows)
_aba_rows = _device(aba_planar.aba_rows)
_forward_dynamics_rows_auto = _device(
    aba_planar.forward_dynamics_rows_auto,
    aba_rows=_aba_rows,
    _forward_dynamics_rows=_forward_dynamics_rows,
)
_rk4_step = _device(rk4.rk4_step, forward_dynamics_rows_auto=_forward_dynamics_rows_auto)
_scale_row = _device(motion_rk4.scale_row)


@cuda.jit
def _make_parameters(unit, lower, upper, inertias_kgm2, rod_inertias, params):
    s = cuda.grid(1)
    if s < unit.shape[0]:
        _scale_row(unit, s, lower, upper, inertias_kgm2, rod_inertias, params[s])


@cuda.jit
def _advance(
    params, gravity_m_s2, torque_Nm, theta_rad, omega_rad_s, step_s, n_steps, scratch, matrix
):
    s = cuda.grid(1)
    if s < params.shape[0]:
        p = params[s]
        work = scratch[s, 0:9]  # kernels.aba_planar.ABA_WORK_ROWS (the NOC path uses 6)
        d_theta = scratch[s, 9:13]
        d_omega = scratch[s, 13:17]
        theta = scratch[s, 17]
        omega = scratch[s, 18]
        for _ in range(n_steps):
            _rk4_step(
                p[0],
                p[1],
                p[2],
                gravity_m_s2,
                torque_Nm,
                theta_rad[s],
                omega_rad_s[s],
                step_s,
                work,
                matrix[s],
                d_theta,
                d_omega,
                theta,
                omega,
            )


#: Threads per block.
THREADS = 128


class CudaBatch:
    """S robots on the GPU: parameters made from the unit design there, states kept there.

    ``CudaBatch(unit, lower, upper, inertias_kgm2, rod_inertias, theta0, omega0, gravity,
    torque)``, then :meth:`advance` in chunks and :meth:`angles` to copy θ (S, n) back.
    """

    def __init__(
        self,
        unit,
        lower,
        upper,
        inertias_kgm2,
        rod_inertias,
        theta_rad,
        omega_rad_s,
        gravity_m_s2,
        torque_Nm,
    ):
        import numpy as np

        samples = unit.shape[0]
        n = inertias_kgm2.shape[0]
        self.samples = samples
        self.blocks = (samples + THREADS - 1) // THREADS
        self.gravity_m_s2 = float(gravity_m_s2)
        self.params = cuda.device_array((samples, 3, n))
        self.torque = cuda.to_device(np.ascontiguousarray(torque_Nm, dtype=np.float64))
        self.theta = cuda.to_device(np.ascontiguousarray(theta_rad, dtype=np.float64))
        self.omega = cuda.to_device(np.ascontiguousarray(omega_rad_s, dtype=np.float64))
        self.scratch = cuda.device_array((samples, 19, n))
        size = 1 if n >= aba_planar.ABA_MIN_LINKS else n  # the O(n) path needs no matrix
        self.matrix = cuda.device_array((samples, size, size))
        if samples:
            _make_parameters[self.blocks, THREADS](
                cuda.to_device(np.ascontiguousarray(unit, dtype=np.float64)),
                cuda.to_device(np.ascontiguousarray(lower, dtype=np.float64)),
                cuda.to_device(np.ascontiguousarray(upper, dtype=np.float64)),
                cuda.to_device(np.ascontiguousarray(inertias_kgm2, dtype=np.float64)),
                cuda.to_device(np.ascontiguousarray(rod_inertias, dtype=np.bool_)),
                self.params,
            )

    def advance(self, step_s: float, n_steps: int) -> None:
        """Take ``n_steps`` RK4 steps of every robot (waits for the GPU)."""
        if self.samples and n_steps:
            _advance[self.blocks, THREADS](
                self.params,
                self.gravity_m_s2,
                self.torque,
                self.theta,
                self.omega,
                float(step_s),
                int(n_steps),
                self.scratch,
                self.matrix,
            )
            cuda.synchronize()

    def angles(self):
        """The relative joint angles (S, n) now, on the host."""
        return self.theta.copy_to_host()

    def parameters(self):
        """The robots' (S, 3, n) lengths, masses, inertias, on the host."""
        return self.params.copy_to_host()


def usable() -> str | None:
    """``None`` when a CUDA GPU can run kernels (or numba's CUDA simulator is on), else why
    not (one line)."""
    from numba import config

    if config.ENABLE_CUDASIM:
        return None
    try:
        if not cuda.is_available():
            return "no usable CUDA GPU (numba.cuda.is_available() is false)"
        cuda.get_current_device()
    except Exception as error:  # driver, runtime or device errors all mean "not usable"
        return f"no usable CUDA GPU ({str(error).splitlines()[0] if str(error) else type(error).__name__})"
    return None
