"""What the CLI shows: no app without a terminal, help without value placeholders on
flags, titled workspace maps with their final bracket, progress complete at 80 columns."""

from __future__ import annotations

import csv
import io
import re
import subprocess
import sys
import time

from planar_tui.errors import ExitCode
from tests.conftest import REPO

TINY = REPO / "tests" / "data" / "app" / "tiny.toml"

WORKSPACE_PRESET = """
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30

[[workspace]]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 0.9375
form = "mean-value"
output = "ws-a.csv"

[[workspace]]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
precision_cm = 1.875
form = "arc-distance"
output = "ws-b.csv"
"""


def test_no_command_without_a_terminal_prints_help_and_exits_2_in_process(cli, monkeypatch):
    opened = []
    monkeypatch.setattr("planar_tui.app.run_app", opened.append)  # never the real app here
    result = cli()
    assert opened == []
    assert result.exit_code == ExitCode.BAD_INPUT
    assert "Usage: planar-tui" in result.stdout
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith("error: ") and "terminal" in line


def test_no_command_in_a_pipe_exits_2_quickly_with_the_usage():
    started = time.monotonic()
    try:
        finished = subprocess.run(
            [sys.executable, "-m", "planar_tui"],
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            timeout=120,
            cwd=REPO,
        )
    except subprocess.TimeoutExpired as error:
        raise AssertionError(
            "`planar-tui` with stdout piped did not exit (the app ran?)"
        ) from error
    assert time.monotonic() - started < 20
    assert finished.returncode == ExitCode.BAD_INPUT
    assert "Usage: planar-tui" in finished.stdout
    assert "\x1b[?1049h" not in finished.stdout  # no full-screen app escape codes
    assert finished.stderr.strip().splitlines()[-1].startswith("error: ")


def test_help_shows_no_value_placeholder_after_flags(cli):
    for command in ([], ["workspace"], ["simulate"], ["run"]):
        text = cli(*command, "--help").stdout
        assert "<bool>" not in text and "BOOLEAN" not in text
        flag_lines = [line for line in text.splitlines() if "--help" in line or "--map" in line]
        assert flag_lines
        for line in flag_lines:
            assert "<" not in line, line
    workspace_help = cli("workspace", "--help").stdout
    assert "--job" in workspace_help and "--form-mean-value" in workspace_help


def read_row(path):
    with open(path, newline="", encoding="utf-8") as stream:
        (row,) = list(csv.DictReader(stream))
    return row


