"""Bad input that used to escape as a traceback, or pass validation and fail (or write NaN)
later: each is one line ``error: FILE: key: problem (expected …)``, exit code 2, found
before any job runs and nothing written."""

from __future__ import annotations

import pytest

from tests.conftest import PRESETS

TABLE1 = (PRESETS / "paper-a-table1.toml").read_text()

TWO_LINKS = """[robot]
lengths_m = [0.3, 0.2]
masses_kg = [1.0, 0.8]
"""


def edited(old: str, new: str) -> str:
    assert old in TABLE1, old
    return TABLE1.replace(old, new, 1)


def deep(depth: int) -> str:
    return TWO_LINKS.replace("lengths_m = [0.3, 0.2]", f"lengths_m = {'[' * depth}{']' * depth}")


CASES = {
    "arrays nested 600 deep": (deep(600), "(syntax)", "nested too deeply"),
    "inline tables nested 600 deep": (
        "x = " + "{a = " * 600 + "1" + "}" * 600 + "\n",
        "(syntax)",
        "nested too deeply",
    ),
    "an integer of 5000 digits": (
        edited("every = 10", "every = 1" + "0" * 5000),
        "(syntax)",
        "4300 digits",
    ),
    "an integer too large for a float": (
        edited("lengths_m = [0.25,", "lengths_m = [1" + "0" * 400 + ","),
        "robot.lengths_m",
        "item 1 is 100000... (401 digits), not a finite number",
    ),
    "an integer too large for a float, as a duration": (
        edited("duration_s = 1.0", "duration_s = 1" + "0" * 310),
        "simulate[1].duration_s",
        "is 100000... (311 digits), not a finite number",
    ),
    "an integer beyond 64 bits": (
        edited("every = 10", "every = 18446744073709551616"),
        "simulate[1].every",
        "above the maximum",
    ),
    "a NUL in an output name": (
        edited('output = "table1-6r-torques.csv"', 'output = "a\\u0000b.csv"'),
        "torques.output",
        "holds a NUL character",
    ),
    "an output name longer than a file name may be": (
        edited('output = "table1-6r-torques.csv"', f'output = "{"n" * 300}.csv"'),
        "torques.output",
        "has a name of 304 bytes, longer than a file name may be (255)",
    ),
    "an output path longer than a path may be": (
        edited('output = "table1-6r-torques.csv"', f'output = "{"d/" * 2100}t.csv"'),
        "torques.output",
        "longer than a path may be (4096)",
    ),
    "a length of 1e-300 m": (
        edited("lengths_m = [0.25,", "lengths_m = [1e-300,"),
        "robot.lengths_m",
        "item 1 is 1e-300, below the minimum (expected >= 1e-50)",
    ),
    "a length of 1e200 m": (
        edited("lengths_m = [0.25,", "lengths_m = [1e200,"),
        "robot.lengths_m",
        "item 1 is 1e+200, above the maximum (expected <= 1e+50)",
    ),
    "an isotropic posture of 1e-300 m links": (
        TWO_LINKS.replace("[0.3, 0.2]", "[1e-300, 7e-301]")
        + '[sensitivity]\nposture = "isotropic"\ntolerance_length_mm = 1e-310\n',
        "robot.lengths_m",
        "item 1 is 1e-300, below the minimum",
    ),
    "gravity of 1e308": (
        edited("gravity_m_s2 = 9.81", "gravity_m_s2 = 1e308"),
        "robot.gravity_m_s2",
        "above the maximum",
    ),
}


def refused_line(cli, tmp_path, text: str, key: str, problem: str) -> str:
    """Run ``text`` as a preset: exit 2, one ``error: PRESET: KEY: …`` line holding
    ``problem``, nothing written; returns the line."""
    preset = tmp_path / "bad.toml"
    preset.write_text(text, encoding="utf-8")
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: {key}: "), lines[0]
    assert problem in lines[0], lines[0]
    assert not (tmp_path / "out").exists()
    return lines[0]


SWEPT_SIMULATE = (
    TWO_LINKS + '[simulate]\nduration_s = 1\nstep_s = 0.01\n[[sweep]]\njob = "JOB"\n'
    'values."robot.masses_kg[2]" = [1.0]\n'
)
CASES.update(
    {
        "a sweep's job index in superscript digits": (
            SWEPT_SIMULATE.replace("JOB", "simulate[²]"),
            "sweep[1].job",
            "simulate[²]",
        ),
        "a sweep's job index of 5000 digits": (
            SWEPT_SIMULATE.replace("JOB", "simulate[1" + "0" * 5000 + "]"),
            "sweep[1].job",
            "characters",
        ),
        "a motion step of 5e-324 s": (
            TWO_LINKS + "[motion_uncertainty]\nduration_s = 1\nstep_s = 5e-324\n",
            "motion_uncertainty.step_s",
            "inf steps",
        ),
        "a simulation step of 1e-310 s": (
            TWO_LINKS + "[simulate]\nduration_s = 1e10\nstep_s = 1e-310\n",
            "simulate.step_s",
            "inf steps",
        ),
        "the isotropic posture of a 1e30 m link": (
            "[robot]\nlengths_m = [1e30, 0.2, 0.3]\nmasses_kg = [2.0, 1.5, 1.0]\n[sensitivity]\n"
            'posture = "isotropic"\ntolerance_length_mm = 1\ntolerance_mass_g = 10\n',
            "sensitivity.posture",
            "no isotropic posture",
        ),
    }
)


