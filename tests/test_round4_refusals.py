"""Hostile round 4: what the CLI reads is refused in one line with exit code 2
and no traceback, or computed right: a torques job's memory estimated from its rows,
optimisation variables that overlap, empty paths, leg limits and lengths at the edge of
the floats."""

from __future__ import annotations

from pathlib import Path

import pytest

from planar_tui import limits
from planar_tui.dynamics.torques import BYTES_PER_STATE_CELL, torques_estimate
from planar_tui.errors import PresetError
from planar_tui.presets import load_preset

ROBOT = "[robot]\nlengths_m = [0.303, 0.214]\nmasses_kg = [1.126, 0.796]\n"


def refused(result, *parts: str) -> None:
    """Exit code 2, one line on stderr holding every part, no traceback."""
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    for part in parts:
        assert part in result.stderr, (part, result.stderr)


def write(folder: Path, text: str, name: str = "p.toml") -> Path:
    path = folder / name
    path.write_text(text)
    return path


# -- torques: memory from the rows ---------------------------------------------------------
def test_a_torques_job_estimates_its_memory_from_its_rows():
    memory, seconds = torques_estimate(5_000_000, 2)
    assert memory == 5_000_000 * 8 * BYTES_PER_STATE_CELL  # 8 cells a state of a 2R
    assert seconds > 0


def test_a_torques_job_over_the_memory_limit_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(limits, "memory_limit_bytes", lambda: 2**20)
    rows = "[" + ", ".join(["[0, 1]"] * 500) + "]"
    path = write(tmp_path, ROBOT + f"\n[torques]\ntheta_deg = {rows}\n")
    with pytest.raises(PresetError) as caught:
        load_preset(path)
    assert str(caught.value) == (
        f"error: {path}: torques.theta_deg: 500 states of 2 links needs about 1.22 MiB of "
        "memory (limit 1 MiB) (expected fewer states)"
    )
    rows = "[" + ", ".join(["[0, 1]"] * 400) + "]"  # 400 × 8 × 320 bytes: under 1 MiB
    write(tmp_path, ROBOT + f"\n[torques]\ntheta_deg = {rows}\n")
    assert load_preset(path).jobs[0].kind == "torques"


# -- optimisation and sweep variables that overlap -----------------------------------------
TORQUES = ROBOT + "\n[torques]\ntheta_deg = [[0, 10]]\n"


@pytest.mark.parametrize(
    ("variables", "problem"),
    [
        (
            'variables."robot.masses_kg" = { choices = [[1.0, 0.8], [1.1, 0.7]] }\n'
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\n',
            'optimise[1].variables."robot.masses_kg[1]": overlaps robot.masses_kg: one names a'
            " value within the other (expected each value once, by one key path)",
        ),
        (
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\n'
            'variables."robot.masses_kg" = { choices = [[1.0, 0.8], [1.1, 0.7]] }\n',
            'optimise[1].variables."robot.masses_kg": overlaps robot.masses_kg[1]',
        ),
        (
            'variables."theta_deg[1]" = { choices = [[0, 10], [5, 5]] }\n'
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\n'
            'coarse = { "theta_deg[1][2]" = 3 }\n',
            'optimise[1].coarse."theta_deg[1][2]": overlaps theta_deg[1]',
        ),
        (
            'variables."robot.masses_kg[1]" = { from = 0.5, to = 2, fixed_sum = '
            '{ "robot.masses_kg" = 2 } }\n',
            'fixed_sum."robot.masses_kg": overlaps robot.masses_kg[1]',
        ),
    ],
)
def test_optimisation_variables_that_overlap_are_refused(tmp_path, cli, variables, problem):
    preset = write(
        tmp_path,
        TORQUES
        + '\n[[optimise]]\njob = "torques"\noutput = "o.csv"\n'
        + variables
        + 'minimise = "tau1_abs_max_Nm"\n',
    )
    result = cli("optimise", preset, "--out-dir", tmp_path, "--workers", "1")
    refused(result, f"error: {preset}: ", problem)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]


def test_sweep_key_paths_that_overlap_are_refused(tmp_path, cli):
    preset = write(
        tmp_path,
        TORQUES + '\n[[sweep]]\njob = "torques"\n'
        'values."robot.masses_kg" = [[1.0, 0.8], [1.1, 0.7]]\n'
        'values."robot.masses_kg[2]" = [0.5, 0.6]\n',
    )
    result = cli("sweep", preset, "--out-dir", tmp_path)
    refused(result, 'sweep[1].values."robot.masses_kg[2]": overlaps robot.masses_kg')


