"""The tabs of the parallel robots beyond the 3-RRR: the 3-RRR's workspace pane (map, live
bracket, summary) for the 3-RPR's and the 3-PRR's workspace jobs."""

from __future__ import annotations

from planar_tui.app.widgets.workspace_pane import WorkspacePane


class Workspace3RPRPane(WorkspacePane):
    """The ``workspace3rpr`` kind's tab."""

    kind = "workspace3rpr"


class Workspace3PRRPane(WorkspacePane):
    """The ``workspace3prr`` kind's tab."""

    kind = "workspace3prr"
