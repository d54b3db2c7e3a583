"""The path tabs (``[[path3rrr]]``, ``[[path3rpr]]``, ``[[path3prr]]``, ``[[path5r]]``): the
parallel robot drawn at the scrubbed time of a finished path job beside its actuator
efforts against time (textual-plotext), a cursor line on the plot at the same time and the
row's values read out below.

The drawing is the robot's own
(:meth:`~planar_tui.workspace.paving.mechanism.Mechanism.linkage`: no robot is named
here), played back by :class:`~planar_tui.app.widgets.playback.PlaybackView` (its keys
once the drawing has the focus: ``←``/``→``, ``home``/``end``, ``space``, ``[``/``]``), in
a fixed extent (every drawn point of the path's thinned rows, so the scale stays put).

With ``kappa_max`` (a certified path, :mod:`planar_tui.workspace.path.certify`) the drawing
also shows the path's trace, the platform point at every sampled time: ``·`` where the
certificate holds, ``x`` on the failing stretch from ``first_failure_lo_s`` (the end of the
certified part) to the end of the path; and the certificate's verdict in words below
(:func:`verdict_words`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Static
from textual_plotext import PlotextPlot

from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.playback import PlaybackView
from planar_tui.app.widgets.robot_drawing import (
    BASE_GLYPH,
    BASE_STYLE,
    DISTAL_STYLE,
    JOINT_GLYPH,
    JOINT_STYLE,
    LINK_STYLE,
    PLATFORM_GLYPH,
    PLATFORM_STYLE,
    TIP_GLYPH,
    TIP_STYLE,
    TRIANGLE_STYLE,
    Scene,
)
from planar_tui.app.widgets.simulate_pane import CURSOR_COLOUR, MARKERS, thin
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job

#: Metres per centimetre (the linkage is in cm, a scene in m).
M_PER_CM = 0.01
#: The drawing's margin around the path's extent, a fraction of its larger side.
MARGIN = 0.05
#: The trace's glyphs: the certified part, the failing stretch; and their style.
TRACE_GLYPH, FAILING_GLYPH = "·", "x"
TRACE_STYLE, FAILING_STYLE = "grey50", "bold red"
#: What each failure reason of a certificate means, in words.
REASON_WORDS = {
    "kappa": "κ rises above kappa_max",
    "leg": "a leg cannot close",
    "joint_limit": "a joint or leg leaves its limits",
    "interference": "two links, or a link and the platform, come too close",
}


def failing_stretch(certificate: Any, duration_s: float) -> tuple[float, float] | None:
    """The failing stretch ``[first_failure_lo_s, T]`` of a certificate (``None``: none,
    the path is certified)."""
    if certificate is None or certificate.certified == "yes":
        return None
    return (float(certificate.failure_lo_s), duration_s)


def verdict_words(certificate: Any, duration_s: float) -> str:
    """The certificate's verdict as a sentence (``""`` without one)."""
    if certificate is None:
        return ""
    bound = f"κ ≤ {certificate.kappa_max:g}"
    peak = ""
    if not math.isnan(certificate.kappa_peak_hi):
        peak = f" (largest κ in [{certificate.kappa_peak_lo:.4g}, {certificate.kappa_peak_hi:.4g}])"
    if certificate.certified == "yes":
        return (
            f"Certified: every leg closes within its limits and {bound} for every t in "
            f"[0, {duration_s:g}] s{peak}."
        )
    lo = certificate.failure_lo_s
    if certificate.certified == "no":
        hi = certificate.failure_hi_s
        why = REASON_WORDS.get(certificate.reason, certificate.reason)
        return (
            f"Not certified: the path first fails between t = {lo:.6g} and {hi:.6g} s "
            f"({why}); certified on [0, {lo:.6g}] s{peak}; {FAILING_GLYPH} marks the "
            f"stretch from {lo:.6g} s to the end."
        )
    return (
        f"Undecided: certified ({bound}) on [0, {lo:.6g}] s{peak}, no proof either way "
        f"after it; {FAILING_GLYPH} marks the stretch from {lo:.6g} s to the end."
    )


