"""Messages the tabs post to the app (they never call the app's methods).

Textual messages bubble from the posting widget up to the app, which handles them
(``on_document_edited``, ``on_run_requested``, ``on_cancel_requested``). The outcome of a
job comes back as :class:`planar_tui.app.job_runner.JobFinished`.
"""

from __future__ import annotations

from typing import Any

from textual.message import Message


class DocumentEdited(Message):
    """A tab changed the preset document: the app checks it again with the CLI's parser."""


class RunRequested(Message):
    """A job tab asks to run its current job (its Run button)."""

    def __init__(self, pane: Any):
        super().__init__()
        self.pane = pane


class CancelRequested(Message):
    """A job tab asks to cancel the running job (its Cancel button)."""
