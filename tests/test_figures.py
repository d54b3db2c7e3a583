"""Figures (planar_tui.figures): every kind drawn from a bundled preset's result (small
settings) to SVG and PNG, its artists counted and compared with the result's numbers, and
the `plot` command on every CSV kind."""

from __future__ import annotations

import dataclasses
import math
import struct
from pathlib import Path

import numpy as np
import pytest

from planar_tui import batch, figures
from planar_tui.csvio import CsvTable
from planar_tui.figures.canvas import DPI
from planar_tui.jobkind import JobKind, JobResult
from planar_tui.presets import load_preset
from planar_tui.registry import registered
from planar_tui.schema import integer, setting
from tests.conftest import PRESETS, REPO

FIXTURES = REPO / "tests" / "data" / "figures"


def _run(preset: str, key: str, **changes):
    job = next(j for j in load_preset(PRESETS / f"{preset}.toml").jobs if j.key == key)
    if changes:
        job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, **changes))
    (job,) = batch.prepare_jobs([job])
    return job, batch.run_job(job)


@pytest.fixture(scope="module")
def results():
    """One small run per kind, shared by the module's tests."""
    return {
        "simulate": _run("paper-a-table1", "simulate[1]", duration_s=0.05, every=5),
        "torques": _run("paper-a-table1", "torques"),
        "sensitivity": _run("paper-a-fig5-6", "sensitivity[1]", samples=64, efast_samples=80),
        "workspace": _run("paper-b-table3", "workspace[4]", precision_cm=0.9375),
    }


@pytest.fixture(scope="module")
def drawn(results):
    """Each kind's figure, drawn once."""
    return {kind: figures.figure_for_result(*pair) for kind, pair in results.items()}


def _by_gid(fig, gid: str, kind: str = "lines") -> list:
    return [a for ax in fig.axes for a in getattr(ax, kind) if a.get_gid() == gid]


