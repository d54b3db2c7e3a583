"""`planar-tui workspace`: outputs, map, bad input, budget, cancel, bundled presets."""

from __future__ import annotations

import csv
import dataclasses
import time

import numpy as np
import pytest

from planar_tui.batch import run_job
from planar_tui.errors import Cancelled, PresetError
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.workspace.paving.map import BOUNDARY_GLYPH, INSIDE_GLYPH, render_map
from tests.conftest import PRESETS

ROBOT = """
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = {distal}
"""
JOB = """
[workspace]
joint_limits_deg = {limits}
orientation_deg = 0
precision_cm = {precision}
form = "{form}"
{extra}output = "ws.csv"
"""


def write_preset(
    tmp_path,
    *,
    distal=30,
    limits="[[50, 70], [140, 160], [260, 280]]",
    precision=0.0625,
    form="mean-value",
    extra="",
):
    path = tmp_path / "ws.toml"
    path.write_text(
        ROBOT.format(distal=distal)
        + JOB.format(limits=limits, precision=precision, form=form, extra=extra),
        encoding="utf-8",
    )
    return path


def read_csv(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_workspace_command_writes_summary_boxes_and_map(cli, tmp_path):
    preset = write_preset(tmp_path)
    result = cli("workspace", preset, "--out-dir", tmp_path, "--boxes", tmp_path / "boxes.csv")
    assert result.exit_code == 0, result.output
    (row,) = read_csv(tmp_path / "ws.csv")
    assert row["form"] == "mean-value"
    inside, kept = float(row["area_inside_cm2"]), float(row["area_kept_cm2"])
    assert inside <= float(row["area_geometric_cm2"]) <= kept
    boxes = read_csv(tmp_path / "boxes.csv")
    assert len(boxes) == int(row["boxes_kept"])
    assert {b["status"] for b in boxes} == {"inside", "boundary"}
    assert INSIDE_GLYPH in result.stdout and BOUNDARY_GLYPH in result.stdout
    assert "x (cm)" in result.stdout


def test_form_and_precision_options_override_the_preset(cli, tmp_path):
    preset = write_preset(tmp_path)
    out = tmp_path / "s.csv"
    args = ("workspace", preset, "--form", "arc-distance", "--precision", "0.125")
    result = cli(*args, "--out", out, "--no-map")
    assert result.exit_code == 0, result.output
    (row,) = read_csv(out)
    assert row["form"] == "arc-distance" and float(row["precision_cm"]) == 0.125
    assert INSIDE_GLYPH not in result.stdout


@pytest.mark.parametrize(
    ("settings", "fragment"),
    [
        ({"limits": "[[70, 50], [140, 160], [260, 280]]"}, "joint_limits_deg"),
        ({"limits": "[[50, 50], [140, 160], [260, 280]]"}, "empty or reversed"),
        ({"precision": 0}, "precision_cm"),
        ({"precision": -0.1}, "precision_cm"),
        ({"distal": 0}, "distal_cm"),
        ({"form": "taylor"}, "form"),
        ({"extra": "search_box_cm = [[0, 10], [0, 10]]\n"}, "cannot contain"),
        ({"extra": "search_box_cm = [[10, 0], [0, 10]]\n"}, "search_box_cm"),
        ({"extra": "expanded = true\n"}, "expanded"),
        ({"extra": "refine_precision_cm = 1.0\n"}, "refine_precision_cm"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_nothing_written(cli, tmp_path, settings, fragment):
    preset = write_preset(tmp_path, **settings)
    result = cli("workspace", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and fragment in lines[0]
    assert not (tmp_path / "ws.csv").exists()


@pytest.mark.parametrize(
    ("settings", "line"),
    [
        (
            {"extra": "search_box_cm = [[0, 120, 3], [0, 120]]\n"},
            "workspace.search_box_cm: row 1 has 3 values (expected [min, max] in cm)",
        ),
        (
            {"limits": "[[50, 70], [140], [260, 280]]"},
            "workspace.joint_limits_deg: row 2 has 1 values (expected [min, max] in degrees)",
        ),
        (
            {"distal": "30\nplatform_points_cm = [[0, 0], [40, 0, 1], [20, 40]]"},
            "robot3rrr.platform_points_cm: row 2 has 3 values (expected a point [x, y] in cm)",
        ),
    ],
)
def test_wrong_row_lengths_name_what_a_row_holds(cli, tmp_path, settings, line):
    preset = write_preset(tmp_path, **settings)
    result = cli("workspace", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == f"error: {preset}: {line}\n"
    assert not (tmp_path / "ws.csv").exists()


@pytest.mark.parametrize(("option", "value"), [("--form", "exact"), ("--precision", "0")])
def test_bad_command_line_values_exit_2(cli, tmp_path, option, value):
    preset = write_preset(tmp_path)
    result = cli("workspace", preset, option, value, "--out-dir", tmp_path)
    assert result.exit_code == 2 and result.stderr.startswith("error: ")
    assert not (tmp_path / "ws.csv").exists()


def test_a_job_estimated_past_4_times_its_box_budget_is_refused_when_read(cli, tmp_path):
    """The estimate (13,440 boxes here; the run processes 4,997) past 4 × box_budget: bad
    input, refused before anything runs, naming the budget that would be let through."""
    preset = write_preset(tmp_path, extra="box_budget = 1000\n")
    result = cli("workspace", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr.splitlines() == [
        f"error: {preset}: workspace.precision_cm: is 0.0625 cm: about 13,440 boxes, more "
        "than 4 × box_budget = 1,000: it would stop at its budget with nothing written "
        "(expected a coarser one or box_budget ≥ 3,360)"
    ]
    assert list(tmp_path.glob("*.csv")) == []
    preset = write_preset(tmp_path, extra="box_budget = 3360\n")  # 4 × 3,360 = 13,440
    (job,) = load_preset(preset).jobs
    assert job.spec.box_budget == 3360  # accepted when read


def test_box_budget_stops_with_a_clear_message_and_writes_nothing(cli, tmp_path):
    """A budget exceeded mid-run is a failed job (exit code 1, as docs/cli.md says), not
    bad input; it names the preset's box_budget and precision_cm. The budget is within 4
    × the estimate (13,440 boxes), below the boxes the run processes (4,997)."""
    preset = write_preset(tmp_path, extra="box_budget = 4000\n")
    result = cli("workspace", preset, "--out-dir", tmp_path, "--boxes", tmp_path / "b.csv")
    assert result.exit_code == 1
    assert result.stderr.splitlines()[-1] == (
        f"error: ws:workspace failed: {preset}: workspace.box_budget: the bisection exceeded "
        "4,000 boxes; nothing was written (expected a larger box_budget or a coarser "
        "precision_cm)"
    )
    assert not (tmp_path / "ws.csv").exists() and not (tmp_path / "b.csv").exists()


def test_a_budget_exceeded_at_the_precision_an_option_set_names_the_option(cli, tmp_path):
    preset = write_preset(tmp_path, precision=1.0, extra="box_budget = 4000\n")
    result = cli("workspace", preset, "--precision", "0.0625", "--out-dir", tmp_path)
    assert result.exit_code == 1
    assert result.stderr.splitlines()[-1] == (
        "error: ws:workspace failed: command line: --precision: the bisection exceeded "
        "4,000 boxes; nothing was written (expected a coarser --precision or a larger "
        "box_budget)"
    )
    assert list(tmp_path.glob("*.csv")) == []


def test_cancel_is_honoured_quickly_and_raises(tmp_path):
    preset = load_preset(write_preset(tmp_path, precision=0.001))
    (job,) = preset.jobs
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, geometric_reference=False))
    run_job(
        dataclasses.replace(job, spec=dataclasses.replace(job.spec, precision_cm=0.5))
    )  # compile first
    updates = []
    started = time.perf_counter()

    def stop() -> bool:
        return len(updates) >= 2

    with pytest.raises(Cancelled):
        run_job(job, Progress(on_update=updates.append, should_stop=stop))
    assert time.perf_counter() - started < 10.0  # two updates and a cancel: not the paving
    assert any("boxes" in u.detail for u in updates)


def test_run_command_runs_workspace_jobs(cli, tmp_path):
    preset = write_preset(tmp_path, form="arc-distance")
    result = cli("run", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "ws.csv").exists()


def test_map_is_80_columns_labelled_and_readable_without_colour():
    boxes = np.array([[0.0, 1.0, 0.0, 1.0], [1.0, 1.1, 0.0, 0.1], [5.0, 6.0, 2.0, 3.0]])
    status = np.array([2, 1, 1])
    lines = render_map(boxes, status, extent=(0.0, 10.0, 0.0, 5.0))
    assert all(len(line) <= 80 for line in lines)
    text = "\n".join(lines)
    assert INSIDE_GLYPH in text and BOUNDARY_GLYPH in text
    assert "┤" in text and "└" in text and "x (cm)" in text
    assert lines[-1].endswith("outside")  # the legend is whole at 80 columns
    assert any(line.strip().startswith("0") for line in lines[-3:])  # x tick labels
    narrow = render_map(boxes, status, extent=(0.0, 10.0, 0.0, 5.0), width=50, height=12)
    assert all(len(line) <= 50 for line in narrow) and len(narrow) == 12


@pytest.mark.parametrize("table", [3, 4, 5])
def test_bundled_paper_b_presets_load(table):
    preset = load_preset(PRESETS / f"paper-b-table{table}.toml")
    forms = {job.spec.form for job in preset.jobs}
    assert {"mean-value", "arc-distance", "geometric"} <= forms
    assert all(job.kind == "workspace" for job in preset.jobs)


def test_map_coverage_matches_a_brute_force_overlap():
    from planar_tui.workspace.paving.map import _coverage

    rng = np.random.default_rng(3)
    x, y, w = rng.uniform(-1, 10, 300), rng.uniform(-1, 5, 300), rng.uniform(0.01, 1.5, 300)
    boxes = np.column_stack([x, x + w, y, y + 0.7 * w])
    status = rng.integers(1, 3, 300)
    cover = _coverage(boxes, status, (0.0, 10.0, 0.0, 5.0), 20, 10)
    brute = np.zeros_like(cover)
    for (x0, x1, y0, y1), s in zip(boxes, status, strict=True):
        for i in range(20):
            for j in range(10):
                ox = max(0.0, min(x1, (i + 1) * 0.5) - max(x0, i * 0.5))
                oy = max(0.0, min(y1, (j + 1) * 0.5) - max(y0, j * 0.5))
                brute[0 if s == 2 else 1, j, i] += ox * oy / 0.25
    np.testing.assert_allclose(cover, brute, atol=1e-12)


@pytest.mark.parametrize(
    ("form", "extra"),
    [
        ("natural", ""),
        ("natural", "expanded = true\n"),
        ("slope", "refine_precision_cm = 0.01\n"),
        ("arc-distance", "refine_precision_cm = 0.01\n"),
        ("geometric", ""),
    ],
)
def test_every_form_brackets_the_geometric_area(cli, tmp_path, form, extra):
    preset = write_preset(tmp_path, form=form, precision=0.125, extra=extra)
    result = cli("workspace", preset, "--out-dir", tmp_path, "--no-map")
    assert result.exit_code == 0, result.output
    (row,) = read_csv(tmp_path / "ws.csv")
    exact, error = float(row["area_geometric_cm2"]), float(row["area_geometric_error_cm2"])
    assert float(row["area_inside_cm2"]) <= exact + error
    assert exact - error <= float(row["area_kept_cm2"])
    if form == "geometric":
        assert float(row["area_kept_cm2"]) - float(row["area_inside_cm2"]) <= 2 * error


def test_progress_reports_boxes_and_a_bracket_containing_the_exact_area(tmp_path):
    preset = load_preset(
        write_preset(
            tmp_path, form="arc-distance", precision=0.125, extra="refine_precision_cm = 0.0005\n"
        )
    )
    (job,) = preset.jobs
    updates = []
    result = run_job(job, Progress(on_update=updates.append))
    exact = result.outcome.geometric
    brackets = [
        (u.figures["area_lower_cm2"], u.figures["area_upper_cm2"])
        for u in updates
        if "area_lower_cm2" in u.figures
    ]
    assert len(brackets) >= 2 and all("boxes" in u.detail for u in updates if u.detail)
    # the text beside the bar shows the same bracket as the figures carry
    last = updates[-1]
    lower, upper = last.figures["area_lower_cm2"], last.figures["area_upper_cm2"]
    assert f"area in [{lower:.5g}, {upper:.5g}] cm2" in last.detail
    for lower, upper in brackets:
        assert lower <= exact.outer_cm2 * (1 + 1e-4) and exact.inner_cm2 <= upper * (1 + 1e-4)
    assert brackets[-1][1] - brackets[-1][0] < brackets[0][1] - brackets[0][0]


def test_explicit_points_in_the_preset(cli, tmp_path):
    preset = tmp_path / "ws.toml"
    preset.write_text(
        "[robot3rrr]\nbase_joints_cm = [[0, 0], [120, 0], [60, 103.92304845413263]]\n"
        "platform_points_cm = [[0, 0], [40, 0], [20, 40]]\n"
        + JOB.format(
            limits="[[50, 70], [140, 160], [260, 280]]",
            precision=0.125,
            form="arc-distance",
            extra="",
        ),
        encoding="utf-8",
    )
    result = cli("workspace", preset, "--out-dir", tmp_path, "--no-map")
    assert result.exit_code == 0, result.output
    (row,) = read_csv(tmp_path / "ws.csv")
    assert float(row["area_geometric_cm2"]) == pytest.approx(0.8794, abs=1e-4)


@pytest.mark.slow
def test_ctrl_c_exits_130_quickly_and_writes_nothing(tmp_path):
    import signal
    import subprocess
    import sys

    preset = write_preset(
        tmp_path,
        limits="[[20, 70], [110, 160], [245, 295]]",
        precision=0.005,
        # the leg-wise paving ends before the signal; the budget admits the job's estimate
        # (it runs about 20 s here before stopping at it): the signal comes long before
        extra='strategy = "joint"\nbox_budget = 100_000_000\n',
    )
    command = [
        sys.executable,
        "-m",
        "planar_tui",
        "workspace",
        str(preset),
        "--out-dir",
        str(tmp_path),
        "--boxes",
        str(tmp_path / "b.csv"),
    ]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    time.sleep(4.0)  # start-up (Numba) and well into the bisection
    assert process.poll() is None, "the job finished before it could be interrupted"
    process.send_signal(signal.SIGINT)
    sent = time.perf_counter()
    _, stderr = process.communicate(timeout=300)
    assert time.perf_counter() - sent < 5.0  # 10x the 0.5 s goal (exit included)
    assert process.returncode == 130, stderr.decode()
    assert not (tmp_path / "ws.csv").exists() and not (tmp_path / "b.csv").exists()
    assert not list(tmp_path.glob(".*.tmp"))


def test_a_range_of_orientations_is_not_estimated_so_not_refused_when_read(tmp_path):
    """The 3-RRR's estimate models one orientation: a range is left to its run's budget."""
    preset = write_preset(tmp_path, form="arc-distance", extra="box_budget = 1\n")
    text = preset.read_text(encoding="utf-8")
    preset.write_text(
        text.replace(
            "orientation_deg = 0", 'orientation_deg = [-1, 1]\norientation_mode = "total"'
        ),
        encoding="utf-8",
    )
    (job,) = load_preset(preset).jobs
    assert job.spec.orientation_deg == (-1.0, 1.0) and job.spec.box_budget == 1
    single = write_preset(tmp_path, form="arc-distance", extra="box_budget = 1\n")
    with pytest.raises(PresetError, match="more than 4 × box_budget = 1: it would stop"):
        load_preset(single)
