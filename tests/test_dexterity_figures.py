"""The κ heat map in the workspace figures: a panel per job with ``kappa_max``, each box's
colour bin computed here from the boxes CSV's table (its ``kappa_hi``, empty when
unbounded; ``result.extra_tables["boxes"]``, what ``boxes_output`` writes), the
unbounded boxes hatched apart, the proved dexterous boxes as a layer on the workspace."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planar_tui.figures.dispatch import figure_for_result
from tests.test_dexterity import FIVEBAR, TABLE3, run

BINS = 8


def expected_bins(kappa_hi, kappa_max):
    """Bin of each finite bound: 8 equal bins of [1, kappa_max], 8 above kappa_max."""
    out = []
    for hi in kappa_hi:
        if hi > kappa_max:
            out.append(BINS)
        else:
            out.append(min(math.floor(BINS * (hi - 1.0) / (kappa_max - 1.0)), BINS - 1))
    return np.array(out)


def dexterity_rows(table):
    """The dexterity rows of a boxes table: boxes, ``kappa_hi`` (inf when empty), status."""
    rows = [dict(zip(table.header, r, strict=True)) for r in table.rows]
    rows = [r for r in rows if r["status"].startswith("dexterous")]
    boxes = np.array(
        [[float(r[k]) for k in ("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm")] for r in rows]
    )
    hi = np.array([float(r["kappa_hi"]) if r["kappa_hi"] else math.inf for r in rows])
    return boxes, hi, [r["status"] for r in rows]


def by_gid(fig, gid):
    (found,) = fig.findobj(lambda a: a.get_gid() == gid)
    return found


def corners(collection):
    """Each rectangle of a collection as ``x_lo, x_hi, y_lo, y_hi``."""
    return np.array(
        [
            [
                p.vertices[:, 0].min(),
                p.vertices[:, 0].max(),
                p.vertices[:, 1].min(),
                p.vertices[:, 1].max(),
            ]
            for p in collection.get_paths()
        ]
    ).reshape(-1, 4)


@pytest.fixture(scope="module")
def table3(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fig")
    job, result = run(folder, TABLE3.format(precision=0.5, kappa=4, extra=""))
    return job, result, result.extra_tables["boxes"]


def test_the_figure_has_a_kappa_panel_coloured_by_each_boxs_bin(table3):
    job, result, boxes_csv = table3
    fig = figure_for_result(job, result)
    titles = [ax.get_title() for ax in fig.axes]
    assert "κ upper bound per box" in titles
    boxes, hi, _ = dexterity_rows(boxes_csv)
    bounded = np.isfinite(hi)
    assert bounded.any() and (hi[bounded] > 4).any() and (hi[bounded] <= 4).any()
    heat = by_gid(fig, "kappa")
    np.testing.assert_array_equal(np.asarray(heat.get_array()), expected_bins(hi[bounded], 4.0))
    np.testing.assert_allclose(corners(heat), boxes[bounded])
    unbounded = by_gid(fig, "kappa-unbounded")
    np.testing.assert_allclose(corners(unbounded), boxes[~bounded])


def test_the_colours_follow_the_bins_and_the_dexterous_layer_holds_the_proved_boxes(table3):
    job, result, boxes_csv = table3
    fig = figure_for_result(job, result)
    boxes, hi, status = dexterity_rows(boxes_csv)
    heat = by_gid(fig, "kappa")
    heat.update_scalarmappable()
    colours = heat.get_facecolor()
    bins = expected_bins(hi[np.isfinite(hi)], 4.0)
    for b in np.unique(bins):  # one colour per bin, different bins different colours
        assert len(np.unique(colours[bins == b], axis=0)) == 1
    assert len(np.unique(colours, axis=0)) == len(np.unique(bins))
    proved = np.array([s == "dexterous" for s in status])
    np.testing.assert_allclose(corners(by_gid(fig, "dexterous")), boxes[proved])


def test_a_job_without_kappa_max_has_no_kappa_panel(tmp_path):
    text = TABLE3.format(precision=1.0, kappa=4, extra="").replace("kappa_max = 4\n", "")
    text = text.replace("elbow = [1, -1, 1]\n", "")
    job, result = run(tmp_path, text)
    fig = figure_for_result(job, result)
    assert "κ upper bound per box" not in [ax.get_title() for ax in fig.axes]
    assert not fig.findobj(lambda a: a.get_gid() in ("kappa", "dexterous"))


def test_the_five_bar_figure_has_the_panel_too(tmp_path):
    job, result = run(tmp_path, FIVEBAR.format(precision=1.0, kappa=3, extra=""))
    fig = figure_for_result(job, result)
    assert "κ upper bound per box" in [ax.get_title() for ax in fig.axes]
    _, hi, _ = dexterity_rows(result.extra_tables["boxes"])
    assert len(hi) > 20_000  # past MAX_DRAWN_BOXES: one image, its pixels the bins
    image = by_gid(fig, "kappa-image").get_array()
    drawn = np.unique(image.compressed())
    np.testing.assert_array_equal(drawn, np.unique(expected_bins(hi[np.isfinite(hi)], 3.0)))


def test_a_failing_certified_path_figure_marks_the_stretch_from_the_first_failure(tmp_path):
    from tests.test_app_dexterity import FAILING_PATH
    from tests.test_path3rrr import ROBOT

    job, result = run(tmp_path, ROBOT + FAILING_PATH)
    fig = figure_for_result(job, result)
    table = result.table
    t = np.array([row[0] for row in table.rows])
    xy = np.array([row[1:3] for row in table.rows])
    cert = dict(
        zip(result.certificate.table().header, result.certificate.table().rows[0], strict=True)
    )
    lo = cert["first_failure_lo_s"]
    assert cert["certified"] == "no" and 0.0 < lo < 1.0
    first = int(np.argmax(t >= lo))
    good, bad = by_gid(fig, "trace-certified"), by_gid(fig, "trace-failing")
    np.testing.assert_allclose(np.column_stack(good.get_data()), xy[: first + 1])
    np.testing.assert_allclose(np.column_stack(bad.get_data()), xy[first - 1 :])
    assert any(ax.get_title().startswith("not certified (kappa)") for ax in fig.axes)


def test_the_verdict_in_words_of_a_certified_path():
    from planar_tui.app.widgets.path_pane import failing_stretch, verdict_words
    from planar_tui.workspace.path.certify import Certificate

    yes = Certificate("yes", None, None, "", 4.0, 2.1, 2.2, 10)
    assert verdict_words(yes, 1.0).startswith("Certified: every leg closes")
    assert "[2.1, 2.2]" in verdict_words(yes, 1.0) and failing_stretch(yes, 1.0) is None
    unknown = Certificate("unknown", 0.25, None, "", 4.0, 2.1, 2.2, 10)
    assert verdict_words(unknown, 1.0).startswith("Undecided")
    assert failing_stretch(unknown, 1.0) == (0.25, 1.0)


def test_a_zoomed_kappa_view_marks_only_the_boxes_in_it():
    """The app's κ layer (:func:`~planar_tui.workspace.paving.kappa_map.view_cells`): a
    box outside the view marks no cell (the terminal map's clipping would put it on the
    edge), a box inside marks its cells with its kappa_hi."""
    from types import SimpleNamespace

    from planar_tui.workspace.paving.kappa_map import band_edges, cell_glyph, view_cells

    boxes = np.array([[0.0, 1.0, 0.0, 1.0], [5.0, 6.0, 0.0, 1.0]])
    kappa = np.array([[1.0, 1.5], [1.0, 3.9]])
    worst = view_cells(SimpleNamespace(boxes=boxes, kappa=kappa), (0.0, 2.0, 0.0, 1.0), 4, 2)
    assert np.nanmax(worst) == 1.5 and np.isnan(worst[:, 2:]).all()
    assert cell_glyph(1.5, band_edges(4.0), 4.0) == "1"
    assert cell_glyph(3.9, band_edges(4.0), 4.0) == "4"
    assert cell_glyph(4.1, band_edges(4.0), 4.0) == "?"


def test_a_ranged_jobs_figure_draws_its_kappa_panel_and_dexterous_layer(tmp_path):
    """``orientation_deg = [lo, hi]`` (κ the worst over the range): the figure of the
    ranged 3-RRR job has the κ panel, each bounded box of the boxes CSV in it with its
    bin, the unbounded ones hatched, the proved boxes as the dexterous layer, and a colour
    bar over [1, kappa_max]."""
    from tests.test_dexterity_orientation import RRR

    job, result = run(tmp_path, RRR.format(precision=1.0))
    assert isinstance(job.spec.orientation_deg, tuple)
    fig = figure_for_result(job, result)
    assert "κ upper bound per box" in [ax.get_title() for ax in fig.axes]
    boxes, hi, status = dexterity_rows(result.extra_tables["boxes"])
    bounded = np.isfinite(hi)
    assert bounded.any() and (~bounded).any() and (hi[bounded] <= 6).any()
    heat = by_gid(fig, "kappa")
    np.testing.assert_array_equal(np.asarray(heat.get_array()), expected_bins(hi[bounded], 6.0))
    np.testing.assert_allclose(corners(heat), boxes[bounded])
    np.testing.assert_allclose(corners(by_gid(fig, "kappa-unbounded")), boxes[~bounded])
    proved = np.array([s == "dexterous" for s in status])
    assert proved.any()
    np.testing.assert_allclose(corners(by_gid(fig, "dexterous")), boxes[proved])
    (bar,) = [ax for ax in fig.axes if ax.get_ylabel().startswith("κ upper bound (grey: > 6)")]
    labels = [tick.get_text() for tick in bar.get_yticklabels()]
    assert labels[0] == "1" and labels[-1] == "6"