# -- export: only XML characters -----------------------------------------------------------
@pytest.mark.parametrize(
    ("name", "format_name", "written"),
    [
        ("a \\u0007 \\u001b[31m", "urdf", "a \ufffd \ufffd[31m"),
        ("a\\u0000b", "mjcf", "a\ufffdb"),
        ("tab\\there \\ud7ff \\ufffe", "urdf", "tab\there \ud7ff \ufffd"),
    ],
)
def test_export_writes_only_xml_characters(tmp_path, cli, name, format_name, written):
    import xml.etree.ElementTree as ET

    preset = write(tmp_path, ROBOT.replace("[robot]\n", f'[robot]\nname = "{name}"\n'))
    model = tmp_path / f"m.{format_name}"
    result = cli("export", preset, "--format", format_name, "--out", model)
    assert result.exit_code == 0, result.output
    root = ET.parse(model).getroot()  # Python's parser takes it
    assert root.get("name" if format_name == "urdf" else "model") == written
    again = cli("import", model, "--out", tmp_path / "back.toml")  # and so does planar-tui
    assert again.exit_code == 0, again.output


# -- empty paths -----------------------------------------------------------------------------
SIMULATE = ROBOT + "\n[simulate]\nduration_s = 0.01\nstep_s = 0.001\n"


@pytest.mark.parametrize(
    ("command", "option"),
    [
        (("simulate", "{p}", "--out", ""), "--out"),
        (("simulate", "{p}", "-o", ""), "-o"),
        (("simulate", "{p}", "--out="), "--out"),
        (("run", "{p}", "--out-dir", ""), "--out-dir"),
        (("presets", "paper-a-table1", "--copy", ""), "--copy"),
        (("sensitivity", "{p}", "--export-problem", ""), "--export-problem"),
        (("plot", "r.csv", "--out", ""), "--out"),
    ],
)
def test_an_empty_path_is_refused(tmp_path, cli, monkeypatch, command, option):
    monkeypatch.chdir(tmp_path)
    preset = write(tmp_path, SIMULATE)
    result = cli(*(part.format(p=preset) for part in command))
    refused(result, f"error: command line: {option}: is empty (expected a file or folder path)")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]  # nothing written


# -- sensitivity --export-problem of a PCE-only job ------------------------------------------
SENSITIVITY = ROBOT + '\n[sensitivity]\nposture = "singular"\nsamples = 64\nseed = 1\n'


def test_export_problem_of_a_pce_only_job_is_refused_before_it_runs(tmp_path, cli):
    preset = write(tmp_path, SENSITIVITY + 'methods = ["pce"]\n')
    result = cli(
        "sensitivity", preset, "--out-dir", tmp_path, "--export-problem", tmp_path / "salib"
    )
    refused(
        result,
        "error: command line: --export-problem: job p:sensitivity runs only pce, "
        "which has no SALib design to export",
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.toml"]  # no CSV either


def test_export_problem_of_sobol_and_pce_exports_the_sobol_design(tmp_path, cli):
    import numpy as np

    preset = write(tmp_path, SENSITIVITY + 'methods = ["sobol", "pce"]\n')
    folder = tmp_path / "salib"
    result = cli("sensitivity", preset, "--out-dir", tmp_path, "--export-problem", folder)
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in folder.iterdir()) == ["sobol"]
    x, y = np.load(folder / "sobol" / "X.npy"), np.load(folder / "sobol" / "Y.npy")
    assert x.shape == (64 * (4 + 2), 4) and y.shape[0] == x.shape[0]  # Saltelli: N (D + 2)


# -- numbers at the edge of the floats ---------------------------------------------------------
def test_3rpr_leg_limits_are_bounded_like_lengths(tmp_path, cli):
    preset = write(
        tmp_path,
        "[robot3rpr]\n\n[[workspace3rpr]]\nprecision_cm = 1\n"
        "leg_limits_cm = [[0, 1e300], [0, 1e300], [0, 1e300]]\n",
    )
    result = cli("workspace3rpr", preset, "--out-dir", tmp_path)
    refused(
        result,
        "workspace3rpr[1].leg_limits_cm: leg 1 range [0, 1e+300] (expected 0 <= lo < hi <= 1e+200)",
    )
    write(tmp_path, preset.read_text().replace("1e300", "1e200"))  # at the bound: too large
    result = cli("workspace3rpr", preset, "--out-dir", tmp_path)
    refused(result, "workspace3rpr[1].precision_cm: is 1 cm: about 1e+18 boxes, needs about")


def test_the_box_estimate_of_an_infinite_outline_is_capped_not_an_overflow(monkeypatch):
    from types import SimpleNamespace

    from planar_tui.workspace.paving import estimate

    spec = SimpleNamespace(
        form="natural", precision_cm=1.0, refine_precision_cm=None, singularities=False
    )
    geometry = (float("inf"), (0.0, 1.0, 0.0, 1.0))
    monkeypatch.setattr(estimate, "_geometry", lambda kind, robot, spec: geometry)
    boxes = estimate.estimate_boxes("workspace3rpr", None, spec)
    assert boxes == int(estimate.MAX_ESTIMATED_BOXES) + estimate.MIN_BOXES