def linkage_scene(linkage: Any, extent_m: tuple[float, float, float, float], caption: str) -> Scene:
    """A :class:`~planar_tui.workspace.paving.linkage.Linkage` (cm) as a scene (m): the frame
    in the base triangle's style, each leg's first link as a proximal link and the rest as
    distal ones, the platform closed; ``#`` the actuated joints, ``o`` the passive ones,
    ``*`` the platform joints (``+`` where the legs meet at one point)."""

    def metres(line: Any) -> list[tuple[float, float]]:
        return [(x * M_PER_CM, y * M_PER_CM) for x, y in line]

    scene = Scene(extent_m, caption=caption)
    scene.links += [(metres(line), TRIANGLE_STYLE) for line in linkage.frame]
    for leg in linkage.legs:
        points = metres(leg)
        scene.links.append((points[:2], LINK_STYLE))
        if len(points) > 2:
            scene.links.append((points[1:], DISTAL_STYLE))
    platform = metres(linkage.platform)
    if platform:
        scene.links.append(([*platform, platform[0]], PLATFORM_STYLE))
    for leg in linkage.legs:
        points = metres(leg)
        scene.joints.append((points[0], BASE_GLYPH, BASE_STYLE))
        scene.joints += [(p, JOINT_GLYPH, JOINT_STYLE) for p in points[1:-1]]
    if platform:
        scene.joints += [(p, PLATFORM_GLYPH, PLATFORM_STYLE) for p in platform]
    elif linkage.legs:  # the legs meet at the end point
        scene.joints.append((metres(linkage.legs[0])[-1], TIP_GLYPH, TIP_STYLE))
    return scene


class PathFrames:
    """A path result's linkage at each recorded row: the pose from the CSV's ``x_cm, y_cm
    [, phi_deg]`` columns, the actuators from the solution (rad, or cm for prismatic legs,
    as :meth:`~planar_tui.workspace.paving.mechanism.Mechanism.linkage` takes them)."""

    def __init__(self, job: Job, result: Any):
        self.mechanism, self.robot = job.spec.mechanism, job.robot
        header = list(result.table.header)
        every = np.asarray(result.table.rows, dtype=np.float64)  # an empty cell: nan
        trace = every[:, [header.index("x_cm"), header.index("y_cm")]] * M_PER_CM
        stretch = failing_stretch(getattr(result, "certificate", None), job.spec.duration_s)
        failing = np.zeros(len(every), dtype=bool)
        if stretch is not None:
            failing = every[:, 0] >= stretch[0]
        #: The trace's glyphs (with ``kappa_max`` alone), each ``(point_m, glyph, style)``.
        self.trace: list[tuple[tuple[float, float], str, str]] = []
        if getattr(result, "certificate", None) is not None:
            self.trace = [
                (
                    (float(x), float(y)),
                    FAILING_GLYPH if bad else TRACE_GLYPH,
                    FAILING_STYLE if bad else TRACE_STYLE,
                )
                for (x, y), bad in zip(trace, failing, strict=True)
            ]
        rows = every[np.isfinite(every[:, len(header) - 1])]  # the rows where the legs close
        poses = rows[:, [header.index("x_cm"), header.index("y_cm")]]
        if "phi_deg" in header:
            poses = np.column_stack([poses, np.radians(rows[:, header.index("phi_deg")])])
        self.poses = poses
        scale = 100.0 if result.model.prismatic else 1.0
        self.actuators = np.asarray(result.solution.coordinate, dtype=np.float64) * scale
        self.times_s = np.asarray(result.times_s, dtype=np.float64)
        points = np.array(
            [p for row in thin(len(self.poses)) for p in self.linkage(int(row)).points()]
        )
        if self.trace:
            points = np.concatenate([points, trace / M_PER_CM])
        lo, hi = points.min(axis=0) * M_PER_CM, points.max(axis=0) * M_PER_CM
        grow = MARGIN * float(max(hi - lo))
        self.extent_m = (lo[0] - grow, hi[0] + grow, lo[1] - grow, hi[1] + grow)

    def linkage(self, row: int) -> Any:
        return self.mechanism.linkage(self.robot, self.poses[row], self.actuators[row])

    def scene(self, row: int) -> Scene:
        """The robot at ``row`` over the path's trace (the robot's joints drawn last)."""
        scene = linkage_scene(self.linkage(row), self.extent_m, f"t={self.times_s[row]:.3g} s")
        scene.joints = [*self.trace, *scene.joints]
        return scene


