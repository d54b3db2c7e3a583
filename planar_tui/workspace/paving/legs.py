"""Closing a leg of two revolute links (the 3-RRR's and the five-bar's legs): its active
angles at a given platform point, in floats."""

from __future__ import annotations

import math


# -- float model (the centre's working mode and the prepare check) ----------------------
def on_arc(angle: float, lo: float, hi: float) -> bool:
    return (angle - lo) % (2.0 * math.pi) <= hi - lo


def closing_modes(angles: dict[int, float] | None, lo: float, hi: float) -> list[int]:
    """The working modes ``s`` (``1``, ``-1``) whose active angle ``angles[s]`` (of
    :func:`branch_angles`) lies on the arc ``[lo, hi]``: none where the leg cannot close,
    one where its two solutions coincide (the leg stretched straight)."""
    if angles is None:
        return []
    modes = [s for s in (1, -1) if on_arc(angles[s], lo, hi)]
    return modes[:1] if angles[1] == angles[-1] else modes


def branch_angles(vx: float, vy: float, l1: float, l2: float) -> dict[int, float] | None:
    """The active angles :math:`\\theta = \\alpha + s \\beta` for ``s = +1, -1`` of a leg
    whose platform point is at ``(vx, vy)`` from its base joint, or ``None`` where it
    cannot close."""
    rho = math.hypot(vx, vy)
    cosine = (rho * rho + l1 * l1 - l2 * l2) / (2.0 * l1 * rho) if rho > 0 else 2.0
    if abs(cosine) > 1.0:
        return None
    alpha, beta = math.atan2(vy, vx), math.acos(cosine)
    return {1: alpha + beta, -1: alpha - beta}
