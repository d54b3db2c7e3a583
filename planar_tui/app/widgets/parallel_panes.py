"""The tabs of the parallel robots beyond the 3-RRR: the 3-RRR's workspace pane (map, live
bracket, summary) for the 3-RPR's, the 3-PRR's and the five-bar's workspace jobs. The map
explores as the 3-RRR's (cursor, status, zoom, re-paving); the 3-RRR's own drawing, leg
angles, exact boundary and live preview are not drawn for them (their robots'
``Mechanism.explores`` is false)."""

from __future__ import annotations

from planar_tui.app.widgets.workspace_pane import WorkspacePane


class Workspace3RPRPane(WorkspacePane):
    """The ``workspace3rpr`` kind's tab."""

    kind = "workspace3rpr"


class Workspace3PRRPane(WorkspacePane):
    """The ``workspace3prr`` kind's tab."""

    kind = "workspace3prr"


class FiveBarPane(WorkspacePane):
    """The five-bar's tab: the workspace pane on ``[[workspace5r]]`` jobs."""

    kind = "workspace5r"