class PathPane(JobPane):
    """A path job: its poses, duration, steps and working mode; the robot played back
    along the path beside its efforts against time."""

    DEFAULT_CSS = """
    #path-view { height: 1fr; }
    #path-robot { width: 1fr; min-width: 16; }
    #efforts-plot { width: 1fr; }
    #path-readout { height: auto; max-height: 3; }
    #path-certificate { height: auto; }
    """

    def compose_results(self) -> ComposeResult:
        yield Static("Run the path (F5) to play it back.", id="result-text", markup=False)
        with Horizontal(id="path-view"):
            yield PlaybackView("(the robot: run the path)", id="path-robot")
            yield PlotextPlot(id="efforts-plot")
        yield Static("", id="path-readout", markup=False)
        yield Static("", id="path-certificate", markup=False)

    def render_result(self, job: Job, result: JobResult) -> None:
        view = self.query_one("#path-robot", PlaybackView)
        times = np.asarray(result.times_s)
        same_run = view.frame_scene is not None and len(view.times) == len(times)
        frames = PathFrames(job, result)
        view.load(times, frames.scene, view.row if same_run else 0)
        self.query_one("#result-text", Static).update(result.summary)
        words = verdict_words(getattr(result, "certificate", None), job.spec.duration_s)
        self.query_one("#path-certificate", Static).update(words)

    def on_playback_view_moved(self, message: PlaybackView.Moved) -> None:
        self.draw_plot()

    def effort_columns(self) -> list[str]:
        """The CSV's effort columns (``tau1_Nm`` … or ``force1_N`` …)."""
        model = self.result.model
        return [f"{model.effort}{i}_{model.effort_unit}" for i in range(1, model.actuators + 1)]

    def effort_series(self) -> dict[str, list[float]]:
        """The plotted curves: ``t_s`` and each effort column (thinned rows)."""
        result = self.result
        rows = thin(len(result.times_s))
        series = {"t_s": np.asarray(result.times_s)[rows].tolist()}
        for i, name in enumerate(self.effort_columns()):
            series[name] = np.asarray(result.solution.effort)[rows, i].tolist()
        return series

    def draw_plot(self) -> None:
        """The efforts against time with the cursor at the scrubbed time, and the read-out."""
        result = self.result
        if result is None or not self.is_attached:
            return
        series = self.effort_series()
        plot = self.query_one("#efforts-plot", PlotextPlot)
        plt = plot.plt
        plt.clear_data()
        plt.clear_figure()
        for i, name in enumerate(self.effort_columns()):
            plt.plot(series["t_s"], series[name], marker=MARKERS[i], label=name)
        view = self.query_one("#path-robot", PlaybackView)
        plt.vline(view.t_s, CURSOR_COLOUR)
        unit = result.model.effort_unit.replace("Nm", "N m")
        plt.title(f"{result.model.effort}i ({unit}) vs t (s)")
        plot.refresh()
        self.query_one("#path-readout", Static).update(self.readout())

    def readout(self) -> str:
        """The row at the cursor: ``t = 0.25 s / 0.5 s ‖ ×1  tau1 1.234 N m …``."""
        view = self.query_one("#path-robot", PlaybackView)
        effort = np.asarray(self.result.solution.effort)[view.row]
        unit = self.result.model.effort_unit.replace("Nm", "N m")
        values = "  ".join(
            f"{name.rsplit('_', 1)[0]} {value:.6g}"
            for name, value in zip(self.effort_columns(), effort, strict=True)
        )
        keys = "" if view.has_focus else "  (Tab to the robot: ←/→ space [ ])"
        return f"{view.status()}  {values} {unit}{keys}"


class Path3RRRPane(PathPane):
    kind = "path3rrr"


class Path3RPRPane(PathPane):
    kind = "path3rpr"


class Path3PRRPane(PathPane):
    kind = "path3prr"


class Path5RPane(PathPane):
    kind = "path5r"
