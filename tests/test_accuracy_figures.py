"""The certified layers of a workspace figure: with ``accuracy`` an error panel whose boxes
are coloured by ``max(dx_max_cm, dy_max_cm)`` of the boxes CSV (computed here from the
table ``boxes_output`` writes, ``result.extra_tables["boxes"]``), the boxes not certified
hatched apart; with ``leg_width_cm`` the proved interference-free boxes as a layer."""

from __future__ import annotations

import numpy as np
import pytest

from planar_tui.figures.dispatch import figure_for_result
from tests.test_accuracy import TABLE3
from tests.test_dexterity import run
from tests.test_dexterity_figures import by_gid, corners


def labelled(table, status):
    """The boxes of the rows labelled ``status`` and their rows as dicts."""
    rows = [dict(zip(table.header, r, strict=True)) for r in table.rows]
    rows = [r for r in rows if r["status"] == status]
    boxes = np.array(
        [[float(r[k]) for k in ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm")] for r in rows]
    )
    return boxes.reshape(-1, 4), rows


@pytest.fixture(scope="module")
def table3(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fig")
    text = TABLE3.format(precision=1.0, actuator=0.1, tolerance=0.01, extra="leg_width_cm = 2\n")
    job, result = run(folder, text)
    return job, result, figure_for_result(job, result)


def test_the_error_panel_colours_each_certified_box_by_its_position_error(table3):
    _, result, fig = table3
    assert "certified max(|Δx|, |Δy|) per box" in [ax.get_title() for ax in fig.axes]
    table = result.extra_tables["boxes"]
    boxes, rows = labelled(table, "accuracy-certified")
    error = np.array([max(float(r["dx_max_cm"]), float(r["dy_max_cm"])) for r in rows])
    assert len(boxes) > 10 and error.max() > 1.5 * error.min() > 0
    heat = by_gid(fig, "accuracy")
    np.testing.assert_allclose(corners(heat), boxes)
    np.testing.assert_allclose(np.asarray(heat.get_array()), error, rtol=1e-12)
    assert heat.norm.vmin == 0 and heat.norm.vmax == pytest.approx(error.max())
    heat.update_scalarmappable()
    colours = heat.get_facecolor()
    worst, best = int(np.argmax(error)), int(np.argmin(error))
    assert not np.allclose(colours[worst], colours[best])
    uncertified, _ = labelled(table, "accuracy-not-certified")
    assert len(uncertified)
    np.testing.assert_allclose(corners(by_gid(fig, "accuracy-uncertified")), uncertified)


def test_the_interference_free_layer_holds_the_proved_boxes(table3):
    _, result, fig = table3
    clear, _ = labelled(result.extra_tables["boxes"], "interference-free")
    assert len(clear)
    np.testing.assert_allclose(corners(by_gid(fig, "interference-free")), clear)


def test_a_job_without_accuracy_or_leg_width_has_neither(tmp_path):
    text = TABLE3.format(precision=4.0, actuator=0.1, tolerance=0.01, extra="")
    text = text.replace("accuracy = { actuator_deg = 0.1, tolerance_cm = 0.01 }\n", "")
    text = text.replace("elbow = [1, -1, 1]\n", "")
    job, result = run(tmp_path, text)
    assert result.accuracy is None
    fig = figure_for_result(job, result)
    assert "certified max(|Δx|, |Δy|) per box" not in [ax.get_title() for ax in fig.axes]
    gids = ("accuracy", "accuracy-uncertified", "interference-free")
    assert not fig.findobj(lambda a: a.get_gid() in gids)


def test_past_the_drawn_boxes_the_errors_are_one_image_of_level_edges():
    """Many boxes: one image, each pixel the upper edge of its box's level (never below
    the box's own error)."""
    from types import SimpleNamespace

    from matplotlib.figure import Figure

    from planar_tui.figures.certified import ERROR_LEVELS, draw_errors

    n = 150
    x = np.arange(n, dtype=float)
    lo_x, lo_y = np.meshgrid(x, x)
    boxes = np.column_stack([lo_x.ravel(), lo_x.ravel() + 1, lo_y.ravel(), lo_y.ravel() + 1])
    error = 0.01 + lo_x.ravel() / n
    bound = np.column_stack([error, 0.5 * error, error])
    bound[0] = np.inf
    ax = Figure().add_subplot()
    draw_errors(ax, SimpleNamespace(boxes=boxes, bound=bound))
    image = by_gid(ax.figure, "accuracy-image").get_array()
    top = error[1:].max()
    drawn = np.unique(image.compressed())
    assert drawn.max() == pytest.approx(top)
    assert drawn.min() >= error[1:].min() and len(drawn) <= ERROR_LEVELS
    assert len(drawn) > ERROR_LEVELS // 2


@pytest.mark.parametrize("kind", ["fivebar", "rpr", "prr"])
def test_the_other_robots_figures_have_the_error_panel(tmp_path, kind):
    from planar_tui.batch import run_job
    from tests.test_accuracy import PRISMATIC_ERROR_CM, fivebar_job, prismatic_job

    if kind == "fivebar":
        job = fivebar_job(tmp_path, precision=4.0)
    else:
        error = PRISMATIC_ERROR_CM[kind]
        job = prismatic_job(tmp_path, kind, actuator=error, tolerance=error, precision=4.0)
    result = run_job(job)
    fig = figure_for_result(job, result)
    assert "certified max(|Δx|, |Δy|) per box" in [ax.get_title() for ax in fig.axes]
    boxes, rows = labelled(result.extra_tables["boxes"], "accuracy-certified")
    error = np.array([max(float(r["dx_max_cm"]), float(r["dy_max_cm"])) for r in rows])
    assert len(boxes)
    heat = by_gid(fig, "accuracy")
    np.testing.assert_allclose(corners(heat), boxes)
    np.testing.assert_allclose(np.asarray(heat.get_array()), error, rtol=1e-12)
