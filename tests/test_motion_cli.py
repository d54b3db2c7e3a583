"""``planar-tui motion`` and ``planar-tui run`` on motion uncertainty jobs: files, tables,
bad input, and the device: ``cuda`` without a usable GPU is one line and exit 2, ``auto``
falls back to the CPU and says so, and ``cuda`` on numba's CUDA simulator gives the CPU's
band."""

from __future__ import annotations

import csv
import os
import subprocess
import sys

import numpy as np
import pytest

PRESET = """# tiny motion uncertainty
[robot]
lengths_m = [0.3, 0.2]
masses_kg = [1.0, 0.8]

[motion_uncertainty]
duration_s = 0.01
step_s = 0.001
torques_Nm = [1.0, 0.2]
samples = 16
methods = ["montecarlo", "sobol"]
at_s = [0.005, 0.01]
every = 5
device = "{device}"
output = "tiny.csv"
"""


def write_preset(folder, device="cpu", **changes):
    text = PRESET.format(device=device)
    for key, value in changes.items():
        text = text.replace(f"{key} = ", f"{key} = {value}\n# was: ", 1)
    path = folder / "tiny.toml"
    path.write_text(text)
    return path


def read_csv(path):
    with open(path, newline="") as stream:
        return list(csv.reader(stream))