@pytest.mark.parametrize("case", list(CASES))
def test_bad_input_is_one_line_exit_2_nothing_written(case, tmp_path, cli):
    line = refused_line(cli, tmp_path, *CASES[case])
    assert len(line) < 400  # a 5000-digit value is not echoed whole


SENSITIVITY = TWO_LINKS + '[sensitivity]\nmethods = ["sobol"]\nsamples = 8\noutput = "s.csv"\n'
WORKSPACE = """[robot3rrr]
[workspace]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 1.0
"""


def links(n: int) -> str:
    values = ", ".join(["0.1"] * n)
    return f"[robot]\nlengths_m = [{values}]\nmasses_kg = [{values}]\n"


LIMIT_CASES = {
    "1e18 simulation steps": (
        TWO_LINKS + "[simulate]\nduration_s = 1e14\nstep_s = 1e-4\n",
        "simulate.duration_s",
        "1e+18 steps of 2 links needs about 3.19e+04 years of computing (limit 1 day)",
    ),
    "a simulation too long to hold in memory": (
        TWO_LINKS + "[simulate]\nduration_s = 1e3\nstep_s = 1e-6\n",
        "simulate.duration_s",
        "1e+09 steps of 2 links needs about 447 GiB of memory (limit ",
    ),
    "every = 10**30": (
        TWO_LINKS + "[simulate]\nduration_s = 1\nstep_s = 0.1\nevery = 1" + "0" * 30 + "\n",
        "simulate.every",
        "is 100000... (31 digits), above the maximum",
    ),
    "samples = 2**40": (
        SENSITIVITY.replace("samples = 8", f"samples = {2**40}"),
        "sensitivity.samples",
        f"samples = {2**40}: needs about 2.27e+03 TiB of memory (limit ",
    ),
    "a 5000-link sensitivity": (
        links(5000) + "[sensitivity]\n",
        "sensitivity.samples",
        "5000 links, 1 speed(s), samples = 8192: needs about 41.7 TiB of memory",
    ),
    "a seed beyond 32 bits": (
        SENSITIVITY + f"seed = {2**32}\n",
        "sensitivity.seed",
        "is 4294967296, above the maximum (expected an integer >= 1 and <= 4,294,967,295)",
    ),
    "a seed beyond 64 bits": (
        SENSITIVITY + f"seed = {2**64}\n",
        "sensitivity.seed",
        "above the maximum",
    ),
    "a huge box_budget": (
        WORKSPACE + "box_budget = 1000000000000\n",
        "workspace.box_budget",
        "is 1,000,000,000,000 boxes: needs about 102 TiB of memory",
    ),
}


@pytest.mark.parametrize("case", list(LIMIT_CASES))
def test_what_cannot_run_is_refused_with_the_estimate(case, tmp_path, cli):
    refused_line(cli, tmp_path, *LIMIT_CASES[case])


@pytest.mark.parametrize(
    "options, problem",
    [
        (("--samples", "-8", "--method", "efast"), "command line: --samples: is -8"),
        (("--samples", "0", "--method", "efast"), "command line: --samples: is 0"),
        (("--seed", str(2**32)), "command line: --seed: is 4294967296, above the maximum"),
        (("--samples", str(2**40)), "command line: --samples: 2 links, 1 speed(s), samples"),
    ],
)
def test_every_sensitivity_option_is_checked_whatever_the_method(tmp_path, cli, options, problem):
    preset = tmp_path / "s.toml"
    preset.write_text(SENSITIVITY.replace('["sobol"]', '["sobol", "efast"]'))
    result = cli("sensitivity", preset, "--out-dir", tmp_path / "out", *options)
    assert result.exit_code == 2, result.output
    assert problem in result.stderr and result.stderr.count("\n") == 1, result.stderr
    assert not (tmp_path / "out").exists()


def test_a_non_finite_result_is_a_failure_and_not_written(tmp_path, cli):
    preset = tmp_path / "diverges.toml"
    preset.write_text(
        TWO_LINKS.replace("masses_kg", "gravity_m_s2 = 1e50\nmasses_kg")
        + "[simulate]\nduration_s = 10\nstep_s = 0.01\ntheta0_deg = [10, 10]\n"
        + 'omega0_deg_s = [1e40, 1e40]\noutput = "nan.csv"\n'
    )
    result = cli("simulate", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 1, result.output
    assert result.stderr.strip().splitlines()[-1] == (
        "error: diverges:simulate: the result holds NaN or infinite values (first in the "
        "output column theta1_rad); nothing was written"
    )
    assert not (tmp_path / "out").exists()


def test_the_first_non_finite_column_of_each_table_kind():
    import numpy as np

    from planar_tui.csvio import CsvTable

    array = np.array([[0.0, 1.0, 2.0], [0.0, 1.0, np.inf]])
    assert CsvTable(("a", "b", "c"), array).first_non_finite_column() == "c"
    assert CsvTable(("a", "b"), array[:, :2]).first_non_finite_column() is None
    rows = [["6R", 1.0, float("nan")], ["6R", np.float64("-inf"), 0.0]]
    assert CsvTable(("robot", "S1", "ST"), rows).first_non_finite_column() == "ST"