def test_isotropic_posture_of_a_3r_with_a_1e30_m_middle_link_is_refused(tmp_path, cli):
    preset = write(
        tmp_path,
        "[robot]\nlengths_m = [0.3, 1e30, 0.2]\nmasses_kg = [1, 1, 1]\n"
        '\n[sensitivity]\nposture = "isotropic"\nsamples = 64\n',
    )
    result = cli("sensitivity", preset, "--out-dir", tmp_path)
    refused(
        result,
        "sensitivity.posture: robot has no isotropic posture: the minimum condition number is",
    )


# -- a forged optimisation checkpoint record -------------------------------------------------
def test_a_forged_optimisation_checkpoint_record_is_dropped_on_resume(tmp_path, cli):
    import json

    from planar_tui.optimise.run import run_optimisation
    from planar_tui.optimise.spec import parse_optimisations

    preset = write(
        tmp_path,
        TORQUES + '\n[[optimise]]\njob = "torques"\noutput = "o.csv"\nbudget = 8\n'
        'variables."robot.masses_kg[1]" = { from = 0.5, to = 2 }\nminimise = "tau1_abs_max_Nm"\n',
    )
    out = tmp_path / "out"
    (opt,) = parse_optimisations(load_preset(preset))
    run_optimisation(opt, out_dir=out, keep_checkpoint=True)
    checkpoint = out / "o.csv.checkpoint.jsonl"
    lines = checkpoint.read_text().splitlines()
    for path in out.iterdir():
        if path != checkpoint:
            path.unlink()
    record = json.loads(lines[1])
    assert record["number"] == 1 and record["status"] == "ok"
    record["figures"]["tau1_abs_max_Nm"] = -1e300  # well-formed, finite, a column: forged
    lines[1] = json.dumps(record)
    checkpoint.write_text("\n".join(lines) + "\n")
    result = cli("optimise", preset, "--out-dir", out, "--resume", "--workers", "1")
    assert result.exit_code == 0, result.output
    warnings = [line for line in result.stderr.splitlines() if line.startswith("warning:")]
    assert warnings == [
        f"warning: {checkpoint}:2: record dropped (its digest is not this run's: edited, "
        "damaged or from another run): its point runs again"
    ]
    assert "-1e+300" not in (out / "o.csv").read_text()
    assert "e+300" not in (out / "o.csv").read_text() and "1e300" not in (out / "o.csv").read_text()


# -- box budgets refused up front --------------------------------------------------------------
def test_a_job_estimated_far_past_its_box_budget_is_refused_up_front(tmp_path):
    from planar_tui.workspace.paving.estimate import BUDGET_FACTOR, needs

    job = (
        "[robot3rpr]\n\n[[workspace3rpr]]\nleg_limits_cm = [[20, 80], [20, 80], [20, 80]]\n"
        "orientation_deg = 0\nprecision_cm = 0.0005\n"
    )
    path = write(tmp_path, job + "box_budget = 1000000\n")
    with pytest.raises(PresetError) as caught:
        load_preset(path)
    assert str(caught.value).startswith(
        f"error: {path}: workspace3rpr[1].precision_cm: is 0.0005 cm: about "
    )
    assert "boxes, more than 4 × box_budget = 1,000,000: it would stop at its budget" in str(
        caught.value
    )
    path = write(tmp_path, job + "box_budget = 10000000\n")  # 4 × 10 M: within
    (ok,) = load_preset(path).jobs
    boxes, _, _ = needs(ok.kind, ok.robot, ok.spec)
    assert 1_000_000 * BUDGET_FACTOR < boxes <= 10_000_000 * BUDGET_FACTOR


# -- plot of a large CSV says it may take minutes --------------------------------------------
def test_plot_of_a_csv_past_the_slow_figure_rows_says_so_before_drawing(tmp_path, cli, monkeypatch):
    from planar_tui.cli import commands
    from planar_tui.csvio import CsvTable
    from planar_tui.dynamics.torques import torques_header

    csv = tmp_path / "r.csv"
    rows = [[0.1 * k, 0.2, 0, 0, 0, 0, 1.5 + k, 0.25] for k in range(5)]
    csv.write_text("\n".join(CsvTable(torques_header(2), rows).lines()) + "\n")
    monkeypatch.setattr(commands, "SLOW_FIGURE_ROWS", 4)
    result = cli("plot", csv, "--out", tmp_path / "r.png")
    assert result.exit_code == 0, result.output
    assert result.stderr == "drawing 5 rows of r.csv: a figure of this size can take minutes\n"
    monkeypatch.setattr(commands, "SLOW_FIGURE_ROWS", 5)
    result = cli("plot", csv, "--out", tmp_path / "again.png")
    assert result.exit_code == 0 and result.stderr == ""
