"""Provenance sidecars of a sweep's point files (``point_outputs``): each point CSV has
``point-N.csv.json`` naming its sweep, its number and its values, written, resumed and
cleaned up with the CSV (a foreign sidecar in the folder is refused and kept:
tests/test_sweep_safety.py). And every
CSV ``planar-tui run`` writes (jobs, their extra tables, sweeps, point files,
optimisations) has a sidecar: a future writer without one fails here."""

from __future__ import annotations

import csv
import hashlib

import pytest

from planar_tui.provenance import read_sidecar, sidecar_path
from tests.sweep_presets import TORQUES, TORQUES_BASE, write
from tests.test_app_history import async_test, history_text, make_app, squeezed
from tests.test_motion_cli import PRESET as TINY_MOTION

POINTS = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0, 3.0]
output = "s.csv"
point_outputs = "pts"
"""


def sha256(path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def rows(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def test_every_point_csv_has_a_sidecar_naming_its_point_and_its_settings(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    result = cli("sweep", preset, "--out-dir", out, "--workers", "1")
    assert result.exit_code == 0, result.output
    study = read_sidecar(out / "s.csv")
    assert study is not None and study.kind == "sweep"
    points = sorted((out / "pts").glob("*.csv"))
    assert [p.name for p in points] == ["point-1.csv", "point-2.csv", "point-3.csv"]
    for row, csv_path in zip(rows(out / "s.csv"), points, strict=True):
        record = read_sidecar(csv_path)
        assert record is not None, csv_path
        number, mass_kg = int(row["point"]), float(row["robot.masses_kg[2]"])
        assert csv_path.name == f"point-{number}.csv"
        assert record.point == {
            "sweep": study.label,
            "number": number,
            "values": {"robot.masses_kg[2]": mass_kg},
        }
        assert record.kind == "torques"
        assert record.robot["masses_kg"] == [2.0, mass_kg]  # the point's own job
        assert record.robot["lengths_m"] == [TORQUES_BASE["l1"], TORQUES_BASE["l2"]]
        assert record.settings["theta_deg"] == [[30, 60], [-45, 90]]  # the preset's
        assert record.preset_sha256 == sha256(preset)
        assert record.duration_s is not None and record.duration_s >= 0
    assert sorted(p.name for p in (out / "pts").iterdir()) == sorted(
        name for p in points for name in (p.name, sidecar_path(p).name)
    )


def test_a_fresh_run_deletes_the_sidecars_it_wrote_before(tmp_path, cli):
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    assert cli("sweep", preset, "--out-dir", out, "--workers", "1").exit_code == 0
    (out / "s.csv").unlink()  # afresh: its record's files go, sidecars included
    one = write(
        tmp_path, "p.toml", TORQUES, POINTS.replace("[1.0, 2.0, 3.0]", "[4.0]"), **TORQUES_BASE
    )
    assert cli("sweep", one, "--out-dir", out, "--workers", "1").exit_code == 0
    names = sorted(p.name for p in (out / "pts").iterdir())
    assert names == ["point-1.csv", "point-1.csv.json"]
    record = read_sidecar(out / "pts" / "point-1.csv")
    assert record is not None and record.point["values"] == {"robot.masses_kg[2]": 4.0}


def test_resume_runs_again_a_point_whose_sidecar_is_missing(tmp_path, monkeypatch):
    from planar_tui.presets import load_preset
    from planar_tui.sweep import execute
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    (sweep,) = parse_sweeps(load_preset(preset))
    out = tmp_path / "out"
    run_sweep(sweep, out_dir=out, keep_checkpoint=True)
    (out / "s.csv").unlink()
    first = {p.name: p.read_text() for p in (out / "pts").glob("*.csv")}
    sidecar_path(out / "pts" / "point-2.csv").unlink()
    computed = []
    real = execute.run_point
    monkeypatch.setattr(
        execute, "run_point", lambda task, p=None: computed.append(task.number) or real(task, p)
    )
    run = run_sweep(sweep, out_dir=out, resume=True)
    assert computed == [2] and (run.resumed, run.recomputed) == (2, 1)
    record = read_sidecar(out / "pts" / "point-2.csv")
    assert record is not None and record.point["number"] == 2
    assert {p.name: p.read_text() for p in (out / "pts").glob("*.csv")} == first


#: A preset whose run writes every kind of CSV beyond the bundled presets': a motion job
#: (its band, indices and aggregated tables), a sweep with point files, an optimisation
#: (its evaluations and its optimum).
EVERYTHING = (
    TINY_MOTION.format(device="cpu")
    + """
