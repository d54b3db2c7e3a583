"""Every file the app reads is bounded and validated: provenance sidecars field
by field, and sidecars, settings, the recent-files state and presets read only when they
are regular files under their size bound (a FIFO is refused without waiting, ``/dev/zero``
without reading). Refusals are one line (exit code 2 where the CLI reads the file); the
app's own state files give the defaults and a warning."""

from __future__ import annotations

import dataclasses
import json
import os
import resource
import shutil
from pathlib import Path

import pytest

from planar_tui.app import recent
from planar_tui.app.runs import RunHistory
from planar_tui.app.settings import MAX_STATE_BYTES, Settings, load_settings, settings_path
from planar_tui.csvio import CsvTable
from planar_tui.dynamics.torques import torques_header
from planar_tui.errors import PresetError
from planar_tui.presets import MAX_PRESET_BYTES, read_toml
from planar_tui.provenance import (
    FIELD_TYPES,
    MAX_SIDECAR_BYTES,
    Provenance,
    read_sidecar,
    sidecar_path,
)
from tests.conftest import PRESETS

DATA = Path(__file__).parent / "data" / "app"

GOOD = {
    "kind": "torques",
    "label": "p:torques",
    "preset_path": "/p.toml",
    "preset_sha256": None,
    "settings": {"theta_deg": [[0.0, 10.0]]},
    "robot": {"lengths_m": [0.303, 0.214]},
    "started_utc": "2026-01-02T03:04:05+00:00",
    "duration_s": 0.5,
}


def result_csv(folder: Path, sidecar: str | None = None) -> Path:
    """A torques result CSV of one row (and its sidecar's text, when given)."""
    path = folder / "r.csv"
    table = CsvTable(torques_header(2), [[0.0, 0.1, 0, 0, 0, 0, 1.5, 0.25]])
    path.write_text("\n".join(table.lines()) + "\n")
    if sidecar is not None:
        sidecar_path(path).write_text(sidecar)
    return path


def test_a_good_sidecar_opens_with_its_provenance(tmp_path):
    run = RunHistory().add_csv(result_csv(tmp_path, json.dumps(GOOD)))
    assert run.provenance is not None and run.label == "p:torques"
    assert "settings: theta_deg = [[0.0, 10.0]]" in run.describe()
    assert run.headline()["time"] != "-"


def test_every_field_of_a_sidecar_has_a_declared_type():
    assert set(FIELD_TYPES) == {f.name for f in dataclasses.fields(Provenance)}


BAD_FIELDS = [
    ({"point": "abc"}, "'point' is text, must be an object or null"),
    ({"point": {"x": 1}}, "'point.sweep' must be text"),
    ({"point": {"sweep": "s", "number": 1, "values": "v"}}, "'point.values' must be an object"),
    ({"point": {"sweep": "s", "number": True, "values": {}}}, "'point.number' must be an integer"),
    ({"settings": [1, 2]}, "'settings' is an array, must be an object"),
    ({"label": {"a": 1}}, "'label' is an object, must be text"),
    ({"robot": "2R"}, "'robot' is text, must be an object"),
    ({"started_utc": 5}, "'started_utc' is an integer, must be text or null"),
    ({"started_utc": "yesterday"}, "'started_utc' is 'yesterday', not an ISO 8601 time"),
    ({"seed": 1.5}, "'seed' is a number, must be an integer or null"),
    ({"samples": True}, "'samples' is true or false, must be an integer or null"),
    ({"duration_s": "1 s"}, "'duration_s' is text, must be an integer or a number or null"),
    ({"settings": {"a": json.loads("[" * 32 + "1" + "]" * 32)}}, "nested more than 32 levels deep"),
]


@pytest.mark.parametrize(("change", "message"), BAD_FIELDS)
def test_a_sidecar_field_of_the_wrong_type_is_refused_in_one_line(tmp_path, change, message):
    csv = result_csv(tmp_path, json.dumps(GOOD | change))
    with pytest.raises(ValueError) as caught:
        RunHistory().add_csv(csv)
    assert str(caught.value) == f"{sidecar_path(csv)}: {message}"


def test_a_sidecar_nested_100_000_deep_is_refused_without_recursion_error(tmp_path):
    deep = json.dumps(GOOD)[:-1] + ', "robot": ' + "[" * 100_000 + "]" * 100_000 + "}"
    with pytest.raises(ValueError, match="nested more than 32 levels deep"):
        read_sidecar(result_csv(tmp_path, deep))


def test_tui_open_with_a_damaged_sidecar_exits_2_in_one_line(tmp_path, cli):
    csv = result_csv(tmp_path, json.dumps(GOOD | {"point": "abc"}))
    result = cli("tui", DATA / "tiny.toml", "--open", csv)
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert result.stderr == (
        f"error: {csv}: (file): {sidecar_path(csv).name}: 'point' is text, must be an object"
        " or null (expected a result CSV planar-tui wrote)\n"
    ) or result.stderr.splitlines() == [result.stderr.strip()]
    assert "'point' is text" in result.stderr


