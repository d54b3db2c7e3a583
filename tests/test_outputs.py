"""No output is overwritten or replaced without a word: two tables on one file, an output
onto the preset itself, onto a read-only file or onto something that is not a regular
file (a FIFO, a device node, a folder), and names the file system cannot hold are
refused before any job runs: one line naming the path and why, exit code 2."""

from __future__ import annotations

import os
import stat

import pytest

from tests.conftest import PRESETS, REPO

TABLE1 = PRESETS / "paper-a-table1.toml"
WORKSPACE_SMALL = REPO / "tests" / "data" / "app" / "workspace-small.toml"


def refused(result, path, problem: str) -> None:
    """Exit 2, one line ``error: PATH: (output): PROBLEM…``, and no job ran."""
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {path}: (output): {problem}"), lines[0]
    assert "done" not in result.stderr  # refused before the first job ran


def test_two_jobs_with_the_same_output_are_refused(tmp_path, cli):
    preset = tmp_path / "twice.toml"
    preset.write_text(
        TABLE1.read_text().replace('"table1-6r-free-fall.csv"', '"table1-6r-simulate.csv"')
    )
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    refused(
        result,
        tmp_path / "out" / "table1-6r-simulate.csv",
        "is written by both twice:simulate[1] (output) and twice:simulate[2] (output)",
    )
    assert not (tmp_path / "out").exists()


def test_boxes_output_equal_to_output_is_refused(tmp_path, cli):
    preset = tmp_path / "ws.toml"
    preset.write_text(WORKSPACE_SMALL.read_text() + 'boxes_output = "small-workspace.csv"\n')
    result = cli("run", preset, "--out-dir", tmp_path)
    refused(result, tmp_path / "small-workspace.csv", "is written by both ws:workspace (output)")
    assert "ws:workspace (boxes)" in result.stderr


def test_boxes_option_equal_to_out_is_refused(tmp_path, cli):
    out = tmp_path / "same.csv"
    result = cli("workspace", WORKSPACE_SMALL, "--out", out, "--boxes", out, "--no-map")
    refused(result, out, "is written by both")


def test_out_onto_the_preset_itself_is_refused(tmp_path, cli):
    preset = tmp_path / "mine.toml"
    preset.write_text(TABLE1.read_text())
    result = cli("torques", preset, "--out", preset)
    refused(result, preset, "is the preset file of mine:torques")
    assert preset.read_text() == TABLE1.read_text()


def test_out_onto_a_read_only_file_is_refused(tmp_path, cli):
    out = tmp_path / "kept.csv"
    out.write_text("keep me\n")
    out.chmod(0o444)
    refused(cli("torques", TABLE1, "--out", out), out, "is a read-only file")
    assert out.read_text() == "keep me\n"


def test_out_onto_a_fifo_is_refused(tmp_path, cli):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    result = cli("torques", TABLE1, "--out", fifo)
    refused(result, fifo, "is a FIFO (named pipe), not a regular file")
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_out_onto_dev_null_is_refused_and_the_node_kept(cli, monkeypatch):
    def must_not_write(plan, result):  # a regression must not replace the machine's node
        raise AssertionError(f"would have written {plan.main}")

    monkeypatch.setattr("planar_tui.batch.write_result", must_not_write)
    result = cli("torques", TABLE1, "--out", "/dev/null")
    refused(result, "/dev/null", "is a character device, not a regular file")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_out_onto_a_folder_is_refused(tmp_path, cli):
    refused(cli("torques", TABLE1, "--out", tmp_path), tmp_path, "is a folder")


@pytest.mark.parametrize(
    "name, problem",
    [
        ("a" * 300 + ".csv", "has a name of 304 bytes, longer than a file name may be (255)"),
        ("é" * 130 + ".csv", "has a name of 264 bytes"),
    ],
)
def test_out_names_the_file_system_cannot_hold_are_refused(tmp_path, cli, name, problem):
    out = tmp_path / name
    refused(cli("torques", TABLE1, "--out", out), out, problem)
    assert list(tmp_path.iterdir()) == []


def test_the_run_plan_refuses_a_nul_in_any_path(tmp_path):
    # a command line cannot hold a NUL (Click refuses it too); the app's paths can
    from planar_tui.errors import PresetError
    from planar_tui.plan import plan_run
    from planar_tui.presets import load_preset

    (job, *_) = load_preset(TABLE1).jobs
    with pytest.raises(PresetError, match="holds a NUL character"):
        plan_run([job], tmp_path, out=tmp_path / "a\0b.csv")


def test_a_too_long_out_dir_is_refused(tmp_path, cli):
    out_dir = tmp_path / ("d" * 256)
    result = cli("torques", TABLE1, "--out-dir", out_dir)
    refused(result, out_dir / "table1-6r-torques.csv", "has a name of 256 bytes")


def test_a_too_long_boxes_path_is_refused(tmp_path, cli):
    boxes = tmp_path / ("b" * 260)
    result = cli("workspace", WORKSPACE_SMALL, "--out-dir", tmp_path, "--boxes", boxes)
    refused(result, boxes, "has a name of 260 bytes")


def test_a_name_just_within_the_limit_is_written(tmp_path, cli):
    # the hidden temporary file beside it must fit the name limit too
    out = tmp_path / ("a" * 251 + ".csv")
    result = cli("torques", TABLE1, "--out", out)
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == [out.name]
