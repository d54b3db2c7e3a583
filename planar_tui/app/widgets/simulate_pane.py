"""The Simulate tab: the arm drawn at the scrubbed time of a finished simulation (the
start posture before a run) beside the joint angles and energy against time
(textual-plotext), a cursor line on both plots at the scrubbed time and its values read
out below.

On the drawing (focus it with Tab): the scrubber's keys (:mod:`.playback`), ``1`` … ``9``
show or hide joint i's curve, ``a`` shows them all, ``w`` wraps the angles to
(-180°, 180°].
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import Static
from textual_plotext import PlotextPlot

from planar_tui.app.widgets.panes import JobPane
from planar_tui.app.widgets.playback import PlaybackView, wrap_deg
from planar_tui.app.widgets.robot_drawing import numbers_or_zeros, serial_scene
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job

#: One marker per joint, so curves are told apart without colour.
MARKERS = ("1", "2", "3", "4", "5", "6", "7", "8", "9")
MAX_POINTS = 300
#: The cursor line's colour on the plots.
CURSOR_COLOUR = "red"


def thin(count: int, limit: int = MAX_POINTS) -> np.ndarray:
    """Indices of at most ``limit`` evenly spaced rows out of ``count`` (first and last kept)."""
    if count <= limit:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, limit).round().astype(int))


class ArmPlayback(PlaybackView):
    """The scrubber of the Simulate tab, with the plots' joint and wrap keys."""

    BINDINGS: ClassVar = [
        *(Binding(str(i), f"joint({i})", f"θ{i}", show=False) for i in range(1, 10)),
        Binding("a", "joint(0)", "All θ", show=False),
        Binding("w", "wrap", "Wrap ±180°", show=False),
    ]

    def action_joint(self, joint: int) -> None:
        self.query_ancestor(SimulatePane).toggle_joint(joint)

    def action_wrap(self) -> None:
        pane = self.query_ancestor(SimulatePane)
        pane.wrap = not pane.wrap
        pane.draw_plots()


