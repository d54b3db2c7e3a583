"""The app's working preset: a TOML-like document edited by the tabs (no Textual here).

The app never validates values itself: every edit lands in :attr:`Workbench.document`
(plain TOML values) and :meth:`Workbench.validate` runs the whole document through
:func:`planar_tui.presets.parse_preset`, the parser the CLI uses, so the messages are the
CLI's. A tab whose kind the preset lacks shows :data:`DEFAULT_TABLES`; the table joins the
document (and so the saved preset) only once it is edited or run.
"""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

from planar_tui.errors import PresetError
from planar_tui.presets import Job, Preset, parse_job, parse_preset, read_toml
from planar_tui.resources import preset_description, resolve_preset

#: The preset opened by ``planar-tui`` without an argument.
DEFAULT_PRESET = "paper-a-table1"

#: Tables shown by a tab when the open preset has none of its kind (small, quick jobs).
DEFAULT_TABLES: dict[str, dict[str, Any]] = {
    "robot": {
        "name": "2R, paper A Table 3",
        "gravity_m_s2": 9.81,
        "lengths_m": [0.303, 0.214],
        "masses_kg": [1.126, 0.796],
        "inertias_kgm2": [0.129, 0.045],
    },
    "simulate": {
        "duration_s": 1.0,
        "step_s": 0.001,
        "torques_Nm": [],
        "every": 10,
        "output": "app-simulate.csv",
    },
    "sensitivity": {
        "posture": "singular",
        "speed_rad_s": 1.0,
        "tolerance_length_mm": 1.0,
        "tolerance_mass_g": 1.0,
        "methods": ["sobol", "efast"],
        "samples": 1024,
        "seed": 42,
        "output": "app-sensitivity.csv",
    },
    "robot3rrr": {
        "base_side_cm": 120.0,
        "platform_side_cm": 40.0,
        "proximal_cm": 30.0,
        "distal_cm": 30.0,
    },
    "workspace": {
        "joint_limits_deg": [[20.0, 70.0], [110.0, 160.0], [245.0, 295.0]],
        "orientation_deg": 0.0,
        "precision_cm": 0.9375,
        "form": "arc-distance",
        "output": "app-workspace.csv",
    },
}


def default_table(kind: str, n_links: int | None = None) -> dict[str, Any]:
    """A copy of the default table of ``kind``; per-link arrays sized for ``n_links``."""
    table = copy.deepcopy(DEFAULT_TABLES.get(kind, {}))
    if kind == "simulate" and n_links is not None:
        table["torques_Nm"] = [0.0] * n_links
    if kind == "simulate" and not table.get("torques_Nm"):
        table.pop("torques_Nm", None)
    return table


