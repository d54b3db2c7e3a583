"""The run history, the comparison of two runs, results opened from CSV files, the preset
picker (recent files, path completion, broken presets opened with their problems)."""

from __future__ import annotations

import asyncio
import csv
import functools
import json
import shutil
import time
from pathlib import Path

import pytest

from planar_tui.app import recent
from planar_tui.app.compare import compare_runs, overlay_map
from planar_tui.app.runs import NO_SIDECAR, RunHistory
from planar_tui.app.screens.picker import complete_path
from planar_tui.csvio import CsvTable

DATA = Path(__file__).parent / "data" / "app"


def async_test(function):
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        return asyncio.run(function(*args, **kwargs))

    return wrapper


async def until(pilot, predicate, timeout_s: float = 120.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "the screen did not change in time"
        await pilot.pause(0.05)


async def history_text(app, pilot) -> str:
    """The screen once the history screen (opened at start by the results given) shows."""
    from planar_tui.app.screens.history import HistoryScreen

    await until(pilot, lambda: isinstance(app.screen, HistoryScreen))
    await until(pilot, lambda: "Run history" in app.export_text())
    return app.export_text()


async def compare_latest(app, pilot):
    """``F10`` then ``c``: the comparison of the latest run with the one before it."""
    from planar_tui.app.screens.history import CompareScreen, HistoryScreen

    await pilot.press("f10")
    await until(pilot, lambda: isinstance(app.screen, HistoryScreen))
    await pilot.press("c")
    await until(pilot, lambda: isinstance(app.screen, CompareScreen))
    return app.screen.comparison


def tiny(tmp_path: Path) -> Path:
    path = tmp_path / "tiny.toml"
    shutil.copy(DATA / "tiny.toml", path)
    return path


def rows_of(path: Path) -> list[dict[str, str]]:
    with path.open(encoding="utf-8", newline="") as stream:
        return list(csv.DictReader(stream))


SCROLL_BARS = str.maketrans("", "", "▁▂▃▄▅▆▇█▉▊▋▌▍▎▏")


def squeezed(text: str) -> str:
    """``text`` without white space and scroll bars (a screen wraps lines anywhere in a
    long word, and a scroll bar's thumb ends some lines)."""
    return "".join(text.translate(SCROLL_BARS).split())


def make_app(tmp_path: Path, preset: Path | None = None):
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    return WorkbenchApp(Workbench.open(preset or tiny(tmp_path)), output_dir=tmp_path)


# -- comparison ------------------------------------------------------------------------


@pytest.fixture
def two_sensitivity_csvs(tmp_path, cli):
    """Two small Sobol' runs of one preset that differ in their seed, written by the CLI."""
    preset = tiny(tmp_path)
    paths = []
    for seed in (1, 2):
        out = tmp_path / f"seed{seed}.csv"
        result = cli("sensitivity", preset, "--seed", seed, "--samples", 64, "--out", out)
        assert result.exit_code == 0, result.output
        paths.append(out)
    return paths


def test_two_sensitivity_runs_compared_show_each_index_and_its_difference(two_sensitivity_csvs):
    a_path, b_path = two_sensitivity_csvs
    history = RunHistory()
    a, b = history.add_csv(a_path), history.add_csv(b_path)
    assert a.kind == b.kind == "sensitivity"
    assert (a.provenance.seed, b.provenance.seed, a.provenance.samples) == (1, 2, 64)
    comparison = compare_runs(a, b)
    assert comparison.header == (
        "torque",
        "parameter",
        "S1 A",
        "S1 B",
        "S1 B−A",
        "ST A",
        "ST B",
        "ST B−A",
    )
    # the keys every row shares are said once
    assert "every row: posture singular, speed_rad_s 1, method sobol" in comparison.notes
    rows_a, rows_b = rows_of(a_path), rows_of(b_path)
    assert len(comparison.rows) == len(rows_a) == len(rows_b) == 2 * 4  # torques × parameters
    differ = 0
    for shown, ra, rb in zip(comparison.rows, rows_a, rows_b, strict=True):
        assert (ra["posture"], ra["speed_rad_s"], ra["method"]) == ("singular", "1.0", "sobol")
        assert shown[:2] == (str(int(ra["torque"])), ra["parameter"])
        for k, name in ((2, "S1"), (5, "ST")):
            x, y = float(ra[name]), float(rb[name])
            assert shown[k : k + 3] == (f"{x:.4g}", f"{y:.4g}", f"{y - x:+.3g}")
            differ += x != y
    assert differ > 0  # another seed: other estimates
    assert "setting seed: A 1, B 2" in comparison.notes
    assert not any(note.startswith("the presets differ") for note in comparison.notes)


@pytest.mark.slow
@async_test
async def test_the_compare_screen_shows_two_sensitivity_runs_side_by_side(
    tmp_path, two_sensitivity_csvs
):
    from textual.widgets import DataTable

    from planar_tui.app.screens.history import CompareScreen, HistoryScreen

    app = make_app(tmp_path)
    app.open_results(two_sensitivity_csvs)
    async with app.run_test(size=(120, 40)) as pilot:
        text = await history_text(app, pilot)
        assert "Run history: 2 runs" in text
        assert "sensitivity" in text and "tiny:sensitivity" in text
        await pilot.press("c")  # the highlighted (latest) run against the other
        await until(pilot, lambda: isinstance(app.screen, CompareScreen))
        await until(pilot, lambda: "(A) vs" in app.export_text())
        text = app.export_text()
        assert "#1 (A) vs #2 (B): sensitivity" in text
        assert "setting seed: A 1, B 2" in text
        table = app.screen.query_one(DataTable)
        rows_a, rows_b = (rows_of(p) for p in two_sensitivity_csvs)
        first = table.get_row_at(0)
        x, y = float(rows_a[0]["ST"]), float(rows_b[0]["ST"])
        assert first[5:8] == [f"{x:.4g}", f"{y:.4g}", f"{y - x:+.3g}"]
        await pilot.press("escape")
        await until(pilot, lambda: isinstance(app.screen, HistoryScreen))


RECORDED = [DATA / "history" / f"seed{seed}.csv" for seed in (1, 2)]


def expected_comparison_rows(a_path: Path, b_path: Path) -> list[list[str]]:
    """Each row the comparison of the sensitivity CSVs A and B must show, read from the
    files themselves: torque, parameter, then S1 and ST of A, of B and B − A."""
    rows = []
    for ra, rb in zip(rows_of(a_path), rows_of(b_path), strict=True):
        assert (ra["torque"], ra["parameter"]) == (rb["torque"], rb["parameter"])
        cells = [ra["torque"], ra["parameter"]]
        for name in ("S1", "ST"):
            x, y = float(ra[name]), float(rb[name])
            cells += [f"{x:.4g}", f"{y:.4g}", f"{y - x:+.3g}"]
        rows.append(cells)
    return rows


@pytest.mark.slow
@pytest.mark.parametrize("size", [(80, 24), (120, 40)], ids=lambda s: f"{s[0]}x{s[1]}")
@async_test
async def test_the_compare_screen_shows_every_index_of_both_runs_and_their_difference(
    tmp_path, size
):
    """Two recorded Sobol' runs (seeds 1 and 2, tests/data/app/history): every cell of the
    comparison is the CSVs' own value or their difference, at 80×24 and 120×40; marking
    them the other way round (space) swaps A and B and every difference's sign."""
    from textual.widgets import DataTable

    from planar_tui.app.screens.history import CompareScreen, HistoryScreen

    app = make_app(tmp_path)
    app.open_results(RECORDED)
    async with app.run_test(size=size) as pilot:
        await history_text(app, pilot)
        for order in (RECORDED, RECORDED[::-1]):
            history = app.screen
            assert isinstance(history, HistoryScreen)
            for path in order:  # mark A, then B (space), on their rows
                row = 0 if path == RECORDED[0] else 1
                history.query_one(DataTable).move_cursor(row=row)
                await pilot.press("space")
            assert [run.source for run in history.marked] == [str(p) for p in order]
            marks = [history.query_one(DataTable).get_row_at(k)[0] for k in (0, 1)]
            assert marks == (["A", "B"] if order == RECORDED else ["B", "A"])
            await pilot.press("c")
            await until(pilot, lambda: isinstance(app.screen, CompareScreen))
            await pilot.pause()
            table = app.screen.query_one(DataTable)
            expected = expected_comparison_rows(*order)
            assert [str(c.label) for c in table.columns.values()] == [
                "torque",
                "parameter",
                "S1 A",
                "S1 B",
                "S1 B−A",
                "ST A",
                "ST B",
                "ST B−A",
            ]
            assert table.row_count == len(expected) == 8
            shown = [[str(cell) for cell in table.get_row_at(k)] for k in range(8)]
            assert shown == expected
            assert sum(row[4] not in ("+0", "-0") for row in shown) >= 4  # seeds differ
            text = app.export_text()
            first, second = (1, 2) if order == RECORDED else (2, 1)
            assert f"#{first} (A) vs #{second} (B): sensitivity" in text
            assert f"setting seed: A {first}, B {second}" in text
            # on screen, each row on a line of its own, every column at 80 columns too
            lines = [line.split() for line in text.splitlines()]
            for row in expected:
                assert row in lines
            await pilot.press("escape")
            await until(pilot, lambda: isinstance(app.screen, HistoryScreen))
            history.marked.clear()


def boxes(*rows) -> CsvTable:
    return CsvTable(("x_lo_cm", "x_hi_cm", "y_lo_cm", "y_hi_cm", "status"), list(rows))


def test_the_overlay_map_marks_what_each_workspace_holds():
    # A covers x in [0, 2], B x in [1, 3], both y in [0, 1]: on a 6-column grid over
    # [0, 3] the cell centres 0.25, 0.75 lie in A only, 1.25 and 1.75 in both, 2.25 and
    # 2.75 in B only.
    text = overlay_map(boxes((0.0, 2.0, 0.0, 1.0, 2)), boxes((1.0, 3.0, 0.0, 1.0, 2)), 6, 2)
    lines = text.splitlines()
    assert lines[:2] == ["AA##BB", "AA##BB"]
    assert "# both inside" in lines[2]
    boundary = overlay_map(boxes((0.0, 1.0, 0.0, 1.0, 1)), boxes(), 4, 1)
    assert boundary.splitlines()[0] == "...."


# -- results opened from files -------------------------------------------------------------


def test_a_result_csv_written_by_run_opens_with_its_settings(tmp_path, cli):
    preset = tiny(tmp_path)
    out = tmp_path / "out"
    result = cli("run", preset, "--job", "simulate", "--out-dir", out)
    assert result.exit_code == 0, result.output
    run = RunHistory().add_csv(out / "tiny-simulate.csv")
    assert run.kind == "simulate" and run.label == "tiny:simulate" and not run.note
    assert run.settings["duration_s"] == 0.2 and run.settings["torques_Nm"] == [0.5, 0.1]
    text = run.describe()
    assert "duration_s = 0.2" in text and "torques_Nm = [0.5, 0.1]" in text
    assert str(preset.absolute()) in text
    # the same table without its sidecar: the kind from the header, and said
    bare = tmp_path / "bare.csv"
    shutil.copy(out / "tiny-simulate.csv", bare)
    run = RunHistory().add_csv(bare)
    assert run.kind == "simulate" and run.provenance is None and run.note == NO_SIDECAR
    assert NO_SIDECAR in run.describe()
    (tmp_path / "other.csv").write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match="not a result CSV planar-tui writes"):
        RunHistory().add_csv(tmp_path / "other.csv")


