"""The [sensitivity] job end to end: CSV, structure, determinism, bad input, cancel, views."""

import csv
import re
from pathlib import Path

import numpy as np
import pytest
from rich.console import Console

from planar_tui.batch import prepare_jobs
from planar_tui.batch import run_job as run_batch_job
from planar_tui.errors import Cancelled, PresetError
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.sensitivity.bars import sensitivity_bars
from planar_tui.sensitivity.tables import VIEWS, fit_tables

ROBOT_3R = """
[robot]
name = "3R"
lengths_m = [0.303, 0.303, 0.175]
masses_kg = [1.126, 1.126, 0.650]
inertias_kgm2 = [0.129, 0.129, 0.024]
"""


def write_preset(tmp_path: Path, body: str, robot: str = ROBOT_3R) -> Path:
    path = tmp_path / "job.toml"
    path.write_text(robot + "\n[sensitivity]\n" + body, encoding="utf-8")
    return path


def run_job(path: Path, progress: Progress | None = None):
    (job,) = load_preset(path).jobs_of("sensitivity")
    return job, run_batch_job(job, progress)


def rows_of(path: Path) -> list[dict]:
    with path.open(encoding="utf-8") as stream:
        return list(csv.DictReader(stream))


def test_csv_columns_and_percent(tmp_path, cli):
    preset = write_preset(tmp_path, 'samples = 256\nefast_samples = 200\noutput = "s.csv"\n')
    result = cli("sensitivity", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    rows = rows_of(tmp_path / "s.csv")
    assert list(rows[0]) == [
        "robot",
        "posture",
        "speed_rad_s",
        "torque",
        "parameter",
        "method",
        "S1",
        "S1_conf",
        "ST",
        "ST_conf",
        "percent",
        "runs",
    ]
    assert len(rows) == 3 * 6 * 2  # torques × parameters × methods
    assert {r["parameter"] for r in rows} == {"l1", "l2", "l3", "m1", "m2", "m3"}
    assert {r["method"] for r in rows} == {"sobol", "efast"}
    for method in ("sobol", "efast"):
        for torque in "123":
            share = [
                float(r["percent"]) for r in rows if (r["method"], r["torque"]) == (method, torque)
            ]
            assert sum(share) == pytest.approx(100.0)
    assert "τ3" in result.output  # the Table-4-shaped view


@pytest.mark.parametrize("posture", ['"singular"', '"isotropic"', "[10, 120, 150]"])
def test_sobol_mass_block_is_upper_triangular(tmp_path, posture):
    """τ_i cannot depend on m_j (j < i): S1 = ST = 0 exactly with Sobol'; in the singular
    posture also on l_j (j < i)."""
    body = f'posture = {posture}\nmethods = ["sobol"]\nsamples = 128\nspeed_rad_s = 1.3\n'
    _, result = run_job(write_preset(tmp_path, body))
    (analysis,) = result.analyses
    s1, _, st, _ = analysis.indices
    for i in range(3):
        for j in range(i):
            assert s1[i, 3 + j] == 0.0 and st[i, 3 + j] == 0.0
            if posture == '"singular"':
                assert s1[i, j] == 0.0 and st[i, j] == 0.0
    assert np.all(st[np.triu_indices(3)] > 0)  # ... and does depend on the others


def test_same_seed_gives_byte_identical_csv(tmp_path, cli):
    preset = write_preset(tmp_path, "samples = 128\nefast_samples = 100\nseed = 5\n")
    cli("sensitivity", preset, "-o", tmp_path / "a.csv")
    cli("sensitivity", preset, "-o", tmp_path / "b.csv")
    cli("sensitivity", preset, "-o", tmp_path / "c.csv", "--seed", "6")
    a, b, c = ((tmp_path / f"{x}.csv").read_bytes() for x in "abc")
    assert a == b and a != c


def test_speed_sweep_rows_and_bars(tmp_path):
    body = (
        'posture = "isotropic"\nspeed_rad_s = [0.8, 1.0, 1.2]\nmethods = ["sobol"]\nsamples = 64\n'
    )
    _, result = run_job(write_preset(tmp_path, body))
    assert {row[2] for row in result.table.rows} == {0.8, 1.0, 1.2}
    analyses = result.analyses
    bars_console = Console(width=100, record=True, color_system=None)
    bars_console.print(sensitivity_bars(analyses, "sobol", width=40))
    text = bars_console.export_text()
    bars = [line for line in text.splitlines() if line.startswith("τ")]
    assert len(bars) == 3 * 3  # 3 torques × 3 speeds
    assert all(len(line.split("rad/s ")[1]) == 40 for line in bars)
    assert "legend" in text and "m3" in text
    table_console = Console(width=100, record=True, color_system=None)
    table_console.print(fit_tables(analyses, VIEWS[0], 100).renderable)
    table = table_console.export_text().splitlines()
    assert [line for line in table if "rad/s" in line] == [
        f"% of ST per torque · isotropic · {speed} rad/s" for speed in (0.8, 1, 1.2)
    ]
    rows = [line.split()[0] for line in table if re.match(r"τ\d ", line)]
    assert rows == ["τ1", "τ2", "τ3"] * 3  # one table per speed, a row per torque


def test_cancel_raises_between_chunks(tmp_path):
    path = write_preset(tmp_path, "samples = 64\n")
    calls = []

    def stop():
        calls.append(1)
        return len(calls) > 3

    with pytest.raises(Cancelled):
        run_job(path, Progress(should_stop=stop))


def test_ctrl_c_during_analysis_leaves_the_old_csv_untouched(tmp_path, cli, monkeypatch):
    import planar_tui.sensitivity.engine as runner

    def interrupted(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(runner, "analyse", interrupted)
    preset = write_preset(tmp_path, 'samples = 64\noutput = "keep.csv"\n')
    (tmp_path / "keep.csv").write_text("old\n", encoding="utf-8")
    result = cli("sensitivity", preset, "--out-dir", tmp_path)
    assert result.exit_code == 130
    assert (tmp_path / "keep.csv").read_text(encoding="utf-8") == "old\n"
    assert [p.name for p in tmp_path.iterdir() if p.suffix != ".toml"] == ["keep.csv"]


@pytest.mark.parametrize(
    ("body", "key", "robot"),
    [
        ("tolerance_length_mm = 0\n", "tolerance_length_mm", ROBOT_3R),
        ("tolerance_mass_g = -1\n", "tolerance_mass_g", ROBOT_3R),
        ("tolerance_length_mm = 175\n", "tolerance_length_mm", ROBOT_3R),
        ("tolerance_mass_g = 700\n", "tolerance_mass_g", ROBOT_3R),
        ("samples = 1000\n", "samples", ROBOT_3R),
        ('methods = ["sobol", "morris"]\n', "methods", ROBOT_3R),
        ("posture = [0, 90]\n", "posture", ROBOT_3R),
        ('posture = "upright"\n', "posture", ROBOT_3R),
        ("seed = 0\n", "seed", ROBOT_3R),
        ('posture = "isotropic"\n', "posture", ROBOT_3R.replace("0.175", "0.100")),
    ],
)
def test_bad_input_is_one_line_exit_2_nothing_written(tmp_path, cli, body, key, robot):
    preset = write_preset(tmp_path, body + 'output = "bad.csv"\n', robot)
    with pytest.raises(PresetError, match=key):  # parsing, or solving the posture
        prepare_jobs(load_preset(preset).jobs)
    result = cli("sensitivity", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr.startswith("error: ") and result.stderr.count("\n") == 1
    assert not (tmp_path / "bad.csv").exists()


def test_cli_overrides_are_validated(tmp_path, cli):
    preset = write_preset(tmp_path, 'output = "o.csv"\n')
    for args in (("--samples", "100"), ("--method", "delta"), ("--seed", "0")):
        result = cli("sensitivity", preset, "--out-dir", tmp_path, *args)
        assert result.exit_code == 2 and result.stderr.startswith("error: command line")
    assert not (tmp_path / "o.csv").exists()


def test_bundled_presets_parse_with_the_paper_postures():
    root = Path(__file__).resolve().parent.parent / "presets"
    for name, count in (("paper-a-table4", 5), ("paper-a-table5", 5), ("paper-a-fig5-6", 2)):
        jobs = prepare_jobs(load_preset(root / f"{name}.toml").jobs_of("sensitivity"))
        assert len(jobs) == count
        for job in jobs:
            if job.prepared.posture.label == "isotropic":
                assert job.prepared.posture.condition_number < 1.002
                assert np.degrees(job.prepared.posture.theta_rad[1]) == pytest.approx(
                    135.0 if job.robot.n_links == 2 else 120.0, abs=0.05
                )
