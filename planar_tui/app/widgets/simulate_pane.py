"""The Simulate tab: joint angles and energy against time (textual-plotext)."""

from __future__ import annotations

import numpy as np
from textual.app import ComposeResult
from textual.widgets import Static
from textual_plotext import PlotextPlot

from planar_tui.app.widgets.panes import JobPane
from planar_tui.jobkind import JobResult
from planar_tui.presets import Job

#: One marker per joint, so curves are told apart without colour.
MARKERS = ("1", "2", "3", "4", "5", "6", "7", "8", "9")
MAX_POINTS = 300


def thin(count: int, limit: int = MAX_POINTS) -> np.ndarray:
    """Indices of at most ``limit`` evenly spaced rows out of ``count`` (first and last kept)."""
    if count <= limit:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, limit).round().astype(int))


class SimulatePane(JobPane):
    """Initial state, torques, duration and step; plots of θ_i(t) and E(t)."""

    kind = "simulate"

    def compose_results(self) -> ComposeResult:
        yield Static("Run the simulation (F5) to plot it.", id="result-text", markup=False)
        yield PlotextPlot(id="angles-plot")
        yield PlotextPlot(id="energy-plot")

    def on_mount(self) -> None:
        if self.available():
            for plot_id, title in (
                ("#angles-plot", "joint angles (deg)"),
                ("#energy-plot", "energy (J)"),
            ):
                self.query_one(plot_id, PlotextPlot).plt.title(title)

    def render_result(self, job: Job, result: JobResult) -> None:
        rows = thin(len(result.t_s))
        t_s = result.t_s[rows].tolist()
        angles = self.query_one("#angles-plot", PlotextPlot)
        plt = angles.plt
        plt.clear_data()
        plt.clear_figure()
        theta_deg = np.degrees(result.theta_rad[rows])
        for joint in range(theta_deg.shape[1]):
            plt.plot(
                t_s, theta_deg[:, joint].tolist(), marker=MARKERS[joint % len(MARKERS)],
                label=f"θ{joint + 1}",
            )  # fmt: skip
        plt.title("joint angles θi (deg; marker i) vs t (s)")
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
        plt.title("energy (J) vs t (s); markers E, k, p")
        energy.refresh()
        self.query_one("#result-text", Static).update(result.summary)