# -- sidecars that are no regular file, or too large -------------------------------------
def peak_rss_bytes() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def test_a_fifo_sidecar_is_refused_without_waiting_for_a_writer(tmp_path):
    csv = result_csv(tmp_path)
    os.mkfifo(sidecar_path(csv))
    with pytest.raises(ValueError, match=r"r\.csv\.json: cannot be read: is not a regular file"):
        read_sidecar(csv)  # the test would hang here if the FIFO were opened blocking


def test_a_dev_zero_sidecar_is_refused_without_reading(tmp_path):
    csv = result_csv(tmp_path)
    sidecar_path(csv).symlink_to("/dev/zero")
    before = peak_rss_bytes()
    with pytest.raises(ValueError, match="is not a regular file"):
        read_sidecar(csv)
    assert peak_rss_bytes() - before < 64 * 2**20


def test_a_sidecar_over_its_bound_is_refused_before_it_is_read(tmp_path):
    csv = result_csv(tmp_path)
    with open(sidecar_path(csv), "wb") as sparse:  # 300 MB of zeros, no disk used
        sparse.truncate(300_000_000)
    before = peak_rss_bytes()
    with pytest.raises(ValueError, match=r"is 286 MiB, more than the 16 MiB a provenance file"):
        read_sidecar(csv)
    assert peak_rss_bytes() - before < 64 * 2**20
    assert MAX_SIDECAR_BYTES == 16 * 2**20


# -- the app's settings and recent files -------------------------------------------------
def test_a_fifo_or_dev_zero_settings_file_gives_the_defaults_and_a_warning(tmp_path):
    os.mkfifo(tmp_path / "fifo.json")
    (tmp_path / "zero.json").symlink_to("/dev/zero")
    for name in ("fifo.json", "zero.json"):
        settings, warning = load_settings(tmp_path / name)
        assert settings == Settings()
        assert warning == (
            f"{tmp_path / name}: cannot be read (is not a regular file (a device, FIFO or "
            "socket)); using the default settings"
        )


def test_a_settings_file_over_its_bound_gives_the_defaults_and_a_warning(tmp_path):
    path = tmp_path / "settings.json"
    path.write_text(json.dumps({"theme": "nord", "output_dir": "x" * MAX_STATE_BYTES}))
    settings, warning = load_settings(path)
    assert settings == Settings()
    assert warning is not None and "more than the 512 KiB a settings file may have" in warning


def test_a_settings_file_at_its_bound_is_read(tmp_path):
    path = tmp_path / "settings.json"
    text = json.dumps({"theme": "nord", "output_dir": ""})
    path.write_text(text[:-2] + "x" * (MAX_STATE_BYTES - len(text)) + '"}')
    assert path.stat().st_size == MAX_STATE_BYTES
    settings, warning = load_settings(path)
    assert warning is None and settings.theme == "nord"


@pytest.mark.parametrize("make", ["fifo", "zero", "large"])
def test_a_recent_files_state_that_is_no_small_regular_file_counts_as_empty(make):
    path = recent.recent_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    if make == "fifo":
        os.mkfifo(path)
    elif make == "zero":
        path.symlink_to("/dev/zero")
    else:
        path.write_text(json.dumps({"presets": ["/a.toml"], "results": ["x" * MAX_STATE_BYTES]}))
    assert recent.load() == {"presets": [], "results": []}


# -- presets -------------------------------------------------------------------------------
def test_a_preset_over_its_bound_is_refused_before_it_is_read(tmp_path):
    path = tmp_path / "huge.toml"
    with open(path, "wb") as sparse:  # 4 GiB, sparse
        sparse.truncate(4 * 2**30)
    before = peak_rss_bytes()
    with pytest.raises(PresetError) as caught:
        read_toml(path)
    assert peak_rss_bytes() - before < 64 * 2**20
    assert str(caught.value) == (
        f"error: {path}: (file): cannot be read: is 4.1e+03 MiB, more than the 4 MiB a preset"
        " may have (expected a readable UTF-8 TOML file)"
    )
    assert MAX_PRESET_BYTES == 4 * 2**20


def test_an_unreadable_remembered_preset_says_it_came_from_the_settings(tmp_path, cli):
    preset = tmp_path / "last.toml"
    shutil.copy(PRESETS / "paper-a-table1.toml", preset)
    with open(preset, "ab") as grown:
        grown.truncate(MAX_PRESET_BYTES + 1)
    settings_path().write_text(json.dumps({"last_preset": str(preset)}))
    result = cli("tui")
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert len(result.stderr.strip().splitlines()) == 1
    assert f"error: {preset}: (file): cannot be read: " in result.stderr
    assert f"(the last preset opened, remembered in {settings_path()}" in result.stderr
