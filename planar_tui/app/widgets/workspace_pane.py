"""The Workspace tab: the 3-RRR workspace map, the area bracket and box counts."""

from __future__ import annotations

from typing import ClassVar

from planar_tui.app.widgets.panes import JobPane


class WorkspacePane(JobPane):
    """Form, precision, orientation, joint limits; the character-cell map and summary."""

    kind: ClassVar[str] = "workspace"