@pytest.mark.slow
@pytest.mark.parametrize("size", [(80, 24), (120, 40)], ids=lambda s: f"{s[0]}x{s[1]}")
@async_test
async def test_tui_open_shows_the_result_in_the_history_with_its_settings(tmp_path, cli, size):
    """A CSV written by ``planar-tui run`` opens (as ``tui --open`` opens it) in the
    history: its row (kind, label, start time, the preset's digest) and, below, every
    key of the preset's ``[simulate]`` and ``[robot]`` tables with the value written there
    (read here with tomllib), the preset's path and digest (hashlib) and the command that wrote it."""
    import hashlib
    import tomllib

    from textual.widgets import DataTable

    from planar_tui.app.screens.history import HistoryScreen

    preset = tiny(tmp_path)
    out = tmp_path / "out"
    assert cli("run", preset, "--job", "simulate", "--out-dir", out).exit_code == 0
    app = make_app(tmp_path)
    app.open_results([out / "tiny-simulate.csv"])  # what `planar-tui tui --open` does
    digest = hashlib.sha256(preset.read_bytes()).hexdigest()
    toml = tomllib.loads(preset.read_text("utf-8"))
    written, robot = toml["simulate"], toml["robot"]
    async with app.run_test(size=size) as pilot:
        text = await history_text(app, pilot)
        assert "Run history: 1 run" in text
        row = [str(cell) for cell in app.screen.query_one(DataTable).get_row_at(0)]
        assert row[1:4] == ["1", "simulate", "tiny:simulate"]
        assert row[4] != "-" and row[5:9] == ["-", "-", "-", "-"]  # no seed, N, form, ε
        assert row[9] == digest[:8]
        words = squeezed(text)  # the detail wraps at the screen's width, even in a path
        detail = app.screen.query_one("#history-detail")
        command = squeezed(f"command: planar-tui run {preset} --job simulate")

        def scrolled_to_the_command() -> bool:  # the robot last; under load the detail's
            detail.scroll_end(animate=False)  # layout may grow after a first scroll_end
            return command in squeezed(app.export_text())

        await until(pilot, scrolled_to_the_command)
        end = squeezed(app.export_text())
        assert squeezed(f"preset: {preset.absolute()} (sha256 {digest})") in words + end
        assert command in end
        for table, shown, where in ((written, "settings:", words), (robot, "robot:", end)):
            for key, value in table.items():
                if key != "output":  # angles given as integers are floats in the job
                    value = [float(v) for v in value] if isinstance(value, list) else value
                    assert squeezed(f"{key} = {value!r}") in where.split(shown)[1], key
        await pilot.press("escape")
        await pilot.press("f10")
        await until(pilot, lambda: isinstance(app.screen, HistoryScreen))
    assert recent.recent("results") == [(out / "tiny-simulate.csv").absolute()]


