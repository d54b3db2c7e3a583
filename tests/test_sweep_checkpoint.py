"""The sweep checkpoint (planar_tui/sweep/checkpoint.py) at the level of its own functions:
every rule of :func:`record_problem` on both sides of its limit, the header's fingerprint
and point count, the line a crash cut short, the rewrite on resume keeping every finished
point, ``fsync`` after each record, and a sweep interrupted twice: the second
resume must not recompute what the first one finished."""

from __future__ import annotations

import json
import os

import pytest

from planar_tui.sweep import checkpoint as cp
from planar_tui.sweep.worker import FAILED, OK, PointOutcome
from tests.sweep_presets import TORQUES, TORQUES_BASE, write

COLUMNS = ("tau1_abs_max_Nm", "tau2_abs_max_Nm")


def good(number=1, status=OK, **changes):
    """A valid record of an ok (or failed, figures-free) point ``number`` of 3."""
    figures = {"tau1_abs_max_Nm": 1.5, "tau2_abs_max_Nm": 0.25} if status == OK else {}
    record = {
        "number": number,
        "status": status,
        "message": "",
        "figures": figures,
        "seconds": 0.5,
        "tables": {},
    }
    record.update(changes)
    return record


def problem(record, seen=(), columns=COLUMNS, total=3):
    return cp.record_problem(record, total, set(seen), lambda number: columns)


def test_a_valid_record_has_no_problem_at_every_edge_of_every_limit():
    assert problem(good()) is None
    assert problem(good(status=FAILED, message="x" * cp.MAX_TEXT)) is None
    assert problem(good(number=3, seconds=0)) is None  # the last number; an int, zero s
    assert problem(good(number=2), seen={1, 3}) is None
    assert (
        problem(good(figures={"tau1_abs_max_Nm": 2, "tau2_abs_max_Nm": "t" * cp.MAX_TEXT})) is None
    )
    assert problem(good(figures={"any": 1.0}), columns=None) is None  # kind names none


@pytest.mark.parametrize(
    ("record", "seen", "words"),
    [
        ([], (), "not a JSON object"),
        ({**good(), "extra": 1}, (), "fields extra missing or unknown"),
        ({k: v for k, v in good().items() if k != "seconds"}, (), "fields seconds"),
        (good(number=0), (), "number 0 is not an integer in 1..3"),
        (good(number=4), (), "number 4 is not"),
        (good(number=True), (), "number true is not"),
        (good(number=1.0), (), "number 1.0 is not"),
        (good(number=2), (2,), "point 2 is recorded twice"),
        (good(status="done"), (), 'status "done" is not one of ok, failed'),
        (good(message="two\nlines"), (), "message is not one line"),
        (good(message=3), (), "message is not one line"),
        (good(message="x" * (cp.MAX_TEXT + 1)), (), "message is not one line"),
        (good(seconds=-1e-300), (), "seconds -1e-300 is not a finite number >= 0"),
        (good(seconds=float("inf")), (), "seconds Infinity"),
        (good(seconds=True), (), "seconds true"),
        (good(seconds="1"), (), 'seconds "1"'),
        (good(tables={"a.csv": "t"}), (), "tables is not empty"),
        (good(tables=[]), (), "tables is not empty"),
        (good(figures=[1]), (), "figures [1] is not a mapping"),
        (good(status=FAILED, figures={"tau1_abs_max_Nm": 1.0}), (), "a failed point has figures"),
        (good(figures={**good()["figures"], "forged": 1}), (), 'figure "forged" is not a column'),
        (good(figures={"tau1_abs_max_Nm": float("nan"), "tau2_abs_max_Nm": 1}), (), "tau1_abs"),
        (good(figures={"tau1_abs_max_Nm": None, "tau2_abs_max_Nm": 1}), (), "= null is not"),
        (good(figures={"tau1_abs_max_Nm": "a\nb", "tau2_abs_max_Nm": 1}), (), "is not a finite"),
        (
            good(figures={"tau1_abs_max_Nm": "t" * (cp.MAX_TEXT + 1), "tau2_abs_max_Nm": 1}),
            (),
            "is not a finite number or text",
        ),
        (good(figures={"tau1_abs_max_Nm": 1.0}), (), "figure tau2_abs_max_Nm is missing"),
    ],
)
def test_each_rule_of_a_record_names_its_problem(record, seen, words):
    found = problem(record, seen)
    assert found is not None and words in found, found


def test_a_failed_point_is_not_checked_against_the_columns_of_an_ok_one():
    """A failed point has no figures, so none can be missing (``columns`` not consulted)."""
    asked: list[int] = []

    def columns(number):
        asked.append(number)
        return COLUMNS

    found = cp.record_problem(good(status=FAILED), 3, set(), columns)
    assert found is None and asked == []


