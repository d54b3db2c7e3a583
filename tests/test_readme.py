"""The README and the documentation say what is true: the README's commands table is the
CLI's commands, its Quick start is what CI runs, its links resolve, and it stays a short
page for users (no development log, no machine paths); docs/csv.md's column lists are the
headers of the files the CLI writes; docs/development.md's recipe for a new job kind names
files that exist."""

from __future__ import annotations

import ast
import csv
import re
import tomllib

import pytest

from tests.conftest import REPO

README = (REPO / "README.md").read_text(encoding="utf-8")
DOCS = REPO / "docs"
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


def section(title: str, text: str = README) -> str:
    """The text under ``## title`` (the README's by default), up to the next ``## ``."""
    start = text.index(f"\n## {title}\n")
    end = text.find("\n## ", start + 1)
    return text[start:] if end < 0 else text[start:end]


def doc(name: str) -> str:
    return (DOCS / name).read_text(encoding="utf-8")


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
    """Each ``- **kind** ...: `columns``` line of docs/csv.md, by its label."""
    lines = re.findall(r"^- \*\*(\w+)\*\*( \w+)?.*?: `([^`]+)`", doc("csv.md"), re.M)
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
    """The motion band CSV's columns as docs/csv.md says: ``t_s``, then per output
    (``theta1_rad … thetan_rad, tip_x_m, tip_y_m``) ``NAME_mean, NAME_std …``."""
    text = re.search(
        r"^- The \*\*motion_uncertainty band\*\* CSV.*?(?=^- )", doc("csv.md"), re.M | re.S
    ).group(0)
    quoted = re.findall(r"`([^`]+)`", " ".join(text.split()))
    outputs = next(q for q in quoted if "…" in q)
    statistics = next(q for q in quoted if q.startswith("NAME_"))
    suffixes = [item.strip().removeprefix("NAME") for item in statistics.split(",")]
    return ["t_s"] + [name + suffix for name in expand(outputs, n_links) for suffix in suffixes]


def test_the_python_version_is_the_one_the_package_requires():
    required = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["requires-python"]
    assert required == ">=3.11"
    assert "needs Python 3.11 or newer" in section("Install")
    assert "planar-tui needs Python 3.11 or newer" in doc("install.md")


def test_the_new_job_kind_recipe_names_files_that_exist_and_the_kind_gets_a_command():
    """The "new job kind" recipe of docs/development.md names exactly the files a kind
    touches (its module, the registry, its tests): they exist; and a kind registered as
    it says (the toy kind of ``tests/test_toy_kind.py``) is a command of ``--help``."""
    from typer.testing import CliRunner

    from planar_tui.cli import build_app
    from planar_tui.registry import JOB_KINDS, registered
    from tests.test_toy_kind import TOY

    development = doc("development.md")
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


def cli_commands() -> set[str]:
    import typer

    from planar_tui.cli import build_app

    return set(typer.main.get_command(build_app()).commands)


def test_the_commands_table_is_the_clis_commands():
    """Every row of the README's commands table is a command of the CLI (or ``--version``),
    and every command of the CLI has its row."""
    rows = re.findall(r"^\| `planar-tui ([^` ]+)[^`]*` \|", section("Commands"), re.M)
    assert len(rows) == len(set(rows)), rows
    assert set(rows) - {"--version"} == cli_commands()
    assert "--version" in rows


def test_the_quick_start_has_the_two_commands_ci_runs():
    block = re.search(r"```sh\n(.*?)```", section("Quick start"), re.S).group(1)
    assert block.splitlines() == [
        "python3 -m venv .venv && .venv/bin/pip install -q -e . && .venv/bin/planar-tui "
        "simulate paper-a-table1 --out-dir out",
        'python3 -m venv .venv && .venv/bin/pip install -q -e ".[test]" && .venv/bin/python '
        "-m pytest -n 2",
    ]
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8")
    assert "python3 -m venv .venv\n" in ci
    assert '.venv/bin/pip install -q -e ".[test]"\n' in ci
    assert ".venv/bin/python -m pytest -n 2\n" in ci
    assert "first run" in section("Quick start") and "compile" in section("Quick start")


def headings_slugs(text: str) -> set[str]:
    """The anchors of a Markdown text's headings, as the site (and GitHub) makes them."""
    from pymdownx.slugs import slugify

    slug = slugify(case="lower")
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    return {slug(title.strip(), "-") for title in re.findall(r"^#+ (.+)$", text, re.M)}


def test_the_readmes_links_resolve():
    links = re.findall(r"\]\(([^)\s]+)\)", README)
    assert links
    for link in links:
        if re.match(r"[a-z]+://", link):
            continue
        target, _, anchor = link.partition("#")
        path = (REPO / target) if target else REPO / "README.md"
        assert path.exists(), link
        if anchor:
            text = path.read_text(encoding="utf-8")
            assert anchor in headings_slugs(text), link


#: An absolute path of a particular machine (a home, a scratch or a work folder).
#: An absolute path into a machine's top-level folders (the names joined, so that this file
#: holds no such path itself).
MACHINE_ROOTS = ("work", "root", "home", "tmp")
MACHINE_PATH = re.compile(r"(?<![\w.~$])/(?:" + "|".join(MACHINE_ROOTS) + ")/")


def test_the_readme_is_a_short_page_without_development_log():
    assert len(README.splitlines()) <= 500
    assert re.findall(r"\b[Ii]ssues? #?\d+|(?<![\w`])#\d+\b", README) == []
    assert re.findall(r"\bpass(?:es)?\b", README) == []
    assert re.findall(r"\b20\d\d-\d\d-\d\d\b|\d\d:\d\d UTC", README) == []
    assert MACHINE_PATH.findall(README) == []


def docstrings(path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    nodes = [tree, *ast.walk(tree)]
    return [
        text
        for node in nodes
        if isinstance(node, ast.Module | ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)
        and (text := ast.get_docstring(node)) is not None
    ]


def test_no_machine_paths_in_the_docs_or_the_benchmarks_docstrings():
    pages = sorted(DOCS.rglob("*.md"))
    assert len(pages) >= 10
    found = [page.name for page in pages if MACHINE_PATH.search(page.read_text(encoding="utf-8"))]
    assert found == []
    benchmarks = sorted((REPO / "benchmarks").glob("*.py"))
    assert benchmarks
    found = [b.name for b in benchmarks if any(MACHINE_PATH.search(d) for d in docstrings(b))]
    assert found == []


def test_the_machine_path_check_sees_paths():
    for root in MACHINE_ROOTS:
        assert MACHINE_PATH.search(f"Run: ``/{root}/venv/bin/python x.py``")
        assert MACHINE_PATH.search(f"see /{root}/out.csv")
    assert not MACHINE_PATH.search(
        "`TMPDIR/planar-tui-UID` and ~/.cache/planar-tui and a/" + MACHINE_ROOTS[2] + "/b"
    )
