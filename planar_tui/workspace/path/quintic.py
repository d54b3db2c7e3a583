r"""The quintic rest-to-rest path: :math:`X(t) = X_0 + (X_1 - X_0)\,s(\tau)`,
:math:`\tau = t/T`, :math:`s = 10\tau^3 - 15\tau^4 + 6\tau^5` (zero rate and acceleration
at both ends), with its rate :math:`\dot X = (X_1 - X_0)\,s'(\tau)/T` and acceleration
:math:`\ddot X = (X_1 - X_0)\,s''(\tau)/T^2`, analytic."""

from __future__ import annotations

from typing import Any


def quintic(start: Any, stop: Any, duration_s: float, times_s: Any) -> tuple[Any, Any, Any]:
    """``(pose, rate, acceleration)`` at ``times_s`` (n,), each (n, d) for ``start``,
    ``stop`` (d,) in SI units; times outside ``[0, T]`` are held at the ends."""
    import numpy as np

    tau = np.clip(np.asarray(times_s, dtype=np.float64) / duration_s, 0.0, 1.0)[:, None]
    delta = np.asarray(stop, dtype=np.float64) - np.asarray(start, dtype=np.float64)
    s = tau**3 * (10.0 - 15.0 * tau + 6.0 * tau**2)
    ds = 30.0 * tau**2 * (1.0 - tau) ** 2
    dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau)
    pose = np.asarray(start, dtype=np.float64) + delta * s
    return pose, delta * ds / duration_s, delta * dds / duration_s**2


def sample_times(duration_s: float, steps: int) -> Any:
    """The ``steps + 1`` times :math:`t_k = kT/\\text{steps}`."""
    import numpy as np

    return np.arange(steps + 1, dtype=np.float64) * (duration_s / steps)
