"""Error types and exit codes shared by the CLI and the app."""

from __future__ import annotations

from enum import IntEnum
from pathlib import Path


class ExitCode(IntEnum):
    """Process exit codes of ``planar-tui``."""

    OK = 0
    RUN_FAILED = 1
    BAD_INPUT = 2
    INTERRUPTED = 130
    TERMINATED = 143


class PresetError(ValueError):
    """A preset that cannot be used, located by file and dotted key.

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


class BudgetExceeded(PresetError):
    """A valid job that ran out of its budget while running (a workspace's boxes): located
    like a preset error (file, key, what to change), but the input was accepted and the
    job failed, so the CLI exits with 1 (:attr:`exit_code`), not 2."""

    exit_code = 1


class Cancelled(Exception):
    """Raised inside a runner when the user asked it to stop (Ctrl-C, the app's Cancel)."""


class Terminated(KeyboardInterrupt):
    """SIGTERM (``kill``, ``timeout``, systemd, SLURM) during a batch run, raised like
    Ctrl-C's ``KeyboardInterrupt`` so every clean-up that handles it (temporary files)
    applies; the CLI then exits with 143 (128 + 15)."""