def test_tui_open_refuses_a_file_that_is_no_result_in_one_line(tmp_path, cli):
    bad = tmp_path / "notes.csv"
    bad.write_text("hello\n")
    result = cli("tui", DATA / "tiny.toml", "--open", bad)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {bad}: (file): not a result CSV planar-tui writes")
    assert len(result.stderr.strip().splitlines()) == 1 and "Traceback" not in result.output


@pytest.mark.slow
@async_test
async def test_runs_of_the_session_are_kept_and_two_simulations_overlaid(tmp_path, monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")  # the curves told apart by their glyphs alone
    app = make_app(tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        app.action_show_tab("simulate")
        for _ in range(2):
            await pilot.press("f5")
            await until(pilot, lambda: not app.job_running, 600)
            await app.workers.wait_for_complete()
            await pilot.pause(0.1)
        assert [run.kind for run in app.run_history] == ["simulate", "simulate"]
        assert app.run_history.runs[0].provenance.duration_s > 0
        comparison = await compare_latest(app, pilot)
        assert comparison.series and comparison.series[0][0] == "A θ1"
        assert "same settings" in comparison.notes
        by_column = {row[0]: row for row in comparison.rows}
        assert by_column["theta1_rad"][3] == "0"  # one preset, one integrator: identical
        # a glyph per curve and a legend naming each, on screen at 80x24
        await pilot.pause(0.2)
        screen = app.export_text()
        legend = "1 A θ1   a B θ1   2 A θ2   b B θ2"
        assert legend in screen, screen
        plot = app.screen.query_one("#compare-plot").content_region
        rows = screen.splitlines()[plot.y + 1 : plot.bottom]  # below the plot's title
        drawn = "".join(line[plot.x : plot.right] for line in rows)
        assert set("ab") <= set(drawn), drawn  # B's curves (digits: A's, and the ticks')


# -- recent files, completion, the picker ---------------------------------------------------


def test_recent_files_are_kept_newest_first_and_a_bad_state_file_is_ignored(
    tmp_path, isolated_state_dir
):
    files = [tmp_path / f"p{k}.toml" for k in range(recent.MAX_ENTRIES + 2)]
    for path in files:
        path.write_text("")
        recent.remember("presets", path)
    recent.remember("presets", files[3])
    kept = recent.recent("presets")
    assert kept[0] == files[3] and len(kept) == recent.MAX_ENTRIES and files[0] not in kept
    assert recent.recent_path() == isolated_state_dir / "recent.json"
    assert json.loads(recent.recent_path().read_text())["presets"][0] == str(files[3])
    files[3].unlink()
    assert files[3] not in recent.recent("presets")  # gone files are not offered
    recent.recent_path().write_text("{not json")
    assert recent.load() == {"presets": [], "results": []}
    recent.remember("results", files[4])
    assert recent.recent("results") == [files[4]]


def test_path_completion_completes_a_unique_name_and_a_shared_start(tmp_path):
    (tmp_path / "alpha.toml").write_text("")
    (tmp_path / "alpine.toml").write_text("")
    (tmp_path / "beta.csv").write_text("")
    (tmp_path / "bravo").mkdir()
    (tmp_path / ".hidden.toml").write_text("")
    base = f"{tmp_path}/"
    assert complete_path(base + "al") == base + "alp"  # alpha / alpine share "alp"
    assert complete_path(base + "alph") == base + "alpha.toml"
    assert complete_path(base + "br") == base + "bravo/"
    assert complete_path(base + "b", (".toml",)) == base + "bravo/"  # beta.csv left out
    assert complete_path(base + "b") is None  # beta.csv and bravo/ share only "b"
    assert complete_path(base + ".h") == base + ".hidden.toml"
    assert complete_path(base + "zzz") is None and complete_path("") is None


@pytest.mark.slow
@async_test
async def test_the_picker_lists_bundled_and_recent_presets_and_opens_a_broken_one(tmp_path):
    from textual.widgets import OptionList

    from planar_tui.app.screens.picker import FilePicker

    broken = tmp_path / "broken.toml"
    broken.write_text(
        (DATA / "tiny.toml").read_text().replace("step_s = 0.001", "step_s = -1"), "utf-8"
    )
    recent.remember("presets", broken)
    app = make_app(tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("ctrl+o")
        await until(pilot, lambda: isinstance(app.screen, FilePicker))
        options = app.screen.query_one(OptionList)
        labels = [str(options.get_option_at_index(k).prompt) for k in range(options.option_count)]
        assert labels[0] == "Recent" and labels[1].strip() == str(broken)
        assert "Bundled presets" in labels
        assert any(label.strip().startswith("paper-a-table1 — ") for label in labels)
        await pilot.press("down", "enter")  # into the list, on its first entry: broken.toml
        await until(pilot, lambda: app.workbench.path == broken)
        await until(pilot, lambda: bool(app.problems))
        assert app.problems[0].key == "simulate.step_s"
        validation = str(app.query_one("#validation").render())
        assert validation.startswith("error: simulate.step_s")


def test_tables_that_are_no_tables_become_empty_tables_with_one_line_each():
    from planar_tui.app.workbench import repair_tables

    document = {
        "robot": 3,
        "simulate": [{"duration_s": 1.0}, "fast"],
        "torques": {"robot": [1, 2], "angles_deg": [[0.0]]},
        "sensitivity": {"samples": 8},
    }
    lines = repair_tables(document)
    assert lines == [
        "robot: is an integer (expected a table [robot]); opened as an empty table, saving writes it",
        "simulate[2]: is a text (expected a table [simulate[2]]); opened as an empty table, saving writes it",
        "torques.robot: is an array (expected a table [torques.robot]); opened as an empty table, saving writes it",
    ]
    assert document == {
        "robot": {},
        "simulate": [{"duration_s": 1.0}, {}],
        "torques": {"robot": {}, "angles_deg": [[0.0]]},
        "sensitivity": {"samples": 8},
    }
    assert repair_tables(document) == []  # nothing left to repair


@pytest.mark.slow
@async_test
async def test_a_preset_with_a_table_that_is_no_table_opens_marked_and_modified(tmp_path):
    """``planar-tui tui PRESET`` (and the picker) open such a preset instead of refusing
    it: the table empty, its fields marked, a warning naming it, the file untouched."""
    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench

    text = (DATA / "tiny.toml").read_text()
    start = text.index("[robot]")
    end = text.index("\n[", start + 1)
    broken = tmp_path / "broken.toml"
    broken.write_text(text[:start] + "robot = 3\n" + text[end + 1 :], "utf-8")
    before = broken.read_bytes()
    app = WorkbenchApp(Workbench.open_marked(broken), output_dir=tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: bool(app.problems))
        assert app.workbench.document["robot"] == {}
        assert app.workbench.modified  # the file says robot = 3: saving would change it
        assert any(problem.key.startswith("robot") for problem in app.problems)
        shown = [str(toast.message) for toast in app._notifications]
        assert any(
            line.startswith("robot: is an integer (expected a table [robot])") for line in shown
        )
    assert broken.read_bytes() == before