def test_workspace_maps_are_titled_and_done_lines_show_the_final_bracket(cli, tmp_path):
    preset = tmp_path / "ws.toml"
    preset.write_text(WORKSPACE_PRESET, encoding="utf-8")
    result = cli("workspace", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    titles = [line for line in result.stdout.splitlines() if line.startswith("ws:workspace")]
    assert titles == [
        "ws:workspace[1]: mean-value, ε = 0.9375 cm",
        "ws:workspace[2]: arc-distance, ε = 1.875 cm",
    ]
    stderr = result.stderr.splitlines()
    for number, name in ((1, "ws-a.csv"), (2, "ws-b.csv")):
        row = read_row(tmp_path / name)
        inside, kept = float(row["area_inside_cm2"]), float(row["area_kept_cm2"])
        assert 0 < inside < kept
        pattern = rf"ws:workspace\[{number}\] done in 0:\d\d:\d\d"
        (done,) = [n for n, line in enumerate(stderr) if re.fullmatch(pattern, line)]
        assert stderr[done + 1] == (
            f"  {int(row['boxes_processed']):,} boxes, area in [{inside:.5g}, {kept:.5g}] cm2"
        )


def test_cli_progress_at_80_columns_shows_count_percent_and_time_uncut(cli, tmp_path, monkeypatch):
    from planar_tui.cli import output

    monkeypatch.setattr(output.stderr, "_force_terminal", True)
    monkeypatch.setattr(output.stderr, "_color_system", None)
    result = cli("simulate", TINY, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    shown = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]|\r", "\n", result.stderr)  # the last frame's lines
    lines = [line.rstrip() for line in shown.split("\n")]
    assert "tiny:simulate done" in lines
    bar = lines[lines.index("tiny:simulate done") + 1]
    assert re.search(r"━ 100%  200/200  in 0:00:\d\d$", bar), bar
    assert all(len(line) <= 80 and "…" not in line for line in lines)


class _Job:
    label = "paper-b-table3:workspace[2]"


def test_progress_display_mid_run_at_80_columns():
    from rich.console import Console

    from planar_tui.cli import job_progress_display, progress_bar

    console = Console(width=80, record=True, force_terminal=True, file=io.StringIO())
    bars = job_progress_display(console)
    detail = "1,234,567 boxes, area in [102.67, 147.38] cm2 (a long detail, folded not cut)"
    with progress_bar(bars, _Job.label) as progress:
        progress.start(5000, "natural-expanded bisection, a long stage name")
        progress.advance(1000, detail)
        time.sleep(0.05)
        progress.advance(1100, detail)
        console.print(bars.get_renderable())
    text = console.export_text()
    lines = text.splitlines()
    assert "…" not in text and all(len(line) <= 80 for line in lines)
    (figures,) = [line for line in lines if "%" in line]
    assert re.search(r"━ +42%  2,100/5,000  ETA \d+:\d\d:\d\d$", figures), figures
    assert "paper-b-table3:workspace[2] natural-expanded bisection" in text
    assert "(a long detail, folded not" in text


def test_every_help_text_is_shown_as_written(cli):
    """Typer reads help as Rich markup: ``[[sweep]]`` came out ``[]``. Every bracketed
    word of every command's and option's help appears in its rendered help."""
    import click
    import typer

    from planar_tui.cli import app

    group = typer.main.get_command(app)
    commands = {"": group, **group.commands}
    for name, command in commands.items():
        texts = [command.help or ""]
        texts += [getattr(param, "help", None) or "" for param in command.params]
        rendered = cli(*([name] if name else []), "--help")
        assert rendered.exit_code == 0, rendered.output
        shown = " ".join(re.sub(r"[│╭╮╰╯─]", " ", rendered.stdout).split())
        for text in texts:
            raw = click.unstyle(text).replace("\\[", "[")  # as written, before escaping
            for word in re.findall(r"\S*\[\S*", raw):
                assert word.strip(".,;:()") in shown, (name, word)
    assert "([[sweep]] tables)" in " ".join(cli("sweep", "--help").stdout.split())


def test_a_sweep_label_with_brackets_is_shown_as_written(cli, tmp_path):
    preset = tmp_path / "[bold]p.toml"
    preset.write_text(
        "[robot]\nlengths_m = [0.25, 0.2]\nmasses_kg = [2.0, 1.5]\n[[torques]]\n"
        "theta_deg = [[30, 60]]\nomega_deg_s = [[10, -20]]\nalpha_deg_s2 = [[1, 2]]\n"
        'output = "tq.csv"\n[[sweep]]\njob = "torques"\nvalues."robot.masses_kg[2]" = [1.0]\n'
    )
    result = cli("run", preset, "--out-dir", tmp_path, "--workers", "1")
    assert result.exit_code == 0, result.output
    assert "[bold]p:torques" in result.stdout and "[bold]p:sweep[1]" in result.stdout
    assert "[bold]p:sweep[1]" in result.stderr  # the sweep's progress bar


def _coercions(annotation, **info):
    """(ours, Typer's) value coercion of an option of ``annotation``."""
    from typer._coercion import build_runtime_param, resolve_type_descriptor
    from typer.models import OptionInfo

    from planar_tui.cli.coercion import CommonValues

    descriptor = resolve_type_descriptor(annotation, OptionInfo(**info))
    ours = CommonValues(
        parameter_info=descriptor.parameter_info, annotation=annotation, descriptor=descriptor
    )
    return ours, build_runtime_param(descriptor)


def _outcome(coercion, value):
    from typer._click.exceptions import BadParameter

    try:
        result = coercion._coerce_value(value, param=None, ctx=None)
        return type(result), result
    except BadParameter as error:
        return "refused", error.message


def test_option_values_are_coerced_as_typers_pydantic_adapters_coerce_them(tmp_path):
    """The common values coerced without pydantic (:class:`planar_tui.cli.output.
    CommonValues`) come out as Typer's own adapters make them, type included; the rest
    (numbers, bad values, paths that must exist) goes to those adapters, messages and all."""
    from pathlib import Path

    import typer

    from planar_tui.cli import output
    from planar_tui.cli.coercion import CHECKED_TYPER

    if not typer.__version__.startswith(CHECKED_TYPER):  # another Typer: Typer's own coercion
        assert output.install_common_values is None
        return
    (tmp_path / "file.csv").write_text("x\n")
    texts = ["", "-", ".", "a b", "é/ü", "~/x", "x/../y", str(tmp_path), "[[sweep]]", " 3 "]
    cases = [
        (str, {}, texts),
        (list[str], {}, [texts, tuple(texts), []]),
        (Path, {}, [*texts, str(tmp_path / "file.csv")]),
        (Path, {"exists": True, "dir_okay": False}, [str(tmp_path), str(tmp_path / "no.csv")]),
        (int, {}, ["3", " 4", "x", "1.5"]),
        (float, {"min": 0.0}, ["0.5", "-1", "nan", "y"]),
    ]
    for annotation, info, values in cases:
        ours, typers = _coercions(annotation, **info)
        for value in values:
            assert _outcome(ours, value) == _outcome(typers, value), (annotation, info, value)
    refused = _outcome(_coercions(int)[0], "x")
    assert refused[0] == "refused" and refused[1]  # the comparison can see a refusal


def test_a_typer_release_not_checked_keeps_typers_own_coercion_and_the_cli_works(tmp_path):
    """Under a Typer release whose private coercion API was not checked, the CLI does not
    touch it (:mod:`planar_tui.cli.coercion` refuses to import) and still runs: a preset
    copied with ``presets NAME --copy PATH`` (text and path options) is written."""
    import subprocess
    import sys

    out = tmp_path / "copy.toml"
    code = (
        "import sys, typer; typer.__version__ = '99.0.0'\n"
        "from planar_tui.cli import output\n"
        "assert output.install_common_values is None, 'the private coercion was installed'\n"
        "from planar_tui.entry import main\n"
        f"sys.argv = ['planar-tui', 'presets', 'paper-a-table4', '--copy', {str(out)!r}]\n"
        "main()\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "[sensitivity]" in out.read_text()
