"""``planar-tui plot`` of a boxes CSV past :data:`MAX_DRAWN_BOXES` draws the boxes as one
image, says so in the figure and on stderr, and takes seconds (200 000 boxes
took 43 s under load, minutes in the corpus)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from planar_tui.figures import workspace
from planar_tui.figures.canvas import DISPLAY_NOTE, display_notes

HEADER = "x_lo_cm,x_hi_cm,y_lo_cm,y_hi_cm,status\n"


def boxes_csv(path, count: int) -> None:
    """A square grid of ``count`` boxes of side 0.5 cm from the origin, the left half
    inside, written as a boxes CSV."""
    side = int(np.ceil(np.sqrt(count)))
    j, i = np.divmod(np.arange(count), side)
    boxes = np.column_stack([0.5 * i, 0.5 * i + 0.5, 0.5 * j, 0.5 * j + 0.5])
    inside = i < side // 2
    status = np.where(inside, "inside", "boundary")
    lines = [
        f"{a:g},{b:g},{c:g},{d:g},{s}\n" for (a, b, c, d), s in zip(boxes, status, strict=True)
    ]
    path.write_text(HEADER + "".join(lines), encoding="utf-8")


def test_coverage_paints_each_box_and_at_least_one_pixel_of_a_small_one():
    boxes = np.array([[2.0, 5.0, 3.0, 4.0], [7.2, 7.4, 8.5, 8.6], [0.0, 1.0, 9.0, 10.0]])
    covered = workspace.coverage(boxes, (0.0, 0.0), 1.0, (10, 10))
    expected = np.zeros((10, 10), dtype=bool)
    expected[3, 2:5] = True  # rows are y
    expected[8, 7] = True  # 0.2 × 0.1 cm: one pixel
    expected[9, 0] = True  # on the grid's last row and column edge
    assert (covered == expected).all()


def test_past_the_bound_the_boxes_are_one_image_and_the_plot_says_so(tmp_path, cli, monkeypatch):
    monkeypatch.setattr(workspace, "MAX_DRAWN_BOXES", 50)
    monkeypatch.setattr(workspace, "IMAGE_PIXELS", 20)
    csv = tmp_path / "b.csv"
    boxes_csv(csv, 100)  # 10 × 10 boxes of 0.5 cm: a 5 cm square, 4 pixels a cm
    result = cli("plot", csv, "--out", tmp_path / "b.png")
    assert result.exit_code == 0, result.output
    assert result.stderr == (
        "b.csv: 100 boxes drawn as one image of 20 × 20 pixels (a box narrower than a pixel "
        "fills one)\n"
    )
    assert (tmp_path / "b.png").stat().st_size > 0
    from planar_tui.figures import figure_for_table, read_table

    figure = figure_for_table(read_table(csv), "b.csv")
    (image,) = figure.axes[0].get_images()
    pixels = image.get_array()
    from matplotlib.colors import to_rgba

    inside, boundary = to_rgba(workspace.INSIDE_COLOUR), to_rgba(workspace.BOUNDARY_COLOUR)
    assert (pixels[:, :10] == inside).all() and (pixels[:, 10:] == boundary).all()
    assert display_notes(figure) == [result.stderr.removeprefix("b.csv: ").rstrip("\n")]
    legend = [t.get_text() for t in figure.axes[0].get_legend().get_texts()]
    assert legend == ["inside (proved)", "boundary (kept)"]


def test_within_the_bound_each_box_is_a_rectangle_and_nothing_is_said(tmp_path, cli):
    csv = tmp_path / "b.csv"
    boxes_csv(csv, 100)
    result = cli("plot", csv, "--out", tmp_path / "b.png")
    assert result.exit_code == 0 and result.stderr == ""
    from planar_tui.figures import figure_for_table, read_table

    figure = figure_for_table(read_table(csv), "b.csv")
    assert not figure.axes[0].get_images() and not display_notes(figure)
    assert not figure.findobj(lambda a: a.get_gid() == DISPLAY_NOTE)


@pytest.mark.slow
def test_a_plot_of_200_000_boxes_takes_seconds(tmp_path, cli):
    """Goal 15 s (measured 20 s whole at load 4.5, matplotlib's import included; the
    rectangles took 6 s to draw alone, 28 s for 800 000); bound 10 × the goal."""
    csv = tmp_path / "b.csv"
    boxes_csv(csv, 200_000)
    started = time.perf_counter()
    result = cli("plot", csv, "--out", tmp_path / "b.png")
    elapsed = time.perf_counter() - started
    assert result.exit_code == 0, result.output
    # 448 boxes a row, 447 rows: 224 × 223.5 cm at 1200 / 224 pixels a cm, rounded up
    assert "200,000 boxes drawn as one image of 1200 × 1198 pixels" in result.stderr
    assert "can take minutes" not in result.stderr
    assert elapsed < 150.0