class SimulatePane(JobPane):
    """Initial state, torques, duration and step; the arm, θ_i(t) and E(t) with a cursor."""

    kind = "simulate"

    DEFAULT_CSS = """
    #simulate-view { height: 1fr; }
    #simulate-arm { width: 1fr; min-width: 16; }
    #simulate-plots { width: 1fr; }
    #playback-readout { height: auto; max-height: 3; }
    """

    #: Joints whose curves are hidden (1-based); angles wrapped to (-180°, 180°].
    hidden: frozenset[int] = frozenset()
    wrap = False

    def compose_results(self) -> ComposeResult:
        yield Static("Run the simulation (F5) to plot it.", id="result-text", markup=False)
        with Horizontal(id="simulate-view"):
            yield ArmPlayback("(no drawing)", id="simulate-arm")
            with Vertical(id="simulate-plots"):
                yield PlotextPlot(id="angles-plot")
                yield PlotextPlot(id="energy-plot")
        yield Static("", id="playback-readout", markup=False)

    def on_mount(self) -> None:
        if self.available():
            for plot_id, title in (
                ("#angles-plot", "joint angles (deg)"),
                ("#energy-plot", "energy (J)"),
            ):
                self.query_one(plot_id, PlotextPlot).plt.title(title)
            self.draw_start()

    def on_table_form_changed(self, event) -> None:
        super().on_table_form_changed(event)
        if self.result is None:
            self.draw_start()

    def draw_start(self) -> None:
        """Before a run: the arm at the job's ``theta0_deg`` (zeros where not numbers)."""
        try:
            job = self.bench.job(self.kind, self.index)
        except Exception:  # an invalid form: the validation line says why
            return
        lengths = list(job.robot.lengths_m)
        theta = numbers_or_zeros(list(job.spec.theta0_deg), len(lengths))
        self.query_one(ArmPlayback).show(serial_scene(lengths, theta, caption="start"))

    def render_result(self, job: Job, result: JobResult) -> None:
        lengths = list(job.robot.lengths_m)
        theta_deg = np.degrees(result.theta_rad)
        view = self.query_one(ArmPlayback)
        same_run = view.frame_scene is not None and len(view.times) == len(result.t_s)

        def frame(row: int):
            return serial_scene(lengths, theta_deg[row].tolist())

        view.load(result.t_s, frame, view.row if same_run else 0)
        self.query_one("#result-text", Static).update(result.summary)

    def on_playback_view_moved(self, message: PlaybackView.Moved) -> None:
        self.draw_plots()

    def toggle_joint(self, joint: int) -> None:
        """Show or hide joint ``joint``'s curve (0: show every joint)."""
        if self.result is None:
            return
        count = self.result.theta_rad.shape[1]
        if joint == 0:
            self.hidden = frozenset()
        elif joint <= count:
            hidden = self.hidden ^ {joint}
            self.hidden = hidden if len(hidden) < count else self.hidden
        self.draw_plots()

    def angles_deg(self, rows) -> np.ndarray:
        """The relative joint angles (deg) at ``rows``, wrapped when asked."""
        angles = np.degrees(self.result.theta_rad[rows])
        return wrap_deg(angles) if self.wrap else angles

    def draw_plots(self) -> None:
        """The angle and energy plots with the cursor at the scrubbed time, and the read-out."""
        result = self.result
        if result is None or not self.is_attached:
            return
        view = self.query_one(ArmPlayback)
        rows = thin(len(result.t_s))
        t_s = result.t_s[rows].tolist()
        cursor = view.t_s
        angles = self.query_one("#angles-plot", PlotextPlot)
        plt = angles.plt
        plt.clear_data()
        plt.clear_figure()
        theta_deg = self.angles_deg(rows)
        for joint in range(theta_deg.shape[1]):
            if joint + 1 not in self.hidden:
                plt.plot(
                    t_s,
                    theta_deg[:, joint].tolist(),
                    marker=MARKERS[joint % len(MARKERS)],
                    label=f"θ{joint + 1}",
                )
        plt.vline(cursor, CURSOR_COLOUR)
        wrapped = ", wrapped" if self.wrap else ""
        plt.title(f"θi (deg{wrapped}) vs t (s)")
        angles.refresh()
        energy = self.query_one("#energy-plot", PlotextPlot)
        plt = energy.plt
        plt.clear_data()
        plt.clear_figure()
        kinetic = result.kinetic_J[rows]
        potential = result.potential_J[rows]
        plt.plot(t_s, (kinetic + potential).tolist(), marker="E", label="E total")
        plt.plot(t_s, kinetic.tolist(), marker="k", label="kinetic")
        plt.plot(t_s, potential.tolist(), marker="p", label="potential")
        plt.vline(cursor, CURSOR_COLOUR)
        plt.title("E, k, p (J) vs t (s)")
        energy.refresh()
        self.query_one("#playback-readout", Static).update(self.readout())

    def readout(self) -> str:
        """The values at the cursor: ``t = 0.5 s / 1 s ‖ ×1  θ1 12.3° …  E 1.234 J …``."""
        view = self.query_one(ArmPlayback)
        row = view.row
        result = self.result
        angles = self.angles_deg([row])[0]
        shown = "  ".join(
            f"θ{j + 1} {angle:.4g}°" for j, angle in enumerate(angles) if j + 1 not in self.hidden
        )
        kinetic, potential = float(result.kinetic_J[row]), float(result.potential_J[row])
        if self.wrap:
            shown += " (wrapped)"
        keys = "" if view.has_focus else "  (Tab to the arm: ←/→ space [ ])"
        return (
            f"{view.status()}  {shown}  E {kinetic + potential:.5g} J "
            f"(K {kinetic:.4g}, P {potential:.4g}){keys}"
        )

    def on_descendant_focus(self, event) -> None:
        if self.result is not None:
            self.query_one("#playback-readout", Static).update(self.readout())

    def on_descendant_blur(self, event) -> None:
        self.on_descendant_focus(event)
