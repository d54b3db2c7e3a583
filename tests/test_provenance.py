"""Provenance sidecars (``NAME.csv.json``) beside every CSV planar-tui writes."""

from __future__ import annotations

import hashlib
import json
import shlex

import pytest

from planar_tui import provenance
from planar_tui.presets import load_preset
from planar_tui.provenance import (
    Provenance,
    has_sidecar,
    job_provenance,
    read_sidecar,
    sidecar_path,
    study_provenance,
)
from planar_tui.registry import JOB_KINDS
from tests.conftest import PRESETS


def sha256(path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


#: (preset, job kind, the headline fields it must have, those it must not)
KINDS = [
    ("paper-a-table1", "simulate", {}, ("seed", "samples", "form", "precision_cm")),
    ("paper-a-table1", "torques", {}, ("seed", "samples", "form", "precision_cm")),
    ("paper-a-table4", "sensitivity", {"seed": int, "samples": int}, ("precision_cm",)),
    ("paper-a-table1-motion", "motion_uncertainty", {"seed": int, "samples": int}, ("form",)),
    ("paper-b-table3", "workspace", {"form": str, "precision_cm": float}, ("seed", "samples")),
]


@pytest.mark.parametrize(("preset", "kind", "present", "absent"), KINDS)
def test_the_sidecar_of_each_kind_holds_its_settings_and_headline(preset, kind, present, absent):
    path = PRESETS / f"{preset}.toml"
    job = next(j for j in load_preset(path).jobs if j.kind == kind)
    record = job_provenance(job, (0.0, 1.25))
    assert record.kind == kind and record.label == job.label
    assert record.preset_path == str(path.absolute())
    assert record.preset_sha256 == sha256(path)  # hashed here independently
    assert record.settings == JOB_KINDS[kind].dump(job.spec)
    assert record.robot  # the robot's keys as in the preset
    assert record.started_utc == "1970-01-01T00:00:00+00:00" and record.duration_s == 1.25
    from planar_tui import __version__

    assert record.version == __version__ and record.command
    for name, type_ in present.items():
        value = getattr(record, name)
        assert isinstance(value, type_) and value == record.settings[name]
    for name in absent:
        assert getattr(record, name) is None
    again = Provenance.from_json(record.to_json())
    assert again == record  # round trip, every field


def test_a_sidecar_round_trips_through_its_file_and_ignores_unknown_keys(tmp_path):
    job = load_preset(PRESETS / "paper-a-table4.toml").jobs[0]
    record = job_provenance(job)
    csv = tmp_path / "r.csv"
    sidecar_path(csv).write_text(record.to_json())
    assert read_sidecar(csv) == record
    data = json.loads(record.to_json()) | {"from_a_newer_version": 1}
    sidecar_path(csv).write_text(json.dumps(data))
    assert read_sidecar(csv) == record
    assert read_sidecar(tmp_path / "none.csv") is None
    sidecar_path(csv).write_text("[1, 2]")
    with pytest.raises(ValueError, match="not a planar-tui provenance file"):
        read_sidecar(csv)


@pytest.mark.parametrize(
    ("seconds", "shown"), [(1.23456789, 1.234568), (2.0000004, 2.0), (0.0000015, 0.000002)]
)
def test_the_sidecar_keeps_the_duration_to_the_microsecond(seconds, shown):
    job = load_preset(PRESETS / "paper-a-table1.toml").jobs[0]
    assert job_provenance(job, (0.0, seconds)).duration_s == shown


@pytest.mark.parametrize(
    ("stem", "fits"),
    [("a" * 246, True), ("a" * 247, False), ("é" * 123, True), ("é" * 123 + "a", False)],
)
def test_a_sidecar_is_written_while_its_name_fits_in_255_bytes(tmp_path, stem, fits):
    """``NAME.csv.json`` is 9 bytes longer than NAME: 246 ASCII letters give 255 bytes,
    the limit of a file name (Linux NAME_MAX), 123 two-byte letters 255 too."""
    assert has_sidecar(tmp_path / f"{stem}.csv") is fits


@pytest.mark.parametrize(
    ("argv", "shown"),
    [
        (["/usr/bin/planar-tui", "run", "a b.toml"], "planar-tui run 'a b.toml'"),
        (["/x/planar_tui/__main__.py", "run", "a.toml"], "planar-tui run a.toml"),
        (["-c", "list"], "planar-tui list"),
        (["-m"], "planar-tui"),
        ([], "planar-tui"),
        (["./tool"], "tool"),
    ],
)
def test_the_command_line_comes_from_argv_when_the_cli_did_not_record_it(monkeypatch, argv, shown):
    monkeypatch.setattr(provenance, "invoked", None)
    monkeypatch.setattr("sys.argv", argv)
    assert provenance.command_line() == shown


def test_a_sidecar_of_only_its_kind_reads_with_the_defaults_and_is_indented_by_two():
    record = Provenance.from_json('{"kind": "simulate"}')
    assert (record.label, record.preset_path, record.preset_sha256) == ("", "", None)
    assert record.settings == {} and record.seed is None
    assert record.to_json().startswith('{\n  "kind": "simulate",\n  "label": "",\n')


@pytest.mark.parametrize("key", ["seed", "samples", "duration_s", "precision_cm"])
def test_a_sidecar_number_that_is_true_is_refused(key):
    """JSON true is a bool, which Python counts as an int: refused all the same."""
    with pytest.raises(ValueError, match=f"'{key}' is true or false, must be"):
        Provenance.from_json(json.dumps({"kind": "sweep", key: True}))
    assert getattr(Provenance.from_json(json.dumps({"kind": "sweep", key: 3})), key) == 3


def test_study_sidecars_name_the_study_and_its_job():
    from planar_tui.optimise.spec import parse_optimisations
    from planar_tui.sweep.spec import parse_sweeps

    path = PRESETS / "sweep-tolerance-crossover.toml"
    sweep = parse_sweeps(load_preset(path))[0]
    record = study_provenance("sweep", sweep)
    assert record.kind == "sweep" and record.settings["job_kind"] == sweep.job.kind
    assert record.settings["job_settings"] == JOB_KINDS[sweep.job.kind].dump(sweep.job.spec)
    assert record.settings["job"] == "sensitivity[1]"  # the sweep's table as written
    assert record.preset_sha256 == sha256(path)
    assert Provenance.from_json(record.to_json()) == record
    path = PRESETS / "optimise-3r-tolerance.toml"
    opt = parse_optimisations(load_preset(path))[0]
    record = study_provenance("optimise", opt)
    assert record.kind == "optimise" and record.seed == opt.job.spec.seed
    assert record.settings["seed"] == opt.seed  # the optimiser's own, as written


def test_the_cli_writes_a_sidecar_beside_each_csv_and_leaves_the_csv_as_it_was(tmp_path, cli):
    from planar_tui.batch import prepare_jobs, run_job

    out = tmp_path / "out"
    result = cli("run", PRESETS / "paper-a-table1.toml", "--job", "torques", "--out-dir", out)
    assert result.exit_code == 0, result.output
    (job,) = [j for j in load_preset(PRESETS / "paper-a-table1.toml").jobs if j.kind == "torques"]
    csv = out / job.output
    expected = run_job(prepare_jobs([job])[0]).table
    assert csv.read_text() == "\n".join(expected.lines()) + "\n"  # the CSV's bytes unchanged
    record = read_sidecar(csv)
    assert record is not None and record.kind == "torques" and record.label == job.label
    assert record.settings == JOB_KINDS["torques"].dump(job.spec)
    assert record.preset_sha256 == sha256(PRESETS / "paper-a-table1.toml")
    assert record.duration_s is not None and record.duration_s >= 0
    assert shlex.split(record.command)[1:3] == ["run", str(PRESETS / "paper-a-table1.toml")]


def test_a_sidecar_path_that_cannot_be_written_refuses_the_run_before_anything_is_written(
    tmp_path, cli
):
    out = tmp_path / "out"
    (out / "table1-6r-torques.csv.json").mkdir(parents=True)
    result = cli("run", PRESETS / "paper-a-table1.toml", "--job", "torques", "--out-dir", out)
    assert result.exit_code == 2
    assert "table1-6r-torques.csv.json: (output): is a folder" in result.stderr
    assert sorted(p.name for p in out.iterdir()) == ["table1-6r-torques.csv.json"]


@pytest.mark.parametrize("kind", [3, None, ["torques"], {"name": "torques"}, True])
def test_a_sidecar_whose_kind_is_not_text_is_refused(tmp_path, kind):
    """``kind`` names the job kind a sidecar describes: anything but text is no sidecar
    (the same sidecar with its own text kind reads back)."""
    csv = tmp_path / "r.csv"
    record = job_provenance(load_preset(PRESETS / "paper-a-table4.toml").jobs[0])
    data = json.loads(record.to_json())
    sidecar_path(csv).write_text(json.dumps(data | {"kind": kind}))
    with pytest.raises(ValueError, match=r"r\.csv\.json"):
        read_sidecar(csv)
    with pytest.raises(ValueError):
        Provenance.from_json(json.dumps(data | {"kind": kind}))
    sidecar_path(csv).write_text(json.dumps(data))
    assert read_sidecar(csv) == record
