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


@pytest.mark.parametrize("case", list(CASES))
def test_bad_input_is_one_line_exit_2_nothing_written(case, tmp_path, cli):
    text, key, problem = CASES[case]
    preset = tmp_path / "bad.toml"
    preset.write_text(text, encoding="utf-8")
    result = cli("run", preset, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {preset}: {key}: "), lines[0]
    assert problem in lines[0], lines[0]
    assert len(lines[0]) < 400  # a 5000-digit value is not echoed whole
    assert not (tmp_path / "out").exists()
