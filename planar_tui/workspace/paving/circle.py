"""The singularity-free circle every parallel robot certifies: its summary columns, the
centre key, the refusal of circle keys without ``singularities``, and the outcome
(:class:`FreeCircle`: the kept singular leaves, the centre and the certified radius
bracket ``r_in <= r* <= r_out``) of the robots whose circle is a distance to a bad set."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from planar_tui.errors import PresetError

#: |det A| below this fraction of (l1 + l2)^3 (|q|max + 1) counts as singular at the centre.
SINGULAR_RELATIVE = 1e-9


#: The summary's circle columns: centre, certified radius bracket and the working mode the
#: radius holds for (``elbow``: the three signs, e.g. ``1 -1 1``).
HEADER = (
    "circle_centre_x_cm",
    "circle_centre_y_cm",
    "circle_radius_lo_cm",
    "circle_radius_hi_cm",
    "elbow",
)


def read_centre(reader, name, default, robot, values):
    """A point ``[x, y]`` in cm."""
    if not reader.has(name):
        return default
    point = reader.numbers(name, length=2, items_doc="a point [x, y] in cm")
    return (point[0], point[1])


def refuse_without_singularities(values: dict, reader, names) -> None:
    """The first of the keys ``names`` that is set, without ``singularities = true``, is
    a :class:`PresetError` (exit code 2)."""
    for name in names:
        if values[name] is not None:
            raise reader.error(name, "is set without singularities = true", "singularities = true")


#: Round-off margin of the float distances (cm): coordinates below 1e3 cm err below 1e-12.
MARGIN_CM = 1e-9


@dataclass
class FreeCircle:
    """The kept leaves (rows ``x_lo, x_hi, y_lo, y_hi``: may hold a singular pose), the
    circle's centre and certified radius bracket."""

    boxes: Any
    centre_cm: tuple[float, float]
    radius_lo_cm: float
    radius_hi_cm: float
    boxes_processed: int
    seconds: float
    #: The working modes the circle holds for (``"1 -1 1"``; empty for the 3-RPR).
    elbow: str = ""

    @property
    def singular_boxes(self) -> Any:
        return self.boxes

    def columns(self) -> list:
        """The 3-RRR's circle columns (``elbow``: the working modes, if any)."""
        return [*self.centre_cm, self.radius_lo_cm, self.radius_hi_cm, self.elbow]

    def describe(self) -> str:
        modes = f", modes [{self.elbow}]" if self.elbow else ""
        return (
            f"singularity-free: r ∈ [{self.radius_lo_cm:.5g}, {self.radius_hi_cm:.5g}] cm "
            f"about ({self.centre_cm[0]:.4g}, {self.centre_cm[1]:.4g}){modes}"
        )


def given_or_centroid(job: Any, polygon_of: Any) -> tuple[float, float]:
    """The job's ``circle_centre_cm``, or the centroid of its exact workspace
    (``polygon_of(robot, spec, segments, outward)``; a point inside when the centroid is
    not); an empty workspace is a :class:`PresetError`."""
    if job.spec.circle_centre_cm is not None:
        return job.spec.circle_centre_cm
    polygon = polygon_of(job.robot, job.spec, 256, False)
    if polygon.is_empty:
        raise PresetError(
            job.preset_path,
            f"{job.key}.circle_centre_cm",
            "has no default: the workspace is empty",
            "a non-empty workspace",
        )
    point = polygon.centroid
    if not polygon.contains(point):
        point = polygon.representative_point()
    return (float(point.x), float(point.y))


def box_distances(boxes, centre):
    """The distance from ``centre`` to each row ``x_lo, x_hi, y_lo, y_hi`` (0 inside)."""
    import numpy as np

    dx = np.maximum(np.maximum(boxes[:, 0] - centre[0], 0.0), centre[0] - boxes[:, 1])
    dy = np.maximum(np.maximum(boxes[:, 2] - centre[1], 0.0), centre[1] - boxes[:, 3])
    return np.hypot(dx, dy)


#: What a wrong ``elbow`` is told to expect.
ELBOW_DOC = "3 signs, each 1 or -1 (one per leg)"


def read_elbow(reader, name, default, robot, values):
    """Three elbow signs, each ``1`` or ``-1``."""
    if not reader.has(name):
        return default
    signs = reader.numbers(name, length=3, items_doc=ELBOW_DOC)
    if any(s not in (1.0, -1.0) for s in signs):
        raise reader.error(name, f"is {list(signs)}", ELBOW_DOC)
    return tuple(int(s) for s in signs)
