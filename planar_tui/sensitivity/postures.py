r"""Postures of the sensitivity study: singular, isotropic (minimum condition number), explicit.

The isotropic posture minimises the condition number :math:`\kappa = \sigma_{max}/\sigma_{min}`
of the manipulator Jacobian (Angeles, *Fundamentals of Robotic Mechanical Systems*, 4th ed.,
pp. 306-317, paper A ref. [19]):

* 2R: the 2×2 positional Jacobian, columns :math:`E(p - o_i)`; it is isotropic
  (:math:`\kappa = 1`) iff :math:`l_2 = l_1/\sqrt2` and :math:`\theta_2 = \pm 135°`.
* n ≥ 3: the 3×n Jacobian with the orientation row, columns
  :math:`[1;\ E(p - o_i)/L]`, with the characteristic length L a design variable optimised
  with the angles. For 3R, :math:`JJ^T = 3I` forces the joint centres to be an equilateral
  triangle with the end point at its centroid: :math:`l_1 = l_2 = \sqrt3\,l_3`,
  :math:`\theta_2 = \pm120°`, :math:`\theta_3 = \pm150°`, :math:`L = l_3/\sqrt2`.

:math:`\kappa` does not depend on :math:`\theta_1`; it is set to 0 (the robot's first link
horizontal) and, of the two mirror-image solutions, the one with :math:`\theta_2 > 0` is
returned (it is the one that reproduces paper A's Tables 4-5, see ``docs/sensitivity.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from planar_tui.sensitivity.optimise import levenberg_marquardt, nelder_mead


@dataclass(frozen=True)
class Posture:
    """A posture of the study: its label, relative joint angles and Jacobian conditioning.

    ``condition_number`` is :math:`\\kappa` of the Jacobian used to judge isotropy (the
    positional one for 2R, the one with orientation row and ``characteristic_length_m``
    for n ≥ 3).
    """

    label: str
    theta_rad: tuple[float, ...]
    condition_number: float
    characteristic_length_m: float | None = None


class NoIsotropicPosture(ValueError):
    """The robot's minimum condition number is above 1 + tolerance."""


def jacobian(lengths_m, theta_rad, characteristic_length_m: float | None = None) -> np.ndarray:
    r"""Manipulator Jacobian of the end point of an n-link planar chain.

    Column i is :math:`E(p - o_i)` (2 rows) when ``characteristic_length_m`` is None, else
    :math:`[1;\ E(p - o_i)/L]` (3 rows), with :math:`o_i` joint i, p the end of link n and
    :math:`E` the rotation by +90°.
    """
    lengths = np.asarray(lengths_m, dtype=np.float64)
    phi = np.cumsum(np.asarray(theta_rad, dtype=np.float64))
    links = lengths[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])
    to_end = np.cumsum(links[::-1], axis=0)[::-1]  # p - o_i
    columns = np.column_stack([-to_end[:, 1], to_end[:, 0]]).T
    if characteristic_length_m is None:
        return columns
    return np.vstack([np.ones(len(lengths)), columns / characteristic_length_m])


def condition_number(matrix: np.ndarray) -> float:
    """:math:`\\sigma_{max}/\\sigma_{min}` (``inf`` when singular)."""
    sigma = np.linalg.svd(matrix, compute_uv=False)
    return math.inf if sigma[-1] <= 1e-300 else float(sigma[0] / sigma[-1])


_EYE = {rows: np.eye(rows) for rows in (2, 3)}
_UPPER = {rows: np.triu_indices(rows) for rows in (2, 3)}


def _isotropy_residual(variables, lengths_m, with_orientation):
    """:math:`JJ^T\\,m/\\mathrm{tr}(JJ^T) - I` (upper triangle): zero iff κ = 1."""
    theta = np.concatenate([[0.0], variables[: len(lengths_m) - 1]])
    length = _length_of(variables[-1]) if with_orientation else None
    j = jacobian(lengths_m, theta, length)
    gram = j @ j.T
    rows = gram.shape[0]
    scaled = gram * rows / max(np.trace(gram), 1e-300) - _EYE[rows]
    return scaled[_UPPER[rows]]


#: Bound of the search's log characteristic length, ``|log L| <= 700`` (``exp(709.8)`` is
#: the largest double): a search wandering off (a 1e30 m middle link) stays finite.
MAX_LOG_LENGTH = 700.0


def _length_of(log_length: float) -> float:
    """The characteristic length :math:`L = e^{v}`, ``v`` clipped to ``±``:data:`MAX_LOG_LENGTH`."""
    return math.exp(min(max(float(log_length), -MAX_LOG_LENGTH), MAX_LOG_LENGTH))


def _wrap_deg(angle_rad: float) -> float:
    """An angle in degrees wrapped to (-180, 180]."""
    degrees = math.degrees(angle_rad) % 360.0
    return degrees - 360.0 if degrees > 180.0 else degrees


def _kappa_of(variables, lengths_m) -> float:
    """κ of the 3×n Jacobian at θ = (0, variables[:-1]), L = exp(variables[-1])."""
    theta = np.concatenate([[0.0], variables[:-1]])
    return condition_number(jacobian(lengths_m, theta, _length_of(variables[-1])))


