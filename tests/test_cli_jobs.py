"""`--job` selects the jobs a command runs; an override names its files by what was run."""

from __future__ import annotations

import csv

import pytest

from planar_tui.errors import ExitCode
from tests.conftest import REPO

TINY = REPO / "tests" / "data" / "app" / "tiny.toml"

PRESET = """
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30

[[workspace]]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 1.875
form = "arc-distance"
boxes_output = "a-boxes.csv"
output = "a-arc.csv"

[[workspace]]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 1.875
form = "geometric"
output = "b-geometric.csv"

[[workspace]]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 3.75
form = "arc-distance"
output = "c-arc.csv"
"""


@pytest.fixture
def preset(tmp_path):
    path = tmp_path / "three.toml"
    path.write_text(PRESET, encoding="utf-8")
    return path


def written(folder):
    return sorted(p.name for p in folder.iterdir() if p.suffix == ".csv")


def summary(path):
    with open(path, newline="", encoding="utf-8") as stream:
        (row,) = list(csv.DictReader(stream))
    return row


def test_job_selects_by_table_key_and_by_output_name(cli, preset, tmp_path):
    out = tmp_path / "out"
    result = cli(
        "workspace",
        preset,
        "--job",
        "workspace[3]",
        "-j",
        "b-geometric.csv",
        "--out-dir",
        out,
        "--no-map",
    )
    assert result.exit_code == 0, result.output
    assert written(out) == ["b-geometric.csv", "c-arc.csv"]
    assert "three:workspace[1]" not in result.stdout


def test_run_selects_jobs_across_presets_by_label(cli, preset, tmp_path):
    out = tmp_path / "out"
    result = cli(
        "run",
        preset,
        TINY,
        "--job",
        "three:workspace[2]",
        "--job",
        "tiny:simulate",
        "--out-dir",
        out,
    )
    assert result.exit_code == 0, result.output
    assert written(out) == ["b-geometric.csv", "tiny-simulate.csv"]


@pytest.mark.parametrize(
    ("command", "valid"),
    [
        ("workspace", "one of workspace[1], workspace[2], workspace[3], or a job's output"),
        ("run", "one of three:workspace[1], three:workspace[2], three:workspace[3], tiny:"),
    ],
)
def test_an_unknown_job_is_one_line_exit_2_listing_the_names(cli, preset, tmp_path, command, valid):
    extra = (TINY,) if command == "run" else ()
    result = cli(command, preset, *extra, "--job", "workspace[9]", "--out-dir", tmp_path)
    assert result.exit_code == ExitCode.BAD_INPUT
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith("error: command line: --job: is 'workspace[9]', no such job")
    assert valid in line
    assert written(tmp_path) == []


def test_an_override_names_the_files_after_what_was_run(cli, preset, tmp_path):
    out = tmp_path / "out"
    result = cli(
        "workspace",
        preset,
        "--form",
        "mean-value",
        "--precision",
        "3.75",
        "--job",
        "workspace[1]",
        "--job",
        "workspace[3]",
        "--out-dir",
        out,
    )
    assert result.exit_code == 0, result.output
    assert written(out) == [
        "a-arc--form-mean-value--precision-3.75.csv",
        "a-boxes--form-mean-value--precision-3.75.csv",
        "c-arc--form-mean-value.csv",
    ]
    for name in ("a-arc--form-mean-value--precision-3.75.csv", "c-arc--form-mean-value.csv"):
        row = summary(out / name)
        assert (row["form"], row["precision_cm"]) == ("mean-value", "3.75")
    assert "three:workspace[1]: mean-value, ε = 3.75 cm" in result.stdout


def test_an_override_equal_to_the_preset_keeps_its_names(cli, preset, tmp_path):
    result = cli(
        "workspace",
        preset,
        "--form",
        "arc-distance",
        "--job",
        "workspace[3]",
        "--out-dir",
        tmp_path,
        "--no-map",
    )
    assert result.exit_code == 0, result.output
    assert "c-arc.csv" in written(tmp_path)


def test_out_names_are_kept_under_an_override(cli, preset, tmp_path):
    result = cli(
        "workspace",
        preset,
        "--form",
        "mean-value",
        "--job",
        "workspace[3]",
        "--out",
        tmp_path / "mine.csv",
        "--no-map",
    )
    assert result.exit_code == 0, result.output
    assert written(tmp_path) == ["mine.csv"]


def test_sensitivity_overrides_name_their_files(cli, tmp_path):
    result = cli("sensitivity", TINY, "--samples", "64", "--seed", "3", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert written(tmp_path) == ["tiny-sensitivity--samples-64--seed-3.csv"]