def png_size(path: Path) -> tuple[int, int]:
    """Width and height from a PNG's IHDR chunk."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["simulate", "torques", "sensitivity", "workspace"])
def test_each_kind_saves_as_svg_and_png_of_the_figure_size(results, drawn, kind, tmp_path):
    fig = drawn[kind]
    width, height = fig.get_size_inches()
    from planar_tui.figures.canvas import save

    svg = save(fig, tmp_path / "f.svg")
    png = save(fig, tmp_path / "f.png")
    assert svg.read_text(encoding="utf-8").lstrip().startswith("<?xml")
    assert "<svg" in svg.read_text(encoding="utf-8")
    assert png_size(png) == (round(width * DPI), round(height * DPI))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png", "f.svg"]  # no temp file


def test_simulate_figure_has_a_line_per_joint_and_the_tip_of_the_csv_angles(results, drawn):
    job, result = results["simulate"]
    fig = drawn["simulate"]
    n = job.robot.n_links
    series = _by_gid(fig, "series")
    assert len(series) == 2 * n + 3 + 1  # angles, rates, 3 energies, the drift
    (tip,) = _by_gid(fig, "tip")
    assert len(_by_gid(fig, "arm")) == 5
    # the tip by an explicit sum over the links of the CSV's angles
    rows = np.asarray([row[: n + 1] for row in result.table.rows])  # κ may be empty
    for row, (x, y) in zip(rows, tip.get_xydata(), strict=True):
        phi = xs = ys = 0.0
        for length, theta in zip(job.robot.lengths_m, row[1 : n + 1], strict=True):
            phi += theta
            xs += length * math.cos(phi)
            ys += length * math.sin(phi)
        assert (x, y) == pytest.approx((xs, ys), abs=1e-12)


def test_torques_figure_has_one_bar_per_joint_and_state_of_the_csv_height(results, drawn):
    job, result = results["torques"]
    ax = drawn["torques"].axes[0]
    heights = [bar.get_height() for container in ax.containers for bar in container]
    tau = np.asarray(result.table.rows)[:, -job.robot.n_links :]
    assert heights == pytest.approx(tau.T.ravel().tolist(), abs=0.0)
    assert len(_by_gid(drawn["torques"], "arm")) == len(tau)


def test_sensitivity_bars_stack_the_csv_percent_per_speed_and_method(results, drawn):
    job, result = results["sensitivity"]
    fig = drawn["sensitivity"]
    bar_axes = [ax for ax in fig.axes if ax.get_gid() == "bars"]
    n, speeds, methods = job.robot.n_links, len(job.spec.speeds_rad_s), len(job.spec.methods)
    d = 2 * n
    assert len(bar_axes) == n
    rows = result.table.rows
    header = result.table.header
    col = {name: header.index(name) for name in header}
    from matplotlib.container import ErrorbarContainer

    for torque, ax in enumerate(bar_axes, start=1):
        bars = [p for p in ax.patches if p.get_width() > 0]
        assert len(bars) == speeds * methods * d
        # the stacks, bottom to top, at each x: the CSV's percents of one speed and method
        stacks: dict[float, list] = {}
        for bar in sorted(bars, key=lambda b: (b.get_x(), b.get_y())):
            stacks.setdefault(round(bar.get_x(), 9), []).append(bar.get_height())
        assert len(stacks) == speeds * methods
        for speed in job.spec.speeds_rad_s:
            for method in job.spec.methods:
                expected = [
                    r[col["percent"]]
                    for r in rows
                    if r[col["torque"]] == torque
                    and r[col["speed_rad_s"]] == speed
                    and r[col["method"]] == method
                ]
                assert sum(expected) == pytest.approx(100.0)
                assert any(s == pytest.approx(expected, abs=1e-9) for s in stacks.values())
        # one error bar per segment whose index has a half-width (here every ST_conf > 0)
        (error_bars,) = [c for c in ax.containers if isinstance(c, ErrorbarContainer)]
        (segments,) = error_bars.lines[2]
        with_conf = [r for r in rows if r[col["torque"]] == torque and r[col["ST_conf"]] > 0]
        assert len(segments.get_segments()) == len(with_conf) > 0
    (matrix,) = [ax for ax in fig.axes if ax.get_gid() == "matrix"]
    cells = [t for t in matrix.texts if t.get_gid() == "cell"]
    middle = sorted(job.spec.speeds_rad_s)[len(job.spec.speeds_rad_s) // 2]
    at_middle = [r for r in rows if r[col["speed_rad_s"]] == middle]
    assert len(cells) == n * methods * d == len(at_middle)
    assert sorted(t.get_text() for t in cells) == sorted(
        f"{r[col['percent']]:.1f}" for r in at_middle
    )


def test_workspace_figure_boxes_exact_boundary_and_a_robot_pose_within_its_limits(results, drawn):
    job, result = results["workspace"]
    fig = drawn["workspace"]
    statuses = [row[-1] for row in result.extra_tables["boxes"].rows]
    inside = [c for ax in fig.axes for c in ax.collections if c.get_gid() == "inside"]
    boundary = [c for ax in fig.axes for c in ax.collections if c.get_gid() == "boundary"]
    assert len(inside[0].get_paths()) == statuses.count("inside")
    assert len(boundary[0].get_paths()) == statuses.count("boundary")
    # the exact boundary: its shoelace area is the geometric area (720 segments a turn)
    rings = _by_gid(fig, "exact")
    area = sum(
        0.5 * abs(np.dot(x, np.roll(y, 1)) - np.dot(y, np.roll(x, 1)))
        for x, y in (ring.get_data() for ring in rings[::2])
    )
    assert area == pytest.approx(result.outcome.geometric.area_cm2, rel=2e-3)
    # the legs: A -> B of length l1 at an angle within the limits, B -> C of length l2
    legs = _by_gid(fig, "leg")
    assert len(legs) == 3
    robot = job.robot
    for (lo, hi), leg in zip(job.spec.joint_limits_deg, legs, strict=True):
        (ax_, ay), (bx, by), (cx, cy) = leg.get_xydata()
        assert math.hypot(bx - ax_, by - ay) == pytest.approx(robot.proximal_cm, rel=1e-12)
        assert math.hypot(cx - bx, cy - by) == pytest.approx(robot.distal_cm, rel=1e-12)
        angle = math.degrees(math.atan2(by - ay, bx - ax_)) % 360
        assert lo - 1e-9 <= angle <= hi + 1e-9
    (point,) = _by_gid(fig, "point")
    px, py = point.get_xydata()[0]
    boxes = np.asarray(result.outcome.boxes)
    assert np.any(
        (boxes[:, 0] <= px) & (px <= boxes[:, 1]) & (boxes[:, 2] <= py) & (py <= boxes[:, 3])
    )


FIXTURE_KINDS = {
    "sweep-orientation.csv": "sweep",
    "sweep-grid.csv": "sweep",
    "motion-band.csv": "motion uncertainty band",
    "motion-indices.csv": "motion uncertainty indices",
}


def test_sweep_figures_mark_the_failed_points():
    one = figures.figure_for_table(figures.read_table(FIXTURES / "sweep-orientation.csv"))
    failed = _by_gid(one, "failed")
    assert failed and all(len(line.get_xdata()) == 1 for line in failed)
    assert failed[0].get_xdata()[0] == 10  # point 4: orientation 10 deg
    lines = _by_gid(one, "sweep")
    # 6 figures: area_geometric_error_cm2 holds 0.001 at every point, no panel
    assert len(lines) == 6 and all(len(line.get_xdata()) == 4 for line in lines)
    two = figures.figure_for_table(figures.read_table(FIXTURES / "sweep-grid.csv"))
    heat = _by_gid(two, "heat", "collections")
    assert len(heat) == 2 and heat[0].get_array().shape == (9,)  # 3 x 3 cells, row-major
    assert heat[0].get_array().mask[4]  # point 5 (distal 30, orientation 0) failed
    assert _by_gid(two, "failed")[0].get_xydata().tolist() == [[0.0, 30.0]]


def test_motion_band_figure_has_a_band_and_a_mean_per_output():
    table = figures.read_table(FIXTURES / "motion-band.csv")
    fig = figures.figure_for_table(table)
    assert len(_by_gid(fig, "band", "collections")) == 4
    means = _by_gid(fig, "mean")
    assert len(means) == 4
    assert means[2].get_ydata().tolist() == [row[11] for row in table.rows]  # tip_x_m_mean


def test_motion_indices_figure_has_a_panel_per_output():
    fig = figures.figure_for_table(figures.read_table(FIXTURES / "motion-indices.csv"))
    bar_axes = [ax for ax in fig.axes if ax.get_gid() == "bars"]
    assert [ax.get_title() for ax in bar_axes] == ["theta1_rad", "tip_x_m"]
    assert all(len(ax.patches) >= 2 * 2 * 4 for ax in bar_axes)


@pytest.fixture(scope="module")
def csv_files(results, tmp_path_factory):
    """Every CSV kind the project writes, plus the sweep and motion-uncertainty shapes."""
    folder = tmp_path_factory.mktemp("csv")
    files = {}
    for kind, (job, result) in results.items():
        (plan,) = batch.plan_outputs([job], folder)
        plan = dataclasses.replace(
            plan, extras={"boxes": folder / "boxes.csv"} if kind == "workspace" else {}
        )
        written = batch.write_result(plan, result)
        files[written[0].name] = "workspace summary" if kind == "workspace" else kind
        if kind == "workspace":
            files["boxes.csv"] = "workspace boxes"
    for name, kind in FIXTURE_KINDS.items():
        (folder / name).write_bytes((FIXTURES / name).read_bytes())
        files[name] = kind
    return folder, files


@pytest.mark.slow
def test_plot_command_draws_every_csv_kind(cli, csv_files, tmp_path):
    folder, files = csv_files
    assert len(set(files.values())) == 8 and len(files) == 9
    for name, kind in files.items():
        table = figures.read_table(folder / name)
        assert figures.recognise(table.header) == kind, name
        out = tmp_path / f"{name}.svg"
        result = cli("plot", folder / name, "--out", out)
        assert result.exit_code == 0, result.output
        assert out.stat().st_size > 1000
    # the default: RESULT.png beside the CSV
    name = next(n for n, k in files.items() if k == "torques")
    assert cli("plot", folder / name).exit_code == 0
    assert png_size((folder / name).with_suffix(".png"))[0] > 100


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("a,b\n1,2\n", "(header): is 'a,b', the header of no result CSV"),
        ("", "(file): cannot be read"),
    ],
)
def test_plot_of_a_csv_it_does_not_know_is_one_line_exit_2(cli, tmp_path, text, fragment):
    path = tmp_path / "x.csv"
    path.write_text(text, encoding="utf-8")
    result = cli("plot", path)
    assert result.exit_code == 2
    assert result.stderr.count("\n") == 1 and fragment in result.stderr
    assert result.stderr.startswith(f"error: {path}: ")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.csv"]


@pytest.mark.parametrize("command", [["plot", "RESULT"], ["torques", "paper-a-table1"]])
def test_a_figure_suffix_that_names_no_format_is_exit_2(cli, tmp_path, command):
    args = [str(tmp_path / "r.csv") if a == "RESULT" else a for a in command]
    option = "--out" if command[0] == "plot" else "--plot"
    extra = ["--out-dir", tmp_path] if option == "--plot" else []
    result = cli(*args, option, tmp_path / "f.gif", *extra)
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: command line: {option}: is '{tmp_path / 'f.gif'}': has the suffix '.gif' "
        "(expected a file ending .svg, .png, .pdf)\n"
    )
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_plot_option_with_several_jobs_writes_numbered_figures(cli, tmp_path):
    result = cli("simulate", "paper-a-table1", "--out-dir", tmp_path, "--plot", tmp_path / "s.png")
    assert result.exit_code == 0, result.output
    assert png_size(tmp_path / "s-1.png")[0] > 100 and png_size(tmp_path / "s-2.png")[0] > 100
    one = tmp_path / "one"
    result = cli(
        "run", "paper-a-table1", "--job", "torques", "--out-dir", one, "--plot", one / "t.svg"
    )
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in one.iterdir()) == [
        "t.svg",
        "table1-6r-torques.csv",
        "table1-6r-torques.csv.json",
    ]


def test_plot_key_of_a_job_table_writes_its_figure_and_is_checked(cli, tmp_path):
    text = (PRESETS / "paper-a-table1.toml").read_text(encoding="utf-8")
    preset = tmp_path / "p.toml"
    preset.write_text(
        text.replace('output = "table1-6r-torques.csv"', 'output = "t.csv"\nplot = "t.pdf"')
    )
    out = tmp_path / "out"
    assert cli("torques", preset, "--out-dir", out).exit_code == 0
    assert (out / "t.pdf").read_bytes()[:5] == b"%PDF-"
    preset.write_text(text.replace('output = "table1-6r-torques.csv"', 'plot = "t.jpg"'))
    result = cli("torques", preset, "--out-dir", tmp_path / "bad")
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: {preset}: torques.plot: is 't.jpg': has the suffix '.jpg' "
        "(expected a file ending .svg, .png, .pdf)\n"
    )
    assert not (tmp_path / "bad").exists()


def test_every_job_table_with_a_figure_has_the_plot_key():
    """A kind that draws a figure takes a ``plot`` key; one whose ``figure`` is ``None``
    needs none (the next test)."""
    from planar_tui.presets import JOB_KINDS

    drawn = [(name, kind) for name, kind in JOB_KINDS.items() if kind.figure is not None]
    assert len(drawn) >= 8  # every bundled kind draws one
    for name, kind in drawn:
        names = {field.name for field in dataclasses.fields(kind.settings)}
        assert "plot" in names, f"[{name}] has no plot key"


@dataclasses.dataclass(frozen=True, kw_only=True)
class _CountSpec:
    count: int = setting(integer(minimum=1), type_doc="integer", doc="rows", default=2)


def _run_count(job, progress):
    rows = [[i] for i in range(job.spec.count)]
    return JobResult(table=CsvTable(("i",), rows), summary=f"{job.spec.count} rows")


def test_a_kind_without_a_figure_needs_no_plot_key(cli, tmp_path):
    """A kind declaring no figure and no ``plot`` key is read, run and written as any."""
    kind = JobKind("counting", "robot", _CountSpec, _run_count, "rows counted")
    assert kind.figure is None and "plot" not in kind.keys
    preset = tmp_path / "count.toml"
    preset.write_text(
        '[robot]\nlengths_m = [0.3]\nmasses_kg = [1.0]\n\n[counting]\ncount = 3\noutput = "c.csv"\n'
    )
    with registered(kind):
        result = cli("run", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "c.csv").read_text().split() == ["i", "0", "1", "2"]


def test_a_sweep_without_a_varied_column_and_a_folder_as_figure_are_one_line_exit_2(cli, tmp_path):
    flat = tmp_path / "flat.csv"
    flat.write_text("point,orientation_deg,area_kept_cm2,status,message,seconds\n1,0,5.0,ok,,0.1\n")
    result = cli("plot", flat)
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: {flat}: (content): cannot be drawn: the sweep has no varied key column\n"
    )
    folder = tmp_path / "f.png"
    folder.mkdir()
    result = cli("torques", "paper-a-table1", "--out-dir", tmp_path, "--plot", folder)
    assert result.exit_code == 2
    assert (
        result.stderr == f"error: {folder}: (output): is a folder (expected a figure file path)\n"
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png", "flat.csv"]


def test_workspace_figure_draws_the_singular_boxes_and_the_free_circle(tmp_path):
    """A job with ``singularities = true``: one rectangle per box that may be singular and
    the circle of the certified radius ``r_in`` about the centre, as the result says."""
    from matplotlib.patches import Circle

    preset = tmp_path / "singular.toml"
    preset.write_text(
        "[robot3rrr]\nbase_side_cm = 120\nplatform_side_cm = 40\nproximal_cm = 30\n"
        "distal_cm = 30\n\n[workspace]\njoint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        'orientation_deg = 0\nprecision_cm = 0.5\nform = "arc-distance"\nsingularities = true\n'
        'elbow = [1, -1, 1]\nsingularity_precision_cm = 0.25\noutput = "s.csv"\n'
    )
    (job,) = batch.prepare_jobs(load_preset(preset).jobs)
    result = batch.run_job(job)
    singular = result.singularity.singular_boxes
    assert len(singular) > 0
    fig = figures.figure_for_result(job, result)
    (collection,) = _by_gid(fig, "singular", "collections")
    assert len(collection.get_paths()) == len(singular)
    (circle,) = [p for ax in fig.axes for p in ax.patches if p.get_gid() == "circle"]
    assert isinstance(circle, Circle)
    assert circle.get_radius() == result.singularity.radius_lo_cm
    assert tuple(circle.center) == tuple(result.singularity.centre_cm)
    figures.save_result_figure(job, result, tmp_path / "s.svg")
    assert (tmp_path / "s.svg").stat().st_size > 0


def test_sweep_figure_leaves_out_columns_that_echo_the_varied_key():
    """A workspace sweep over ``orientation_deg`` reports ``orientation_lo_deg`` and
    ``orientation_hi_deg`` equal to it: echoes of the key, not figures to plot."""
    from planar_tui.csvio import CsvTable
    from planar_tui.figures.sweep import split_columns

    header = (
        "point",
        "orientation_deg",
        "area_kept_cm2",
        "orientation_lo_deg",
        "status",
        "message",
        "seconds",
    )
    rows = [
        (1, -10.0, 90.5, -10.0, "ok", "", 0.1),
        (2, 0.0, 106.8, 0.0, "ok", "", 0.1),
        (3, 10.0, 90.5, 10.0, "ok", "", 0.1),
    ]
    assert split_columns(CsvTable(header, rows)) == (["orientation_deg"], ["area_kept_cm2"])


# -- sweeps over text and list-valued keys --------------------------------------------

FORMS_HEADER = (
    "point,form,strategy,precision_cm,boxes_processed,area_kept_cm2,"
    "orientation_lo_deg,status,message,seconds"
)


def _table(tmp_path, header: str, rows: list[str]):
    path = tmp_path / "sweep.csv"
    path.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    return figures.read_table(path)


def test_a_sweep_over_a_text_key_puts_its_values_on_the_x_axis(tmp_path):
    from planar_tui.figures.sweep import split_columns

    table = _table(
        tmp_path,
        FORMS_HEADER,
        [
            "1,natural,legwise,0.9375,3907,137.1,0.0,ok,,0.3",
            "2,slope,legwise,0.9375,4496,140.6,0.0,ok,,0.1",
            "3,mean-value,legwise,0.9375,5628,145.9,0.0,failed,boom,0.1",
        ],
    )
    varied, shown = split_columns(table)
    assert varied == ["form"]  # not boxes_processed, the first output that varies
    assert shown[:2] == ["boxes_processed", "area_kept_cm2"]
    fig = figures.figure_for_table(table)
    ax = fig.axes[1]  # area_kept_cm2
    assert ax.get_xlabel() == "form" and ax.get_ylabel() == "area_kept_cm2"
    assert [t.get_text() for t in ax.get_xticklabels()] == ["natural", "slope", "mean-value"]
    (points,) = [line for line in ax.lines if line.get_gid() == "sweep"]
    assert points.get_xydata().tolist() == [[0.0, 137.1], [1.0, 140.6]]
    assert points.get_linestyle() == "None"  # categories: points, no line between them
    (failed,) = [line for line in ax.lines if line.get_gid() == "failed"]
    assert failed.get_xdata().tolist() == [2.0]


def test_a_text_key_with_a_numeric_key_draws_one_line_per_value(tmp_path):
    header = "point,form,orientation_deg,strategy,area_kept_cm2,status,message,seconds"
    rows = [
        f"{k},{form},{phi},legwise,{area},ok,,0.1"
        for k, (form, phi, area) in enumerate(
            [
                ("natural", -10, 167.9),
                ("natural", 0, 137.1),
                ("natural", 10, 167.8),
                ("mean-value", -10, 166.1),
                ("mean-value", 0, 145.9),
                ("mean-value", 10, 166.2),
            ],
            start=1,
        )
    ]
    fig = figures.figure_for_table(_table(tmp_path, header, rows))
    (ax,) = fig.axes
    lines = [line for line in ax.lines if line.get_gid() == "sweep"]
    assert [line.get_label() for line in lines] == ["form = natural", "form = mean-value"]
    assert lines[0].get_xydata().tolist() == [[-10, 167.9], [0, 137.1], [10, 167.8]]
    assert lines[1].get_xydata().tolist() == [[-10, 166.1], [0, 145.9], [10, 166.2]]
    assert ax.get_xlabel() == "orientation_deg"


def test_two_text_keys_draw_a_heat_map_with_labelled_ticks(tmp_path):
    header = "point,form,strategy,area_kept_cm2,status,message,seconds"
    cells = {
        ("natural", "legwise"): 1.0,
        ("natural", "joint"): 2.0,
        ("slope", "legwise"): 3.0,
        ("slope", "joint"): 4.0,
        ("mean-value", "legwise"): 5.0,
        ("mean-value", "joint"): 6.0,
    }
    rows = [
        f"{k},{form},{strategy},{value},ok,,0.1"
        for k, ((form, strategy), value) in enumerate(cells.items(), start=1)
    ]
    fig = figures.figure_for_table(_table(tmp_path, header, rows))
    (image,) = _by_gid(fig, "heat", "collections")
    ax = image.axes
    assert [t.get_text() for t in ax.get_xticklabels()] == ["natural", "slope", "mean-value"]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["legwise", "joint"]
    assert np.asarray(image.get_array()).tolist() == [1.0, 3.0, 5.0, 2.0, 4.0, 6.0]


def test_a_list_valued_key_is_categorical_in_memory_and_read_back(tmp_path):
    from planar_tui.csvio import CsvTable, write_csv_atomic

    header = ("point", "theta_deg[1]", "tau1_Nm", "status", "message", "seconds")
    rows = [(1, [0, 0], 1.5, "ok", "", 0.1), (2, [10, 20], 2.5, "ok", "", 0.1)]
    table = CsvTable(header, rows)
    write_csv_atomic(tmp_path / "lists.csv", table)
    for source in (table, figures.read_table(tmp_path / "lists.csv")):
        (ax,) = figures.figure_for_table(source).axes
        assert [t.get_text() for t in ax.get_xticklabels()] == ["[0, 0]", "[10, 20]"]
        (points,) = _by_gid(ax.figure, "sweep")
        assert points.get_xydata().tolist() == [[0.0, 1.5], [1.0, 2.5]]


def test_an_output_column_is_never_an_axis(cli, tmp_path):
    # no key column varies (one form), only outputs do: refused, not drawn against one
    table = _table(
        tmp_path,
        FORMS_HEADER,
        [
            "1,natural,legwise,0.9375,3907,137.1,0.0,ok,,0.3",
            "2,natural,legwise,0.9375,4496,140.6,0.0,ok,,0.1",
        ],
    )
    with pytest.raises(ValueError, match="no varied key column"):
        figures.figure_for_table(table)
    result = cli("plot", tmp_path / "sweep.csv")
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: {tmp_path / 'sweep.csv'}: (content): cannot be drawn: "
        "the sweep has no varied key column\n"
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sweep.csv"]


# -- tables the plot command refuses ---------------------------------------------------


def test_plot_of_a_header_without_rows_is_one_line_exit_2_for_every_kind(cli, csv_files, tmp_path):
    """Every kind but the workspace boxes (see the next test): the message names what is
    expected."""
    folder, files = csv_files
    refused = {name: kind for name, kind in files.items() if kind != "workspace boxes"}
    assert len(refused) == len(files) - 1
    for name, kind in refused.items():
        header = (folder / name).read_text(encoding="utf-8").splitlines()[0]
        empty = tmp_path / name
        empty.write_text(header + "\n", encoding="utf-8")
        assert figures.recognise(figures.read_table(empty).header) == kind
        result = cli("plot", empty, "--out", tmp_path / "f.svg")
        assert result.exit_code == 2, (name, result.output)
        assert result.stderr == (
            f"error: {empty}: (content): cannot be drawn: the table has a header but no data "
            "rows (expected at least one row)\n"
        )
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(refused)  # nothing written


def test_plot_of_the_boxes_csv_of_a_geometric_workspace_job_draws_empty_cm_axes(cli, tmp_path):
    """The geometric form keeps no boxes, so its boxes CSV is header-only in normal use:
    drawn as the empty axes in cm with a note, not refused."""
    job, result = _run("paper-b-table3", "workspace[7]")
    assert job.spec.form == "geometric"
    (plan,) = batch.plan_outputs([job], tmp_path)
    boxes = tmp_path / "boxes.csv"
    batch.write_result(dataclasses.replace(plan, extras={"boxes": boxes}), result)
    assert boxes.read_text(encoding="utf-8").splitlines() == [
        "x_lo_cm,x_hi_cm,y_lo_cm,y_hi_cm,status"
    ]
    out = tmp_path / "boxes.svg"
    plotted = cli("plot", boxes, "--out", out)
    assert plotted.exit_code == 0, plotted.output
    assert out.stat().st_size > 1000
    (ax,) = figures.figure_for_table(figures.read_table(boxes)).axes
    assert [t.get_text() for t in ax.texts if t.get_gid() == "note"] == ["no boxes kept"]
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_aspect()) == ("x (cm)", "y (cm)", 1.0)
    assert all(len(c.get_paths()) == 0 for c in ax.collections)


def test_plot_of_a_folder_is_one_line_exit_2(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for argument in (".", str(tmp_path)):
        result = cli("plot", argument)
        assert result.exit_code == 2
        assert (
            result.stderr
            == f"error: {argument}: (file): is a folder (expected a result CSV file)\n"
        )
    assert list(tmp_path.iterdir()) == []


# -- bundled presets' sweep and motion-uncertainty results ------------------------------


def _shrunk(tmp_path, preset: str, replacements: dict[str, str]) -> Path:
    """A bundled preset with smaller settings (each replacement must apply)."""
    text = (PRESETS / f"{preset}.toml").read_text(encoding="utf-8")
    for old, new in replacements.items():
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / f"{preset}.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _saved_as_svg_and_png(fig, folder: Path) -> None:
    from planar_tui.figures.canvas import save

    width, height = fig.get_size_inches()
    svg, png = save(fig, folder / "f.svg"), save(fig, folder / "f.png")
    assert "<svg" in svg.read_text(encoding="utf-8") and svg.stat().st_size > 10_000
    assert png_size(png) == (round(width * DPI), round(height * DPI))


@pytest.mark.slow
def test_bundled_orientation_sweep_figure_to_svg_and_png(tmp_path):
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    path = _shrunk(
        tmp_path,
        "sweep-3rrr-orientation",
        {
            "precision_cm = 0.46875 ": "precision_cm = 0.9375 ",
            "refine_precision_cm = 0.029296875": "refine_precision_cm = 0.46875",
            "count = 25": "count = 3",
        },
    )
    (sweep,) = parse_sweeps(load_preset(path))
    run = run_sweep(sweep)
    fig = figures.figure_for_table(run.table, sweep.label)
    panel = {ax.get_ylabel(): ax for ax in fig.axes if ax.get_visible()}
    assert all(ax.get_xlabel() == "orientation_deg" for ax in panel.values())
    assert "orientation_lo_deg" not in panel and "precision_cm" not in panel  # echoes
    kept, inside, exact = (
        _by_gid(panel[name].figure, "sweep")[list(panel).index(name)].get_xydata()
        for name in ("area_kept_cm2", "area_inside_cm2", "area_geometric_cm2")
    )
    assert kept[:, 0].tolist() == inside[:, 0].tolist() == [-60.0, 0.0, 60.0]
    # the drawn bracket holds the exact area at every orientation; phi = 0 is Table 3's
    assert np.all(inside[:, 1] <= exact[:, 1]) and np.all(exact[:, 1] <= kept[:, 1])
    assert exact[1, 1] == pytest.approx(106.750, abs=1e-3)
    _saved_as_svg_and_png(fig, tmp_path)


@pytest.mark.slow
def test_bundled_motion_uncertainty_figures_to_svg_and_png(tmp_path):
    path = _shrunk(
        tmp_path,
        "paper-a-table1-motion",
        {
            "duration_s = 1.0": "duration_s = 0.02",
            "samples = 256": "samples = 8",
            "at_s = [0.25, 0.5, 1.0]": "at_s = [0.01, 0.02]",
        },
    )
    (job,) = batch.prepare_jobs(load_preset(path).jobs)
    result = batch.run_job(job)
    band = figures.figure_for_result(job, result)
    means = _by_gid(band, "mean")
    outputs = [ax.get_title() for ax in band.axes if ax.get_visible()]
    assert len(means) == len(outputs) == result.band.shape[2]
    for k, line in enumerate(means):
        assert line.get_xdata().tolist() == result.t_s.tolist()
        assert line.get_ydata().tolist() == result.band[:, 0, k].tolist()
    # the first output's band: the polygon between its 5th and 95th percentiles
    polygon = _by_gid(band, "band", "collections")[0].get_paths()[0].vertices
    assert polygon[:, 1].min() == pytest.approx(result.band[:, 2, 0].min(), abs=0)
    assert polygon[:, 1].max() == pytest.approx(result.band[:, 4, 0].max(), abs=0)
    _saved_as_svg_and_png(band, tmp_path)
    indices = figures.figure_for_table(result.extra_tables["indices"], job.label)
    # indices at every recorded time (more than MAX_BAR_TIMES): shares stacked against time,
    # one panel per output and method, titled "OUTPUT (METHOD)"
    stacked = [ax.get_title() for ax in indices.axes if ax.get_gid() == "stacked"]
    assert stacked and stacked[0].split(" (")[0] == outputs[0]
    (tmp_path / "f.svg").unlink()
    _saved_as_svg_and_png(indices, tmp_path)


# -- the simulate figure's energy balance ------------------------------------------------


def test_simulate_energy_panel_is_the_drift_net_of_the_torques_work(tmp_path):
    """Table 1's torque run: the energy grows by the work of the constant torques,
    ``W = Σ τ_i (θ_i(t) − θ_i(0))``; net of it, RK4 at 1e-4 s conserves energy."""
    job, result = _run("paper-a-table1", "simulate[1]", duration_s=0.3, every=10)
    assert any(job.spec.torques_Nm)
    fig = figures.figure_for_result(job, result)
    (ax,) = [ax for ax in fig.axes if ax.get_ylabel() == "E − E(0) − W (J)"]
    (line,) = ax.lines
    energy = result.kinetic_J + result.potential_J
    work = sum(
        tau * (result.theta_rad[:, i] - result.theta_rad[0, i])
        for i, tau in enumerate(job.spec.torques_Nm)
    )
    assert np.max(np.abs(energy - energy[0])) > 0.5  # the torques' work, not drift
    assert np.max(np.abs(line.get_ydata())) < 1e-9
    assert line.get_ydata() == pytest.approx(energy - energy[0] - work, abs=1e-12)
    assert ax.get_title().startswith("drift, max ")
    fig.canvas.draw()  # the title fits over its panel
    assert ax.title.get_window_extent().width < ax.get_window_extent().width


def test_simulate_figure_from_a_csv_alone_names_the_torques_work_not_a_drift(results):
    _, result = results["simulate"]
    fig = figures.figure_for_table(result.table)
    (ax,) = [ax for ax in fig.axes if ax.get_ylabel() == "E(t) − E(0) (J)"]
    energy = result.kinetic_J + result.potential_J
    assert ax.lines[0].get_ydata().tolist() == (energy - energy[0]).tolist()
    assert ax.get_title().startswith("≈ torques' work W, max ") and "drift" not in ax.get_title()
    fig.canvas.draw()
    assert ax.title.get_window_extent().width < ax.get_window_extent().width


# -- sweep heat maps over uneven values, sweeps where every point failed ---------------


def test_a_heat_map_over_uneven_values_centres_each_cell_on_its_values(tmp_path):
    orientations, precisions = [5, 10, 40], [0.5, 1, 2, 4]
    values = {
        (5, 0.5): 11.0,
        (5, 1): 12.5,
        (5, 2): 13.0,
        (5, 4): 14.25,
        (10, 0.5): 21.0,
        (10, 1): 22.0,
        (10, 2): 23.5,
        (10, 4): 24.0,
        (40, 0.5): 31.5,
        (40, 1): 32.0,
        (40, 2): 33.0,
        (40, 4): 34.75,
    }
    rows, number = [], 0
    for phi in orientations:
        for eps in precisions:
            number += 1
            status = "failed,boom" if (phi, eps) == (10, 2) else "ok,"
            cell = "" if status != "ok," else values[phi, eps]
            rows.append(f"{number},{phi},{eps},{cell},{status},0.1")
    header = "point,orientation_deg,precision_cm,area_kept_cm2,status,message,seconds"
    fig = figures.figure_for_table(_table(tmp_path, header, rows))
    (heat,) = _by_gid(fig, "heat", "collections")
    colours = heat.get_array()
    centres = []
    for path, colour in zip(heat.get_paths(), colours, strict=True):
        corners = path.vertices[:4]
        centre = (
            (corners[:, 0].min() + corners[:, 0].max()) / 2,
            (corners[:, 1].min() + corners[:, 1].max()) / 2,
        )
        centres.append(centre)
        if centre == (10, 2):
            assert colour is np.ma.masked  # the failed point: no colour
        else:
            assert colour == values[centre]
    assert sorted(centres) == sorted(values)  # one cell per point, on its values
    (failed,) = _by_gid(fig, "failed")
    assert failed.get_xydata().tolist() == [[10.0, 2.0]]


def test_a_sweep_where_every_point_failed_draws_the_failures_along_its_keys(cli, tmp_path):
    header = "point,orientation_deg,status,message,seconds"
    rows = ["1,5.0,failed,boom,0.2", "2,10.0,failed,boom,0.1"]
    path = tmp_path / "sweep.csv"
    path.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    fig = figures.figure_for_table(figures.read_table(path))
    (ax,) = [ax for ax in fig.axes if ax.get_visible()]
    (failed,) = _by_gid(fig, "failed")
    assert failed.get_xdata().tolist() == [5.0, 10.0]
    assert ax.get_xlabel() == "orientation_deg"
    assert [t.get_text() for t in ax.texts if t.get_gid() == "note"] == ["no point succeeded"]
    result = cli("plot", path, "--out", tmp_path / "f.svg")
    assert result.exit_code == 0, result.output
    # two keys, and figure columns left empty by the failures
    header = "point,orientation_deg,precision_cm,area_kept_cm2,status,message,seconds"
    rows = [
        f"{k},{phi},{eps},,failed,boom,0.1"
        for k, (phi, eps) in enumerate([(5, 1), (5, 2), (10, 1), (10, 2)], start=1)
    ]
    fig = figures.figure_for_table(_table(tmp_path, header, rows))
    (ax,) = [ax for ax in fig.axes if ax.get_visible()]
    (failed,) = _by_gid(fig, "failed")
    assert failed.get_xydata().tolist() == [[5, 1], [5, 2], [10, 1], [10, 2]]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("orientation_deg", "precision_cm")
    assert [t.get_text() for t in ax.texts if t.get_gid() == "note"] == ["no point succeeded"]


TORQUES_CSV = (
    "theta1_rad,theta2_rad,omega1_rad_s,omega2_rad_s,alpha1_rad_s2,alpha2_rad_s2,tau1_Nm,tau2_Nm\n"
)


def _plot_refused(cli, path, fragment, *options):
    result = cli("plot", path, *options)
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    (line,) = result.stderr.strip().splitlines()
    assert fragment in line, line
    return line


def test_plot_refuses_a_fifo_without_waiting_for_a_writer(cli, tmp_path):
    import os

    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    _plot_refused(cli, fifo, "is not a regular file")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pipe.csv"]


def test_plot_refuses_a_device(cli, tmp_path):
    _plot_refused(cli, "/dev/zero", "is not a regular file", "--out", tmp_path / "z.png")


def test_plot_refuses_a_file_over_its_size_limit_unread(cli, tmp_path, monkeypatch):
    from planar_tui.figures import table

    path = tmp_path / "big.csv"
    path.write_text(TORQUES_CSV + "0,0,0,0,0,0,1,2\n" * 10)
    monkeypatch.setattr(table, "MAX_CSV_BYTES", 100)
    _plot_refused(cli, path, "a result CSV may have")
    with open(path, "r+b") as stream:  # a sparse file of 65 MiB: over the real limit
        stream.truncate(65 * 2**20)
    monkeypatch.undo()
    _plot_refused(cli, path, "65 MiB, more than the 64 MiB")


def test_plot_refuses_a_field_too_large(cli, tmp_path):
    path = tmp_path / "wide.csv"
    path.write_text(TORQUES_CSV + '"' + "x" * 200_000 + '",0,0,0,0,0,1,2\n')
    _plot_refused(cli, path, "field larger than field limit")


@pytest.mark.parametrize("value", ["1e308", "-1e308", "inf", "nan", "1e999"])
def test_plot_refuses_numbers_it_cannot_draw(cli, tmp_path, value):
    path = tmp_path / "far.csv"
    path.write_text(TORQUES_CSV + f"0,0,0,0,0,0,1,2\n0,{value},0,0,0,0,1,2\n")
    _plot_refused(cli, path, f"line 3, column theta2_rad: {value} is not a finite number")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["far.csv"]


def test_plot_refuses_an_output_that_is_its_input(cli, tmp_path):
    path = tmp_path / "data.png"
    text = TORQUES_CSV + "0,0,0,0,0,0,1,2\n0,1,0,0,0,0,1,2\n"
    path.write_text(text)
    _plot_refused(cli, path, "--out: is the input")
    _plot_refused(cli, path, "--out: is the input", "--out", tmp_path / "." / "data.png")
    assert path.read_text() == text