def _isotropic_2r(lengths):
    r"""Closed form for 2R: :math:`\kappa + 1/\kappa = \|J\|_F^2/|\det J|
    = (l_1^2 + 2l_2^2 + 2l_1l_2\cos\theta_2)/(l_1l_2|\sin\theta_2|)`, minimal at
    :math:`\cos\theta_2 = -2l_1l_2/(l_1^2 + 2l_2^2)` (always in [-1, 0])."""
    l1, l2 = float(lengths[0]), float(lengths[1])
    theta2 = math.acos(-2.0 * l1 * l2 / (l1 * l1 + 2.0 * l2 * l2))
    theta = np.array([0.0, theta2])
    return condition_number(jacobian(lengths, theta)), theta, None


def _starts(lengths) -> list[list[float]]:
    """Fixed starting points (θ2 … θn, log L): Angeles' 3R design first, then fans."""
    n = len(lengths)
    starts = []
    if n == 3:
        starts.append([math.radians(120.0), math.radians(150.0), math.log(lengths[2] / 2**0.5)])
    base = math.log(float(lengths.mean()))
    for start_deg in (135.0, 120.0, 90.0, 60.0, 150.0, 170.0):
        starts.append([math.radians(start_deg)] * (n - 1) + [base])
    return starts


def _isotropic_with_orientation(lengths):
    """n ≥ 3: least squares on the isotropy residual from :func:`_starts` (deterministic)."""
    best = None
    for start in _starts(lengths):
        x = levenberg_marquardt(lambda v: _isotropy_residual(v, lengths, True), start)
        kappa = _kappa_of(x, lengths)
        if best is None or kappa < best[0] - 1e-12:
            best = (kappa, x)
    return best


@lru_cache(maxsize=64)
def minimum_condition(lengths_m: tuple[float, ...]):
    """(κ, θ, L) of the posture of minimum condition number, θ1 = 0 (cached per process).

    2R: closed form (L None). n ≥ 3: Levenberg-Marquardt on the isotropy residual from
    fixed starts, then Nelder-Mead on κ itself from the best of them (the residual's
    minimiser is κ's only when κ = 1).
    """
    lengths = np.asarray(lengths_m, dtype=np.float64)
    if len(lengths) == 2:
        return _isotropic_2r(lengths)
    kappa, x = _isotropic_with_orientation(lengths)
    polished = nelder_mead(lambda v: _kappa_of(v, lengths), x)
    if _kappa_of(polished, lengths) < kappa:
        x, kappa = polished, _kappa_of(polished, lengths)
    return kappa, np.concatenate([[0.0], x[:-1]]), _length_of(x[-1])


def isotropic_posture(lengths_m, tolerance: float = 0.01) -> Posture:
    """The posture of minimum Jacobian condition number, or :class:`NoIsotropicPosture`.

    See :func:`minimum_condition`. Raises when κ > 1 + tolerance, giving the minimum κ
    and where it is reached.
    """
    lengths = np.asarray(lengths_m, dtype=np.float64)
    n = len(lengths)
    if n < 2:
        raise NoIsotropicPosture("a 1-link robot has no isotropic posture (needs n >= 2)")
    kappa, theta, length = minimum_condition(tuple(float(v) for v in lengths))
    degrees = [_wrap_deg(t) for t in theta]
    if degrees[1] < 0:  # mirror image: same κ; keep θ2 > 0
        degrees = [(-d if d != 180.0 else d) + 0.0 for d in degrees]  # no -0.0
    if not kappa <= 1.0 + tolerance:
        requirement = "l2 = l1/√2" if n == 2 else ("l1 = l2 = √3·l3" if n == 3 else "")
        raise NoIsotropicPosture(
            f"no isotropic posture: the minimum condition number is {kappa:.6g} at "
            f"theta = [{', '.join(f'{d:.2f}' for d in degrees)}] deg, above 1 + {tolerance:g}"
            + (f" (isotropy needs {requirement})" if requirement else "")
        )
    return Posture("isotropic", tuple(math.radians(d) for d in degrees), kappa, length)


def singular_posture(n_links: int, lengths_m=None) -> Posture:
    """All joint angles 0: the arm stretched horizontally (Jacobian rank-deficient, κ = ∞)."""
    return Posture("singular", (0.0,) * n_links, math.inf)


def explicit_posture(theta_deg, lengths_m) -> Posture:
    """Given relative joint angles (degrees); κ reported as for the isotropic search."""
    theta = tuple(math.radians(float(t)) for t in theta_deg)
    lengths = np.asarray(lengths_m, dtype=np.float64)
    if len(lengths) >= 3:
        length = float(np.sqrt(np.mean(lengths**2)))
        kappa = condition_number(jacobian(lengths, theta, length))
    else:
        length = None
        kappa = condition_number(jacobian(lengths, theta))
    label = "theta_deg=" + "/".join(f"{float(t):g}" for t in theta_deg)
    return Posture(label, theta, kappa, length)
