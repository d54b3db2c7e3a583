"""The README says what the commands do: its CSV column lists are the headers of the files
the CLI writes, and it states the Python version the package requires."""

from __future__ import annotations

import csv
import re
import tomllib

import pytest

from tests.conftest import REPO

README = (REPO / "README.md").read_text(encoding="utf-8")
TINY = REPO / "tests" / "data" / "app" / "tiny.toml"

#: Added to the tiny preset: a torques job, a motion job and the workspace's boxes CSV.
EXTRA = """
[torques]
theta_deg = [[0, 0], [10, 20]]
output = "tiny-torques.csv"

[motion_uncertainty]
duration_s = 0.002
step_s = 0.001
samples = 8
methods = ["sobol"]
output = "tiny-motion.csv"
"""


def section(title: str) -> str:
    """The README's text under ``## title``, up to the next ``## `` heading."""
    start = README.index(f"\n## {title}\n")
    end = README.find("\n## ", start + 1)
    return README[start:end]


def expand(columns: str, n_links: int) -> list[str]:
    """A README column list as header names: ``theta1_rad … thetan_rad`` is one column per
    joint, 1 to ``n_links``."""
    names = []
    for item in (part.strip() for part in columns.split(",")):
        per_joint = re.fullmatch(r"(\w+?)1(\w*) … \1n\2", item)
        if per_joint:
            prefix, suffix = per_joint.groups()
            names += [f"{prefix}{i}{suffix}" for i in range(1, n_links + 1)]
        else:
            assert re.fullmatch(r"\w+", item), f"unreadable README column {item!r}"
            names.append(item)
    return names


def documented_columns(n_links: int) -> dict[str, list[str]]:
    """Each ``- **kind** ...: `columns``` line of the CSV formats section, by its label."""
    lines = re.findall(r"^- \*\*(\w+)\*\*( \w+)?.*?: `([^`]+)`", section("CSV formats"), re.M)
    return {(kind + (extra or "")).strip(): expand(cols, n_links) for kind, extra, cols in lines}


def header(path) -> list[str]:
    with open(path, newline="", encoding="utf-8") as stream:
        return next(csv.reader(stream))


@pytest.mark.slow
def test_csv_column_lists_match_the_files_the_commands_write(cli, tmp_path):
    text = TINY.read_text(encoding="utf-8")
    workspace_output = 'output = "tiny-workspace.csv"'
    assert "samples = 256" in text and workspace_output in text
    text = text.replace("samples = 256", "samples = 8").replace(
        workspace_output, f'boxes_output = "boxes.csv"\n{workspace_output}'
    )
    preset = tmp_path / "tiny.toml"
    preset.write_text(text + EXTRA, encoding="utf-8")
    result = cli("run", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    written = {
        "simulate": header(tmp_path / "tiny-simulate.csv"),
        "torques": header(tmp_path / "tiny-torques.csv"),
        "sensitivity": header(tmp_path / "tiny-sensitivity.csv"),
        "workspace summary": header(tmp_path / "tiny-workspace.csv"),
        "workspace boxes": header(tmp_path / "boxes.csv"),
        "motion_uncertainty indices": header(tmp_path / "tiny-motion-indices.csv"),
    }
    assert documented_columns(n_links=2) == written
    assert header(tmp_path / "tiny-motion.csv") == documented_band_columns(n_links=2)


def documented_band_columns(n_links: int) -> list[str]:
    """The motion band CSV's columns as the README says: ``t_s``, then per output
    (``theta1_rad … thetan_rad, tip_x_m, tip_y_m``) ``NAME_mean, NAME_std …``."""
    text = re.search(r"^- The \*\*motion_uncertainty band\*\* CSV.*?(?=^- )",
                     section("CSV formats"), re.M | re.S).group(0)  # fmt: skip
    quoted = re.findall(r"`([^`]+)`", " ".join(text.split()))
    outputs = next(q for q in quoted if "…" in q)
    statistics = next(q for q in quoted if q.startswith("NAME_"))
    suffixes = [item.strip().removeprefix("NAME") for item in statistics.split(",")]
    return ["t_s"] + [name + suffix for name in expand(outputs, n_links) for suffix in suffixes]


def test_the_python_version_is_the_one_the_package_requires():
    required = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["requires-python"]
    assert required == ">=3.11"
    assert "Needs Python 3.11 or newer" in section("Quick start")


def test_the_new_job_kind_recipe_names_files_that_exist_and_the_kind_gets_a_command():
    """The "new job kind" recipe of the Development section names exactly the files a kind
    touches (its module, the registry, its tests): they exist; and a kind registered as
    it says (the toy kind of ``tests/test_toy_kind.py``) is a command of ``--help``."""
    from typer.testing import CliRunner

    from planar_tui.cli import build_app
    from planar_tui.registry import JOB_KINDS, registered
    from tests.test_toy_kind import TOY

    development = section("Development")
    recipe = development[development.index("- **A new job kind**") :]
    recipe = recipe[: recipe.index("\n- **", 1)]
    named = set(re.findall(r"`((?:planar_tui|tests)/[\w/]+\.py)", recipe))
    assert {"planar_tui/registry.py", "tests/test_toy_kind.py"} <= named
    assert [path for path in sorted(named) if not (REPO / path).is_file()] == []
    assert "touches exactly three files: its module, one registry line and its" in recipe
    with registered(TOY):
        help_text = CliRunner().invoke(build_app(), ["--help"]).stdout
    commands = re.findall(r"│ (\w+) ", help_text)
    assert "kinetic" in commands
    assert {k.command.name for k in JOB_KINDS.values() if k.command} <= set(commands)
