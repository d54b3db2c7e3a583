"""Figure of a parallel robot's path job: each actuator's effort and power against time
(two panels). Read from the path CSV (``t_s, x_cm, y_cm, ..., tau1_Nm`` or ``force1_N``,
``power1_W`` ...). A certified path's job (``kappa_max``) adds the path's trace in the
plane (:func:`draw_certificate`): the certified part, the failing stretch from
``first_failure_lo_s`` to the end in red (also shaded on the time axes), the verdict as the
panel's title."""

from __future__ import annotations

from typing import Any

from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import colour, new_figure
from planar_tui.figures.table import column, has_columns, numbered

#: The efforts' columns by actuator kind: prefix, suffix, axis label.
EFFORTS = (("tau", "_Nm", "torque (N m)"), ("force", "_N", "force (N)"))


def matches(header: tuple[str, ...]) -> bool:
    return has_columns(header, ("t_s", "x_cm", "y_cm", "power1_W")) and any(
        f"{prefix}1{suffix}" in header for prefix, suffix, _ in EFFORTS
    )


def draw(table: CsvTable, title: str) -> Any:
    """Efforts (top) and powers (bottom) against time, one line per actuator."""
    header = table.header
    prefix, suffix, label = next(e for e in EFFORTS if f"{e[0]}1{e[1]}" in header)
    efforts = numbered(header, prefix, suffix)
    n = len(efforts)
    t = column(table, "t_s")
    fig = new_figure(7.0, 6.0)
    top, bottom = fig.subplots(2, 1, sharex=True)
    for i, name in enumerate(efforts):
        top.plot(t, column(table, name), color=colour(i, n), label=f"actuator {i + 1}")
        bottom.plot(t, column(table, f"power{i + 1}_W"), color=colour(i, n))
    top.set(ylabel=f"actuator {label}", title="actuator efforts along the path")
    bottom.set(xlabel="time (s)", ylabel="power (W)")
    for ax in (top, bottom):
        ax.axhline(0.0, color="k", lw=0.6)
        ax.grid(alpha=0.3)
    top.legend(fontsize="small")
    fig.suptitle(title)
    return fig


#: The failing stretch's colour.
FAILING_COLOUR = "#c0392b"


def draw_certificate(fig: Any, table: CsvTable, certificate: Any) -> None:
    """The trace panel of a certified path beside the time axes of ``fig``: the CSV's
    ``(x_cm, y_cm)`` at each sampled time, ``gid`` ``"trace-certified"`` before
    ``first_failure_lo_s`` and ``"trace-failing"`` from it (including the sample before,
    so the line is unbroken), start and end marked."""
    import numpy as np

    t, x, y = (column(table, name) for name in ("t_s", "x_cm", "y_cm"))
    axes = list(fig.axes)
    width, height = fig.get_size_inches()
    fig.set_size_inches(width + 5.0, height)
    grid = fig.add_gridspec(len(axes), 2, width_ratios=(1.4, 1.0))
    for k, ax in enumerate(axes):
        ax.set_subplotspec(grid[k, 0])
    panel = fig.add_subplot(grid[:, 1])
    failing = np.zeros(len(t), dtype=bool)
    if certificate.certified != "yes":
        failing = t >= certificate.failure_lo_s
        for ax in axes:
            ax.axvspan(certificate.failure_lo_s, t[-1], color=FAILING_COLOUR, alpha=0.12)
    first = int(np.argmax(failing)) if failing.any() else len(t)
    panel.plot(
        x[: first + 1],
        y[: first + 1],
        color="#2e7d32",
        lw=2,
        gid="trace-certified",
        label="certified",
    )
    if failing.any():
        panel.plot(
            x[max(first - 1, 0) :],
            y[max(first - 1, 0) :],
            color=FAILING_COLOUR,
            lw=2.5,
            gid="trace-failing",
            label=f"failing from t = {certificate.failure_lo_s:.4g} s",
        )
    panel.plot(x[0], y[0], "ko", ms=5, label="start")
    panel.plot(x[-1], y[-1], "k^", ms=6, label="end")
    verdict = {"yes": "certified", "no": "not certified", "unknown": "undecided"}
    reason = f" ({certificate.reason})" if certificate.reason else ""
    panel.set(
        xlabel="x (cm)",
        ylabel="y (cm)",
        aspect="equal",
        title=f"{verdict[certificate.certified]}{reason}, κ ≤ {certificate.kappa_max:g}",
    )
    panel.grid(alpha=0.3)
    panel.legend(fontsize="small")


def from_result(job: Any, result: Any) -> Any:
    """The figure of a finished path job (with its certificate's trace panel)."""
    fig = draw(result.table, job.label)
    certificate = getattr(result, "certificate", None)
    if certificate is not None:
        draw_certificate(fig, result.table, certificate)
    return fig