def test_shown_value_cuts_a_long_value_to_40_characters():
    assert cp.shown_value("x" * 38) == json.dumps("x" * 38)  # 40 characters: whole
    assert cp.shown_value("x" * 39) == '"' + "x" * 36 + "..."  # 41: cut
    assert len(cp.shown_value(list(range(100)))) == 40


def outcome(number, status=OK):
    record = good(number, status)
    return PointOutcome(**record)


def line(record, fingerprint="fp"):
    """A record's checkpoint line as the writer makes it, with its digest
    (:func:`~planar_tui.sweep.checkpoint.record_digest`); a non-object record as it is."""
    if not isinstance(record, dict):
        return json.dumps(record)
    return json.dumps({**record, "digest": cp.record_digest(fingerprint, record)})


def read_back(text_line):
    """A written record without its digest."""
    record = json.loads(text_line)
    record.pop("digest", None)
    return record


def lines_of(*records, header=None):
    header = header or {"fingerprint": "fp", "points": 3}
    return "\n".join([json.dumps(header), *map(line, records)]) + "\n"


def test_read_finished_keeps_the_good_records_and_warns_once_per_bad_one(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text(lines_of(good(1), good(1), good(number=0), good(3, FAILED)))
    warnings: list[str] = []
    finished = cp.read_finished(path, "fp", 3, lambda n: COLUMNS, warnings.append)
    assert finished == {1: outcome(1), 3: outcome(3, FAILED)}
    assert warnings == [
        f"{path}:3: record dropped (point 1 is recorded twice): its point runs again",
        f"{path}:4: record dropped (number 0 is not an integer in 1..3): its point runs again",
    ]


def test_a_line_cut_short_by_a_crash_is_dropped_silently_only_when_it_is_the_last(tmp_path):
    path = tmp_path / "c.jsonl"
    cut = line(good(2))[:-7]
    path.write_text(lines_of(good(1)) + cut)  # the crash: no newline, half a record
    warnings: list[str] = []
    assert cp.read_finished(path, "fp", 3, warn=warnings.append) == {1: outcome(1)}
    assert warnings == []
    path.write_text(lines_of(good(1)) + cut + "\n" + line(good(3)) + "\n")
    assert cp.read_finished(path, "fp", 3, warn=warnings.append) == {1: outcome(1), 3: outcome(3)}
    assert warnings == [f"{path}:3: record dropped (not JSON): its point runs again"]


def test_as_many_bad_records_as_the_warning_limit_give_no_count_line(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text(lines_of(*[good(number=0)] * cp.MAX_WARNINGS))
    warnings: list[str] = []
    assert cp.read_finished(path, "fp", 3, warn=warnings.append) == {}
    assert len(warnings) == cp.MAX_WARNINGS and all("record dropped" in w for w in warnings)


def test_more_bad_records_than_the_warning_limit_give_one_count_line(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text(lines_of(*[good(number=0)] * (cp.MAX_WARNINGS + 2), good(2)))
    warnings: list[str] = []
    assert cp.read_finished(path, "fp", 3, warn=warnings.append) == {2: outcome(2)}
    assert len(warnings) == cp.MAX_WARNINGS + 1
    assert warnings[-1] == f"{path}: 2 more records dropped: their points run again"


@pytest.mark.parametrize(
    "header",
    [{"fingerprint": "other", "points": 3}, {"fingerprint": "fp", "points": 4}, {"points": 3}],
)
def test_a_header_of_another_sweep_or_point_count_resumes_nothing(tmp_path, header):
    path = tmp_path / "c.jsonl"
    path.write_text(lines_of(good(1), header=header))
    warnings: list[str] = []
    assert cp.read_finished(path, "fp", 3, warn=warnings.append) == {}
    assert warnings == []  # another sweep's checkpoint: replaced, no warning


@pytest.mark.parametrize("first", ["[]", "{", ""])
def test_a_first_line_that_is_no_header_warns_and_resumes_nothing(tmp_path, first):
    path = tmp_path / "c.jsonl"
    path.write_text(first + "\n" + line(good(1)) + "\n")
    warnings: list[str] = []
    assert cp.read_finished(path, "fp", 3, warn=warnings.append) == {}
    assert warnings == [f"{path}:1: not a checkpoint header: every point runs"]


def test_a_missing_or_unreadable_checkpoint_resumes_nothing(tmp_path):
    assert cp.read_finished(tmp_path / "none.jsonl", "fp", 3) == {}
    path = tmp_path / "c.jsonl"
    path.write_bytes(b'{"fingerprint": "\xff"}\n')
    assert cp.read_finished(path, "fp", 3) == {}
    path.write_text("")
    assert cp.read_finished(path, "fp", 3) == {}


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ('{"fingerprint": "abc", "points": 2}\n{"number": 1}\n', "abc"),
        ('{"fingerprint": 3}\n', ""),
        ("[1]\n", ""),
        ('{"fingerp', ""),
        ("", ""),
    ],
)
def test_existing_fingerprint_reads_the_first_line_only(tmp_path, text, expected):
    path = tmp_path / "c.jsonl"
    path.write_text(text)
    assert cp.existing_fingerprint(path) == expected
    path.write_bytes(b"\xff\xfe\n")
    assert cp.existing_fingerprint(path) == ""
    assert cp.existing_fingerprint(tmp_path / "none.jsonl") is None


def test_a_fresh_writer_writes_the_header_and_each_added_point(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text("an earlier sweep's checkpoint\n")
    writer = cp.CheckpointWriter(path, "fp", 3, {})
    with_tables = PointOutcome(
        2, OK, "", {"tau1_abs_max_Nm": 1.5, "tau2_abs_max_Nm": 0.25}, 0.5, {"point-2.csv": "a,b\n"}
    )
    writer.add(with_tables)
    writer.close()
    lines = path.read_text().splitlines()
    assert json.loads(lines[0]) == {"fingerprint": "fp", "points": 3}
    assert read_back(lines[1]) == good(2)  # its tables are not kept
    assert cp.read_finished(path, "fp", 3, lambda n: COLUMNS) == {2: outcome(2)}


def test_a_resumed_writer_keeps_every_finished_point_and_drops_a_cut_line(tmp_path):
    path = tmp_path / "c.jsonl"
    path.write_text(lines_of(good(3), good(1, FAILED)) + line(good(2))[:9])
    finished = cp.read_finished(path, "fp", 3)
    assert finished == {1: outcome(1, FAILED), 3: outcome(3)}
    writer = cp.CheckpointWriter(path, "fp", 3, finished)
    writer.add(outcome(2))
    writer.close()
    assert path.read_text() == lines_of(good(1, FAILED), good(3), good(2))
    assert cp.read_finished(path, "fp", 3) == {**finished, 2: outcome(2)}


def test_each_added_point_is_synced_to_disk_unless_the_caller_syncs_a_batch(tmp_path, monkeypatch):
    synced: list[int] = []
    real_fsync = os.fsync

    def fsync(fd):
        synced.append(fd)
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    writer = cp.CheckpointWriter(tmp_path / "c.jsonl", "fp", 3, {})
    synced.clear()  # (the atomic header write may sync too)
    writer.add(outcome(1))
    fd = writer._stream.fileno()
    assert synced == [fd]
    writer.add(outcome(2), sync=False)
    assert synced == [fd]
    assert (tmp_path / "c.jsonl").read_text().count("\n") == 3  # flushed all the same
    writer.sync()
    assert synced == [fd, fd]
    writer.close()


FOUR_POINTS = """[[sweep]]
job = "torques"
values."robot.masses_kg[2]" = [1.0, 2.0, 3.0, 4.0]
output = "s.csv"
"""


def test_a_sweep_interrupted_twice_never_recomputes_a_finished_point(tmp_path):
    """Stopped (Ctrl-C) after point 1, resumed and stopped after point 2, resumed again:
    the checkpoint holds 1, then 1 and 2 (the first resume's rewrite kept point 1); the
    last run computes only 3 and 4 and its CSV equals an uninterrupted run's figures."""
    from planar_tui.presets import load_preset
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    preset = write(tmp_path, "p.toml", TORQUES, FOUR_POINTS, **TORQUES_BASE)
    (sweep,) = parse_sweeps(load_preset(preset))
    out = tmp_path / "out"
    checkpoint = cp.checkpoint_path(out / "s.csv")
    computed: list[int] = []

    def stop_after(number):
        def on_outcome(done):
            if done.number not in resumed:
                computed.append(done.number)
            if done.number == number:
                raise KeyboardInterrupt

        return on_outcome

    def finished_numbers():
        return sorted(cp.read_finished(checkpoint, sweep.fingerprint(), 4))

    resumed: set[int] = set()
    with pytest.raises(KeyboardInterrupt):
        run_sweep(sweep, out_dir=out, on_outcome=stop_after(1))
    assert finished_numbers() == [1]
    resumed = {1}
    with pytest.raises(KeyboardInterrupt):
        run_sweep(sweep, out_dir=out, resume=True, on_outcome=stop_after(2))
    assert finished_numbers() == [1, 2]
    resumed = {1, 2}
    run = run_sweep(sweep, out_dir=out, resume=True, on_outcome=stop_after(0))
    assert run.resumed == 2
    assert computed == [1, 2, 3, 4]  # each point computed once over the three runs
    assert not checkpoint.exists()  # done: removed
    fresh = run_sweep(sweep)
    figures = [[row[2], row[3]] for row in run.table.rows]
    assert figures == [[row[2], row[3]] for row in fresh.table.rows]