class Workbench:
    """An editable preset document and where it came from.

    Parameters
    ----------
    path
        The preset file (names the messages; ``ctrl+s`` offers it).
    document
        The parsed TOML document.
    description
        The preset's first comment line (kept when saving).
    """

    def __init__(self, path: Path | str, document: dict[str, Any], description: str = ""):
        self.path = Path(path)
        self.document = document
        self.description = description

    @classmethod
    def open(cls, argument: str | Path | None) -> Workbench:
        """Open a preset path or bundled name (default :data:`DEFAULT_PRESET`), validated."""
        path = resolve_preset(argument or DEFAULT_PRESET)
        bench = cls(path, read_toml(path), preset_description(path))
        bench.validate()
        return bench

    # -- tables -----------------------------------------------------------------------
    def tables(self, kind: str) -> list[dict[str, Any]]:
        """The document's tables of a job kind (``[kind]`` or ``[[kind]]``), maybe empty."""
        value = self.document.get(kind)
        if value is None:
            return []
        return value if isinstance(value, list) else [value]

    def has(self, kind: str) -> bool:
        """Whether the document holds a table of this kind."""
        return kind in self.document

    def table(self, kind: str, index: int = 0) -> dict[str, Any]:
        """Table ``index`` of ``kind``: the document's, or a default (not yet in the document)."""
        tables = self.tables(kind)
        if index < len(tables):
            return tables[index]
        if kind in self.robot_kinds():
            return default_table(kind)
        robot = self.document.get("robot")
        n_links = len(robot.get("lengths_m", [])) if isinstance(robot, dict) else 2
        return default_table(kind, n_links)

    def set_table(self, kind: str, index: int, table: dict[str, Any]) -> None:
        """Put ``table`` into the document (adding the kind, and its robot if missing)."""
        from planar_tui.registry import JOB_KINDS

        value = self.document.get(kind)
        if value is None:
            self.document[kind] = table
        elif isinstance(value, list):
            if index < len(value):
                value[index] = table
            else:
                value.append(table)
        elif index == 0:
            self.document[kind] = table
        else:
            self.document[kind] = [value, table]
        if kind in JOB_KINDS:
            robot_kind = JOB_KINDS[kind].robot_kind
            if robot_kind not in self.document and robot_kind not in table:
                self.document[robot_kind] = default_table(robot_kind)

    @staticmethod
    def robot_kinds() -> tuple[str, ...]:
        from planar_tui.registry import ROBOT_KINDS

        return tuple(ROBOT_KINDS)

    # -- validation and jobs ----------------------------------------------------------
    def validate(self) -> Preset:
        """Parse the whole document as the CLI would; raises its :class:`PresetError`."""
        return parse_preset(self.path, self.document)

    def job(self, kind: str, index: int = 0) -> Job:
        """The validated job ``index`` (0-based) of ``kind``, checked on its own: a problem
        in another job or in a robot it does not use does not stop it."""
        return parse_job(self.path, self.document, kind, index + 1)

    def problems(self) -> list[PresetError]:
        """Every problem of the document, one per robot table and job at most, in document
        order (each job checked on its own, see :meth:`job`); empty when it is valid."""
        from planar_tui.registry import JOB_KINDS

        found: list[PresetError] = []
        for kind in self.document:
            for index in range(len(self.tables(kind)) if kind in JOB_KINDS else 0):
                try:
                    self.job(kind, index)
                except PresetError as error:
                    found.append(error)
        try:
            self.validate()  # what no job covers: unknown tables, robots no job uses
        except PresetError as error:
            found.append(error)
        unique = {(error.key, error.problem): error for error in reversed(found)}
        return sorted(unique.values(), key=self._document_position)

    def _document_position(self, error: PresetError) -> int:
        """Where the table an error names comes in the document (for ordering)."""
        top = error.key.split(".", 1)[0].split("[", 1)[0]
        names = list(self.document)
        return names.index(top) if top in names else -1

    def display_name(self) -> str:
        """The preset as a person names it: a bundled preset by its name, a file under the
        current folder by its relative path, any other by its file name."""
        from planar_tui.resources import bundled_presets

        if self.path.resolve() in {p.resolve() for p in bundled_presets()}:
            return self.path.stem
        try:
            return str(self.path.resolve().relative_to(Path.cwd().resolve()))
        except ValueError:
            return self.path.name

    # -- robots of jobs (the Robot tab's picker) ----------------------------------------
    def robot_targets(self) -> list[tuple[str, str, int | None]]:
        """The robots the Robot tab can edit: ``(label, robot kind, None)`` for the preset's
        robots, then ``(label, kind, index)`` for each job that carries its own robot."""
        from planar_tui.registry import JOB_KINDS

        targets: list[tuple[str, str, int | None]] = [("preset robots", "", None)]
        for kind in self.document:
            if kind not in JOB_KINDS:
                continue
            robot_kind = JOB_KINDS[kind].robot_kind
            many = isinstance(self.document[kind], list)
            for index, table in enumerate(self.tables(kind)):
                if isinstance(table, dict) and isinstance(table.get(robot_kind), dict):
                    name = f"{kind}[{index + 1}]" if many else kind
                    targets.append((f"{name} {robot_kind}", kind, index))
        return targets

    def job_robot(self, kind: str, index: int) -> dict[str, Any]:
        """The own robot table of job ``index`` of ``kind`` (edited in place)."""
        from planar_tui.registry import JOB_KINDS

        return self.tables(kind)[index][JOB_KINDS[kind].robot_kind]

    def set_job_robot(self, kind: str, index: int, robot: dict[str, Any]) -> None:
        """Replace the own robot table of job ``index`` of ``kind``."""
        from planar_tui.registry import JOB_KINDS

        self.tables(kind)[index][JOB_KINDS[kind].robot_kind] = robot

    def job_labels(self, kind: str) -> list[str]:
        """One label per table of ``kind``: ``kind[i] → output``."""
        return [
            f"{kind}[{i + 1}] → {table.get('output', '(default output)')}"
            for i, table in enumerate(self.tables(kind))
        ]

    def to_toml(self) -> str:
        """The validated document as TOML text (see :mod:`planar_tui.preset_writer`)."""
        from planar_tui.preset_writer import dump_preset

        return dump_preset(self.validate(), self.description)
