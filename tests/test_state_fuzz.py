"""A mutation fuzz of what the app reads besides presets (as tests/test_preset_fuzz.py
does for presets): provenance sidecars, ``settings.json`` and ``recent.json`` with
characters deleted, duplicated or replaced and values swapped for other JSON (deep
nesting, huge numbers, wrong types). Whatever the text, a sidecar either opens (and its
history line and detail render) or is refused with one :class:`ValueError` line; the
settings give a :class:`Settings` and at most a one-line warning; the recent lists are
lists of text. Never another exception. Deterministic (``derandomize``)."""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from planar_tui.app import recent
from planar_tui.app.runs import RunHistory
from planar_tui.app.settings import Settings, load_settings
from planar_tui.csvio import CsvTable
from planar_tui.dynamics.torques import torques_header
from planar_tui.provenance import sidecar_path

pytestmark = pytest.mark.slow  # hypothesis-driven fuzz (see pyproject.toml's markers)

SIDECAR = json.dumps(
    {
        "kind": "torques",
        "label": "p:torques",
        "preset_path": "/p.toml",
        "preset_sha256": "ab" * 32,
        "settings": {"theta_deg": [[0.0, 10.0]], "plot": None},
        "robot": {"lengths_m": [0.303, 0.214]},
        "seed": None,
        "samples": None,
        "form": None,
        "precision_cm": None,
        "version": "1.0",
        "command": "planar-tui run p.toml",
        "started_utc": "2026-01-02T03:04:05+00:00",
        "duration_s": 0.5,
        "point": {"sweep": "s", "number": 2, "values": {"robot.masses_kg[1]": 1.5}},
        "format": 1,
    },
    indent=2,
)
SETTINGS = json.dumps(
    {"theme": "nord", "last_preset": "/a/p.toml", "form_hidden": True, "output_dir": "out"},
    indent=2,
)
RECENT = json.dumps({"presets": ["/a/p.toml", "/b/q.toml"], "results": ["/a/r.csv"]}, indent=2)
#: Characters that matter to JSON.
ALPHABET = '{}[]":,0123456789.eE+-tfnul \n\\x\0'
#: JSON values a value may become.
VALUES = [
    "null",
    "true",
    "0",
    "-1",
    "1e999",
    "1" + "0" * 5000,
    '"abc"',
    '""',
    "[]",
    "{}",
    "[1, 2]",
    '{"x": 1}',
    '{"sweep": "s", "number": 1, "values": "v"}',
    "NaN",
    "-Infinity",
    '"' + "n" * 5000 + '"',
    '"\\u0000\\u001b[31m"',
    '"\\ud800"',
    "5e-324",
]


@st.composite
def mutated(draw, text: str) -> str:
    """``text`` after one to three mutations: a value replaced, nesting inserted, or
    characters deleted, duplicated or replaced."""
    for _ in range(draw(st.integers(1, 3))):
        at = draw(st.integers(0, len(text)))
        width = draw(st.integers(1, 12))
        operation = draw(st.sampled_from(["value", "nest", "delete", "duplicate", "replace"]))
        if operation == "value":  # a value (after ":" or "[" or ",") replaced
            starts = [i + 1 for i, c in enumerate(text) if c in ":[,"]
            at = draw(st.sampled_from(starts)) if starts else at
            end = min((i for i in map(text.find, ",]}\n", [at] * 4) if i >= 0), default=at)
            text = text[:at] + " " + draw(st.sampled_from(VALUES)) + text[end:]
        elif operation == "nest":
            depth = draw(st.integers(1, 3000))
            starts = [i + 1 for i, c in enumerate(text) if c == ":"] or [at]
            at = draw(st.sampled_from(starts))
            end = min((i for i in map(text.find, ",}\n", [at] * 3) if i >= 0), default=at)
            text = text[:at] + " " + "[" * depth + "1" + "]" * depth + text[end:]
        elif operation == "delete":
            text = text[:at] + text[at + width :]
        elif operation == "duplicate":
            text = text[: at + width] + text[at : at + width] + text[at + width :]
        else:
            text = text[:at] + draw(st.text(ALPHABET, min_size=1, max_size=3)) + text[at + 1 :]
    return text


FOLDER = Path(tempfile.mkdtemp(prefix="planar-tui-state-fuzz-"))
CSV = FOLDER / "r.csv"
CSV.write_text(
    "\n".join(CsvTable(torques_header(2), [[0.0, 0.1, 0, 0, 0, 0, 1.5, 0.25]]).lines()) + "\n"
)
FUZZ = settings(
    max_examples=300,
    derandomize=True,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


def write(path: Path, text: str) -> None:
    path.write_text(text, encoding="utf-8", errors="surrogatepass")


@FUZZ
@given(mutated(SIDECAR))
def test_a_mutated_sidecar_opens_or_is_refused_in_one_line(text):
    write(sidecar_path(CSV), text)
    try:
        run = RunHistory().add_csv(CSV)
    except ValueError as error:
        assert "\n" not in str(error)
        return
    assert run.headline() and run.describe()  # what the history shows renders


@FUZZ
@given(mutated(SETTINGS))
def test_mutated_settings_give_settings_and_at_most_a_one_line_warning(text):
    path = FOLDER / "settings.json"
    write(path, text)
    loaded, warning = load_settings(path)
    assert isinstance(loaded, Settings)
    assert warning is None or "\n" not in warning


@FUZZ
@given(mutated(RECENT))
def test_a_mutated_recent_files_state_gives_lists_of_text(text):
    path = recent.recent_path()
    path.parent.mkdir(parents=True, exist_ok=True)
    write(path, text)
    lists = recent.load()
    assert set(lists) == set(recent.LISTS)
    assert all(isinstance(entry, str) for entries in lists.values() for entry in entries)