def test_motion_command_writes_band_and_indices(cli, tmp_path):
    preset = write_preset(tmp_path)
    result = cli("motion", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.stderr
    band = read_csv(tmp_path / "tiny.csv")
    assert band[0][:3] == ["t_s", "theta1_rad_mean", "theta1_rad_std"]
    assert [float(row[0]) for row in band[1:]] == [0.0, 0.005, 0.01]
    indices = read_csv(tmp_path / "tiny-indices.csv")
    assert indices[0] == [
        "output",
        "t_s",
        "parameter",
        "method",
        "S1",
        "S1_conf",
        "ST",
        "ST_conf",
        "percent",
        "runs",
    ]
    # 3 recorded times (at_s among them) × 4 outputs × 4 parameters × 1 method
    assert len(indices) - 1 == 3 * 4 * 4
    assert {row[1] for row in indices[1:] if row[5] != ""} == {"0.005", "0.01"}  # at_s: CIs
    # the angles at t = 0 do not vary (the tip does, with the lengths): no index
    at_start = [row for row in indices[1:] if row[1] == "0.0" and row[0].startswith("theta")]
    assert at_start and all(row[4:9] == [""] * 5 for row in at_start)
    aggregated = read_csv(tmp_path / "tiny-aggregated.csv")
    assert len(aggregated) - 1 == 5 * 4  # 4 outputs and all of them × 4 parameters
    outputs = [column[: -len("_mean")] for column in band[0] if column.endswith("_mean")]
    assert {row[0] for row in aggregated[1:]} == {*outputs, "all outputs"}  # as in the indices
    assert {row[0] for row in indices[1:]} == set(outputs)
    assert "% of ST per output · t = 0.01 s" in result.stdout
    assert "112 robots integrated on cpu\n" in result.stdout  # 16 + 16 (4 + 2)


def test_run_command_runs_motion_jobs_and_overrides_rename(cli, tmp_path):
    preset = write_preset(tmp_path)
    result = cli("run", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "tiny.csv").exists() and (tmp_path / "tiny-indices.csv").exists()
    result = cli("motion", preset, "--method", "montecarlo", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "tiny--method-montecarlo.csv").exists()


def test_bad_input_is_one_line_and_writes_nothing(cli, tmp_path):
    preset = write_preset(tmp_path, methods='["montecarlo", "bootstrap"]')
    result = cli("motion", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr.strip().count("\n") == 0
    assert "motion_uncertainty.methods: has 'bootstrap'" in result.stderr
    assert '"montecarlo", "sobol", "efast"' in result.stderr
    assert not (tmp_path / "tiny.csv").exists()
    result = cli("motion", write_preset(tmp_path), "--samples", "12", "--out-dir", tmp_path)
    assert result.exit_code == 2 and "--samples: is 12, not a power of two" in result.stderr


def test_a_single_output_and_method_are_one_item_lists(cli, tmp_path):
    """``outputs = "tip"`` and ``methods = "sobol"`` read as ``["tip"]``, ``["sobol"]``,
    as ``at_s`` takes one number."""
    preset = write_preset(tmp_path, methods='"sobol"', at_s="0.01")
    preset.write_text(preset.read_text().replace("every = 5", 'every = 5\noutputs = "tip"'))
    result = cli("motion", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.stderr
    band = read_csv(tmp_path / "tiny.csv")
    assert band[0] == [
        "t_s",
        *(f"tip_{axis}_m_{stat}" for axis in "xy" for stat in ("mean", "std", "p5", "p50", "p95")),
    ]
    indices = read_csv(tmp_path / "tiny-indices.csv")
    assert {(row[0], row[1], row[3]) for row in indices[1:]} == {
        (output, t, "sobol") for output in ("tip_x_m", "tip_y_m") for t in ("0.0", "0.005", "0.01")
    }
    assert "96 robots integrated on cpu\n" in result.stdout  # 16 × (4 + 2)


def test_bad_times_and_choices_name_the_allowed_values(cli, tmp_path):
    """One line naming the file, the key and the allowed values; nothing written."""
    preset = write_preset(tmp_path, at_s='"end"')
    result = cli("motion", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: {preset}: motion_uncertainty.at_s: is 'end' (expected a number or a list of "
        "numbers in (0, duration_s = 0.01 s])\n"
    )
    preset = write_preset(tmp_path, at_s="[0.005, 0.02]")
    result = cli("motion", preset, "--out-dir", tmp_path)
    assert result.stderr == (
        f"error: {preset}: motion_uncertainty.at_s: has 0.02 s (expected a number or a list "
        "of numbers in (0, duration_s = 0.01 s])\n"
    )
    preset = write_preset(tmp_path, methods='"bootstrap"')
    result = cli("motion", preset, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == (
        f"error: {preset}: motion_uncertainty.methods: has 'bootstrap' (expected one of "
        '"montecarlo", "sobol", "efast", "pce" or a non-empty list of them)\n'
    )
    assert not list(tmp_path.glob("*.csv"))


def test_problems_of_a_value_an_option_set_name_the_option(cli, tmp_path):
    """The resources are checked again once the options are applied: a run too long
    because of ``--samples`` or ``--method`` blames that option, not the preset (whose own
    values passed when it was read); nothing is written."""
    preset = write_preset(tmp_path, duration_s="10")  # 10 000 steps of 1 ms
    result = cli("motion", preset, "--samples", "4194304", "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == (
        "error: command line: --samples: 29360128 robots of 2 links × 10000 steps: needs "
        "about 3.43 days of computing (limit 1 day) (expected fewer samples, a shorter "
        "duration_s or a longer step_s)\n"
    )  # 4194304 × (1 + 2 + 4) robots × 10⁴ steps × 1.008 µs
    big = write_preset(tmp_path, duration_s="10", samples="1048576", methods='["montecarlo"]')
    result = cli("motion", big, "-m", "sobol", "-m", "efast", "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == (
        "error: command line: --method: 10485760 robots of 2 links × 10000 steps: needs "
        "about 1.22 days of computing (limit 1 day) (expected fewer samples, a shorter "
        "duration_s or a longer step_s)\n"
    )  # 2²⁰ × ((4 + 2) + 4) robots (the options replace the preset's methods)
    assert list(tmp_path.glob("*.csv")) == []


def read_rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def run_cli(preset, out_dir, *options, **env):
    environment = {k: v for k, v in os.environ.items() if k != "NUMBA_ENABLE_CUDASIM"}
    environment.update(env)
    command = [
        sys.executable,
        "-m",
        "planar_tui",
        "motion",
        str(preset),
        "--out-dir",
        str(out_dir),
        *options,
    ]
    return subprocess.run(command, env=environment, capture_output=True, text=True)


@pytest.mark.slow
def test_cuda_without_a_usable_gpu_is_one_line_and_auto_falls_back(tmp_path):
    no_gpu = {"CUDA_VISIBLE_DEVICES": ""}
    done = run_cli(write_preset(tmp_path, "cuda"), tmp_path, **no_gpu)
    assert done.returncode == 2
    (line,) = done.stderr.strip().splitlines()
    assert line.startswith("error: ") and "motion_uncertainty.device: no usable CUDA GPU" in line
    assert not (tmp_path / "tiny.csv").exists()
    done = run_cli(write_preset(tmp_path, "auto"), tmp_path, **no_gpu)
    assert done.returncode == 0, done.stderr
    assert "robots integrated on cpu (no usable CUDA GPU" in done.stdout
    # the preset says cpu: --device cuda is the option's problem, not the preset's
    out_dir = tmp_path / "option"
    done = run_cli(write_preset(tmp_path, "cpu"), out_dir, "--device", "cuda", **no_gpu)
    assert done.returncode == 2
    (line,) = done.stderr.strip().splitlines()
    assert line.startswith("error: command line: --device: no usable CUDA GPU (")
    assert line.endswith('(expected "cpu" or "auto", or a machine with a usable CUDA GPU)')
    assert not out_dir.exists()


@pytest.mark.slow
def test_cuda_device_on_the_simulator_gives_the_cpu_band(tmp_path):
    cpu_dir, gpu_dir = tmp_path / "cpu", tmp_path / "gpu"
    assert run_cli(write_preset(tmp_path, "cpu"), cpu_dir).returncode == 0
    done = run_cli(write_preset(tmp_path, "cuda"), gpu_dir, NUMBA_ENABLE_CUDASIM="1")
    assert done.returncode == 0, done.stderr
    assert "robots integrated on cuda\n" in done.stdout
    cpu = np.array(read_csv(cpu_dir / "tiny.csv")[1:], dtype=float)
    gpu = np.array(read_csv(gpu_dir / "tiny.csv")[1:], dtype=float)
    assert np.allclose(gpu, cpu, rtol=1e-12, atol=1e-15)
    assert read_csv(cpu_dir / "tiny-indices.csv")[0] == read_csv(gpu_dir / "tiny-indices.csv")[0]


def test_a_sweep_of_the_motion_job_gives_each_points_figures(cli, tmp_path):
    """In-process sweep over the mass tolerance: a point's figures are those of a separate
    run of the job at that tolerance (band CSV's last row), and the spread grows with it."""
    preset = write_preset(tmp_path)
    text = preset.read_text() + (
        '\n[[sweep]]\njob = "motion_uncertainty"\n'
        'values = { tolerance_mass_g = [1.0, 50.0] }\noutput = "sweep.csv"\n'
    )
    preset.write_text(text)
    result = cli("sweep", preset, "--workers", "1", "--out-dir", tmp_path)
    assert result.exit_code == 0, result.stderr
    rows = read_rows(tmp_path / "sweep.csv")
    assert [row["status"] for row in rows] == ["ok", "ok"]
    separate = tmp_path / "separate"
    single = (
        preset.read_text()
        .split("[[sweep]]")[0]
        .replace("torques_Nm", "tolerance_mass_g = 50.0\ntorques_Nm")
    )
    (tmp_path / "single.toml").write_text(single)
    assert cli("motion", tmp_path / "single.toml", "--out-dir", separate).exit_code == 0
    band = read_rows(separate / "tiny.csv")[-1]
    for name in ("theta1_rad", "theta2_rad", "tip_x_m", "tip_y_m"):
        for stat in ("mean", "std"):
            assert float(rows[1][f"{name}_{stat}"]) == float(band[f"{name}_{stat}"])
    assert float(rows[1]["theta2_rad_std"]) > 2 * float(rows[0]["theta2_rad_std"])
    assert rows[1]["theta2_rad_dominant"] in ("l1", "l2", "m1", "m2")
