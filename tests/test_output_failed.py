"""One helper turns an OS error while writing into :class:`OutputFailed`
(:func:`planar_tui.errors.writing`): the path named is the one written (or the error's own
file, when asked), the reason the system's words, nothing else is caught."""

from __future__ import annotations

import errno

import pytest

from planar_tui.errors import OutputFailed, writing


def test_an_os_error_is_output_failed_on_the_path_with_the_system_reason(tmp_path):
    target = tmp_path / "missing" / "out.csv"
    with pytest.raises(OutputFailed) as raised, writing(target):
        target.write_text("x")
    assert raised.value.path == target
    assert str(raised.value) == f"{target}: cannot write: No such file or directory"
    assert raised.value.__cause__ is None and raised.value.__suppress_context__


def test_what_was_being_done_prefixes_the_reason():
    with pytest.raises(OutputFailed) as raised, writing("p.csv", "cannot delete the old file"):
        raise PermissionError(errno.EACCES, "Permission denied", "p.csv")
    assert str(raised.value) == "p.csv: cannot write: cannot delete the old file: Permission denied"


def test_the_error_s_own_file_first_when_asked_else_the_path_given():
    error = OSError(errno.ENOSPC, "No space left on device", "table.csv.json")
    with pytest.raises(OutputFailed) as raised, writing("table.csv", filename_first=True):
        raise error
    assert raised.value.path == "table.csv.json"
    with pytest.raises(OutputFailed) as raised, writing("table.csv"):
        raise error
    assert raised.value.path == "table.csv"
    with pytest.raises(OutputFailed) as raised, writing("table.csv", filename_first=True):
        raise OSError("no errno, no file name")
    assert str(raised.value) == "table.csv: cannot write: no errno, no file name"


def test_other_errors_pass_through():
    with pytest.raises(ValueError, match="not an OS error"), writing("t.csv"):
        raise ValueError("not an OS error")
