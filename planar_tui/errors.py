"""Error types and exit codes shared by the CLI and the app."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from enum import IntEnum
from pathlib import Path


class ExitCode(IntEnum):
    """Process exit codes of ``planar-tui``."""

    OK = 0
    RUN_FAILED = 1
    BAD_INPUT = 2
    INTERRUPTED = 130
    TERMINATED = 143


class LocatedError(Exception):
    """A problem located by file (or ``command line``) and dotted key (or option).

    ``str(error)`` is the one line the CLI prints:
    ``error: FILE: key: what is wrong (expected ...)``.
    """

    def __init__(self, path: Path | str, key: str, problem: str, expected: str | None = None):
        self.path = str(path)
        self.key = key
        self.problem = problem
        self.expected = expected
        super().__init__(self.message)

    @property
    def message(self) -> str:
        """The message without the leading ``error:``."""
        text = f"{self.path}: {self.key}: {self.problem}"
        return f"{text} (expected {self.expected})" if self.expected else text

    def __str__(self) -> str:
        return f"error: {self.message}"


class PresetError(LocatedError, ValueError):
    """A preset (or a command-line option) that cannot be used: bad input, exit code 2,
    refused before anything runs where possible."""


class JobError(LocatedError):
    """A job that started and cannot finish, for a reason its settings explain (a box
    budget exceeded mid-run): a failed job (exit code 1), nothing of it written; the
    message names what to change (``command line: --precision`` when an option set it)."""


class Cancelled(Exception):
    """Raised inside a runner when the user asked it to stop (Ctrl-C, the app's Cancel)."""


class Terminated(KeyboardInterrupt):
    """SIGTERM (``kill``, ``timeout``, systemd, SLURM) during a batch run, raised like
    Ctrl-C's ``KeyboardInterrupt`` so every clean-up that handles it (temporary files)
    applies; the CLI then exits with 143 (128 + 15)."""


class OutputFailed(Exception):
    """A finished job's (or study's) result could not be written."""

    def __init__(self, path: Path | str, reason: str):
        super().__init__(f"{path}: cannot write: {reason}")
        self.path = path


@contextmanager
def writing(path: Path | str, doing: str = "", *, filename_first: bool = False) -> Iterator[None]:
    """Turn an :class:`OSError` raised inside into :class:`OutputFailed` on ``path`` (on
    the error's own file name first when ``filename_first``), the reason being the error's
    ``strerror`` (its text when it has none), after ``doing: `` when given."""
    try:
        yield
    except OSError as error:
        reason = error.strerror or str(error)
        where = (error.filename if filename_first else None) or path
        raise OutputFailed(where, f"{doing}: {reason}" if doing else reason) from None