[torques]
theta_deg = [[0, 0]]
omega_deg_s = [[0, 0]]
alpha_deg_s2 = [[0, 0]]
output = "t.csv"

[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0]
output = "sweep.csv"
point_outputs = "points"

[[optimise]]
job = "torques"
variables."theta_deg[1][1]" = { from = -60, to = 30 }
maximise = "tau1_abs_max_Nm"
budget = 8
population = 4
output = "opt.csv"
"""
)


@pytest.mark.slow
def test_every_csv_planar_tui_run_writes_has_a_sidecar(tmp_path, cli):
    preset = tmp_path / "everything.toml"
    preset.write_text(EVERYTHING, encoding="utf-8")
    out = tmp_path / "out"
    result = cli(
        "run", "paper-a-table1", "paper-b-table3", preset, "--out-dir", out, "--workers", "1"
    )
    assert result.exit_code == 0, result.output
    written = sorted(out.rglob("*.csv"))
    names = {p.relative_to(out).as_posix() for p in written}
    for expected in (
        "tiny.csv",
        "tiny-indices.csv",
        "t.csv",
        "sweep.csv",
        "points/point-1.csv",
        "opt.csv",
        "opt-optimum.csv",
        "table1-6r-torques.csv",
        "table3-natural.csv",
    ):
        assert expected in names, sorted(names)
    kinds = {}
    for path in written:
        record = read_sidecar(path)
        assert record is not None, f"{path.relative_to(out)} has no sidecar"
        assert record.version and record.command and record.preset_sha256
        kinds[path.relative_to(out).as_posix()] = record.kind
        if path.parent.name == "points":
            assert record.point is not None and path.name == f"point-{record.point['number']}.csv"
        else:
            assert record.point is None
    assert kinds["sweep.csv"] == "sweep" and kinds["opt-optimum.csv"] == "optimise"
    assert kinds["points/point-2.csv"] == "torques"
    assert kinds["tiny-indices.csv"] == "motion_uncertainty"


def _swept(tmp_path, cli):
    """The torques sweep run by the CLI: (its output folder, its sweep CSV's sidecar)."""
    preset = write(tmp_path, "p.toml", TORQUES, POINTS, **TORQUES_BASE)
    out = tmp_path / "out"
    assert cli("sweep", preset, "--out-dir", out, "--workers", "1").exit_code == 0
    return out, read_sidecar(out / "s.csv")


def test_a_point_csv_opens_into_the_history_as_its_point_with_its_settings(tmp_path, cli):
    from planar_tui.app.runs import RunHistory

    out, study = _swept(tmp_path, cli)
    run = RunHistory().add_csv(out / "pts" / "point-2.csv")
    assert run.kind == "torques" and not run.note
    assert run.label == f"{study.label} point 2"
    assert run.settings["theta_deg"] == [[30, 60], [-45, 90]]
    assert len(run.table.rows) == 2  # the point's own table: one row per state
    text = run.describe()
    assert f"point 2 of {study.label}: robot.masses_kg[2] = 2.0" in text
    assert "masses_kg = [2.0, 2.0]" in text  # the point's robot, not the base job's 1.5


@pytest.mark.slow
@async_test
async def test_tui_open_shows_a_point_csv_in_the_history(tmp_path, cli):
    from textual.widgets import DataTable

    out, study = _swept(tmp_path, cli)
    app = make_app(tmp_path)
    app.open_results([out / "pts" / "point-3.csv"])  # what `planar-tui tui --open` does
    async with app.run_test(size=(80, 24)) as pilot:
        await history_text(app, pilot)
        row = [str(cell) for cell in app.screen.query_one(DataTable).get_row_at(0)]
        assert row[2:4] == ["torques", f"{study.label} point 3"]
        text = squeezed(app.export_text())
        assert squeezed(f"point 3 of {study.label}: robot.masses_kg[2] = 3.0") in text
