"""The app's working preset: a TOML-like document edited by the tabs (no Textual here).

The app never validates values itself: every edit lands in :attr:`Workbench.document`
(plain TOML values) and :meth:`Workbench.validate` runs the whole document through
:func:`planar_tui.presets.parse_preset`, the parser the CLI uses, so the messages are the
CLI's. A tab whose kind the preset lacks shows the table its kind declares
(:func:`default_table`); the table joins the document (and so the saved preset) only once
it is edited or run.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from planar_tui.app.history import EditHistory, link_count, resize_per_link
from planar_tui.app.saving import draft_text, merge_document, same_value
from planar_tui.errors import PresetError
from planar_tui.preset_writer import dump_preset
from planar_tui.presets import Job, Preset, parse_job, parse_preset, read_toml
from planar_tui.registry import JOB_KINDS, ROBOT_KINDS
from planar_tui.resources import bundled_presets, preset_description, resolve_preset
from planar_tui.schema import per_link_keys
from planar_tui.sweep.service import check_preset_sweeps

T = TypeVar("T")

#: The preset opened by ``planar-tui`` without an argument.
DEFAULT_PRESET = "paper-a-table1"


def default_table(kind: str, n_links: int | None = None) -> dict[str, Any]:
    """A copy of the table the kind declares for a tab when the preset has none of it
    (:attr:`~planar_tui.jobkind.JobKind.app_default`,
    :attr:`~planar_tui.jobkind.RobotKind.app_default`; empty for an unknown name), its
    per-link arrays sized for ``n_links`` links and an empty one left out."""
    if kind in JOB_KINDS:
        table = copy.deepcopy(dict(JOB_KINDS[kind].app_default))
        if n_links is not None:
            resize_per_link(table, kind, n_links)
        for key in per_link_keys(JOB_KINDS[kind].settings):
            if table.get(key) == []:
                del table[key]
        return table
    if kind in ROBOT_KINDS:
        return copy.deepcopy(dict(ROBOT_KINDS[kind].app_default))
    return {}


class Workbench:
    """An editable preset document and where it came from.

    Parameters
    ----------
    path
        The preset file (names the messages; ``ctrl+s`` offers it).
    document
        The parsed TOML document.
    description
        The preset's first comment line (written when there is no original text).
    original_text
        The file's text: saving applies the edits into it (comments and order kept, see
        :mod:`planar_tui.app.saving`).

    :attr:`history` holds the document before each edit (``ctrl+z``), :attr:`saved` the
    document as last opened or saved (:attr:`modified` compares them), :attr:`notes` what
    an edit changed besides itself (per-link arrays resized), for the app to show.
    """

    def __init__(
        self,
        path: Path | str,
        document: dict[str, Any],
        description: str = "",
        original_text: str | None = None,
    ):
        self.path = Path(path)
        self.document = document
        self.description = description
        self.original_text = original_text
        self.saved = copy.deepcopy(document)
        self.history = EditHistory()
        self.notes: list[str] = []

    @classmethod
    def open(cls, argument: str | Path | None, *, check: bool = True) -> Workbench:
        """Open a preset path or bundled name (default :data:`DEFAULT_PRESET`), validated
        unless ``check`` is false (the app's open dialog: a preset whose values are wrong
        opens with its problems marked; one that is no TOML cannot); every failure is a
        :class:`PresetError` (even what the TOML parser did not expect: nesting too deep,
        integers too long)."""
        path = resolve_preset(argument or DEFAULT_PRESET)
        document = guarded(path, lambda: read_toml(path))
        text = path.read_text(encoding="utf-8")
        bench = cls(path, document, preset_description(path), text)
        if check:
            bench.validate()
        return bench

    @classmethod
    def open_marked(cls, argument: str | Path | None) -> Workbench:
        """Open a preset for the app whatever its values (they are marked on the tabs): a
        table that is no table (``robot = 3``) becomes an empty table in the document, the
        file as it was (so the document shows as modified), and :attr:`notes` says which
        (:func:`repair_tables`). Only a file that cannot be read or is no TOML raises."""
        bench = cls.open(argument, check=False)
        bench.notes += repair_tables(bench.document)
        return bench

    # -- edits, undo, saved state -----------------------------------------------------
    @property
    def modified(self) -> bool:
        """Whether the document differs from the file as last opened or saved."""
        return not same_value(self.document, self.saved)

    def undo(self) -> bool:
        """Go back to the document before the latest edit; ``False`` if there is none."""
        state = self.history.pop()
        if state is None:
            return False
        self.document = state
        return True

    def mark_saved(self, path: Path, text: str) -> None:
        """The document was written to ``path`` as ``text`` (the next save starts there)."""
        self.path = Path(path)
        self.original_text = text
        self.saved = copy.deepcopy(self.document)

    def take_notes(self) -> list[str]:
        """The notes of the edits since the last call (and forget them)."""
        notes, self.notes = self.notes, []
        return notes

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
        """Put ``table`` into the document (adding the kind, and its robot if missing);
        the document before is kept for undo. When the edit changes a serial robot's link
        count, the per-link arrays of the jobs using that robot are resized (see
        :meth:`resize_jobs`)."""
        tables = self.tables(kind)
        before = tables[index] if index < len(tables) else None
        if before is None or not same_value(before, table):
            self.history.record(self.document, edit_group(kind, index, before or {}, table))
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
        self._resize_per_link(kind, before or {}, table)

    def _resize_per_link(self, kind: str, before: dict[str, Any], table: dict[str, Any]) -> None:
        """After an edit of ``kind``'s table: if it changed a serial robot's link count
        (the preset's ``[robot]`` or a job's own), resize the per-link arrays using it."""
        if kind == "robot":
            old, new = link_count(before), link_count(table)
            if old is not None and new is not None and old != new:
                self.resize_jobs(new)
            return
        old, new = link_count(before.get("robot")), link_count(table.get("robot"))
        if old is not None and new is not None and old != new:
            self._note_resized([f"{kind}.{key}" for key in resize_per_link(table, kind, new)], new)

    def resize_jobs(self, n_links: int) -> None:
        """Resize the per-link arrays (``theta0_deg``, ``torques_Nm`` rows, a posture's
        angles …) of every job on the preset's ``[robot]`` to ``n_links`` (new links get
        zeros), noting which."""
        changed = []
        for kind in JOB_KINDS:
            if JOB_KINDS[kind].robot_kind != "robot":
                continue
            for table in self.tables(kind):
                if "robot" not in table:  # a job with its own robot keeps its arrays
                    changed += [f"{kind}.{key}" for key in resize_per_link(table, kind, n_links)]
        self._note_resized(changed, n_links)

    def _note_resized(self, keys: list[str], n_links: int) -> None:
        if keys:
            names = ", ".join(dict.fromkeys(keys))
            self.notes.append(f"{names} resized to {n_links} links (new links: 0)")

    @staticmethod
    def robot_kinds() -> tuple[str, ...]:
        return tuple(ROBOT_KINDS)

    # -- validation and jobs ----------------------------------------------------------
    def validate(self) -> Preset:
        """Parse the whole document as the CLI would; raises its :class:`PresetError`
        (also for what the parser did not expect, see :func:`guarded`)."""
        return guarded(self.path, lambda: parse_preset(self.path, self.document), self.document)

    def job(self, kind: str, index: int = 0) -> Job:
        """The validated job ``index`` (0-based) of ``kind``, checked on its own: a problem
        in another job or in a robot it does not use does not stop it."""
        return guarded(
            self.path, lambda: parse_job(self.path, self.document, kind, index + 1), self.document
        )

    def check(self) -> tuple[Preset | None, list[PresetError]]:
        """The validated preset and no problem, or ``None`` and every problem of the
        document, one per robot table and job at most, in document order (each job checked
        on its own, see :meth:`job`); a document whose jobs are valid has its sweeps checked
        as the CLI checks them (:func:`~planar_tui.sweep.service.check_preset_sweeps`). A
        valid document is parsed once."""
        try:
            preset = self.validate()
        except PresetError as error:
            found = [error]  # may be what no job covers: an unknown table, an unused robot
        else:
            try:  # the sweeps, checked as the CLI does before running them
                guarded(self.path, lambda: check_preset_sweeps(preset), self.document)
            except PresetError as error:
                return None, [error]
            return preset, []
        for kind in self.document:
            for index in range(len(self.tables(kind)) if kind in JOB_KINDS else 0):
                try:
                    self.job(kind, index)
                except PresetError as error:
                    found.append(error)
        unique = {(error.key, error.problem): error for error in reversed(found)}
        return None, sorted(unique.values(), key=self._document_position)

    def problems(self) -> list[PresetError]:
        """Every problem of the document (see :meth:`check`); empty when it is valid."""
        return self.check()[1]

    def _document_position(self, error: PresetError) -> int:
        """Where the table an error names comes in the document (for ordering)."""
        top = error.key.split(".", 1)[0].split("[", 1)[0]
        names = list(self.document)
        return names.index(top) if top in names else -1

    def display_name(self) -> str:
        """The preset as a person names it: a bundled preset by its name, a file under the
        current folder by its relative path, any other by its file name."""
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
        return self.tables(kind)[index][JOB_KINDS[kind].robot_kind]

    def set_job_robot(self, kind: str, index: int, robot: dict[str, Any]) -> None:
        """Replace the own robot table of job ``index`` of ``kind``."""
        self.tables(kind)[index][JOB_KINDS[kind].robot_kind] = robot

    def job_labels(self, kind: str) -> list[str]:
        """One label per table of ``kind``: ``kind[i] → output``."""
        return [
            f"{kind}[{i + 1}] → {table.get('output', '(default output)')}"
            for i, table in enumerate(self.tables(kind))
        ]

    def digest(self) -> str | None:
        """The SHA-256 (hex) of the edited document as it would be saved (``None`` when
        unmodified: the file's own bytes say what runs). A document with a problem in
        another job still runs its valid jobs: its digest is that of the draft text
        (:func:`planar_tui.app.saving.draft_text`), what saving it anyway would write."""
        import hashlib

        if not self.modified:
            return None
        try:
            text = self.to_toml()
        except PresetError:
            text = draft_text(self.document, self.original_text, self.description)
        return hashlib.sha256(text.encode()).hexdigest()

    def to_toml(self) -> str:
        """The validated document as TOML text: applied into the original file's text
        (comments, order and formatting kept, :func:`planar_tui.app.saving.merge_document`),
        or printed by :mod:`planar_tui.preset_writer` when there is none."""
        preset = self.validate()
        if self.original_text is None:
            return dump_preset(preset, self.description)
        return merge_document(self.original_text, self.document)


def edit_group(kind: str, index: int, before: dict[str, Any], after: dict[str, Any]) -> Any:
    """What an edit changed, for the undo history: the table, its changed keys and its link
    count (typing into one field repeats the group and is one step; each added or
    removed link is a step of its own)."""
    keys = frozenset(
        k for k in before.keys() | after.keys() if not same_value(before.get(k), after.get(k))
    )
    return kind, index, keys, link_count(after)


def guarded(path: Path, action: Callable[[], T], document: Any = None) -> T:
    """``action()``, with any failure but a :class:`PresetError` turned into one: TOML
    nested too deep (``RecursionError``), an integer too long to read or too large for a
    float (``ValueError``, ``OverflowError``) … The key is found in ``document`` when
    given (see :func:`find_unreadable`)."""
    try:
        return action()
    except PresetError:
        raise
    except Exception as error:
        key, problem, expected = find_unreadable(document)
        if key is None:
            problem = f"cannot be read: {type(error).__name__}: {error}"
            if isinstance(error, RecursionError):
                problem = "is nested too deep to read"
        raise PresetError(path, key or "(syntax)", problem, expected) from None


#: Nesting depth beyond which a value cannot be part of a preset.
MAX_DEPTH = 20


def find_unreadable(document: Any) -> tuple[str | None, str, str]:
    """The first value in ``document`` no preset key can hold: an integer beyond a
    float's range, or arrays nested deeper than :data:`MAX_DEPTH`; ``(dotted key, problem,
    expected)``, the key ``None`` when there is none. Walks without recursion."""
    stack: list[tuple[str, Any, int]] = [("", document, 0)]
    while stack:
        key, value, depth = stack.pop()
        if depth > MAX_DEPTH:
            return key, "is nested too deep", f"at most {MAX_DEPTH} levels of arrays and tables"
        if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 1023:
            digits = len(str(abs(value))) if value.bit_length() < 10_000 else "thousands of"
            return key, f"is an integer of {digits} digits", "a number within ±1.8e308"
        if isinstance(value, dict):
            items = [(f"{key}.{k}" if key else str(k), v) for k, v in value.items()]
        elif isinstance(value, list):
            items = [(f"{key}[{i + 1}]", v) for i, v in enumerate(value)]
        else:
            continue
        stack.extend((k, v, depth + 1) for k, v in reversed(items))
    return None, "", "a preset of plain TOML values"


def repair_tables(document: dict[str, Any]) -> list[str]:
    """Make every robot and job table of a preset document a table, as the tabs need (a
    value of the wrong type inside a table is marked on its field instead): a robot or job
    table, an entry of an array of job tables, or a job's own robot table that is no table
    is replaced by an empty table. Returns one line per replacement, in the loader's words
    (``robot: is an integer (expected a table [robot])``)."""

    def kind_of(value: Any) -> str:
        name = {bool: "a boolean", int: "an integer", float: "a number", str: "a text"}
        return name.get(type(value), "an array" if isinstance(value, list) else "a value")

    lines: list[str] = []

    def made_table(value: Any, where: str) -> dict[str, Any]:
        if isinstance(value, dict):
            return value
        lines.append(
            f"{where}: is {kind_of(value)} (expected a table [{where}]); opened as an "
            "empty table, saving writes it"
        )
        return {}

    for name in (*ROBOT_KINDS, *JOB_KINDS):
        if name not in document:
            continue
        value = document[name]
        if name in JOB_KINDS and isinstance(value, list):
            labels = [f"{name}[{k + 1}]" for k in range(len(value))]
            document[name] = [made_table(v, label) for v, label in zip(value, labels, strict=True)]
            labelled = list(zip(labels, document[name], strict=True))
        else:
            document[name] = made_table(value, name)
            labelled = [(name, document[name])]
        for label, table in labelled if name in JOB_KINDS else ():
            for robot in ROBOT_KINDS:
                if robot in table:
                    table[robot] = made_table(table[robot], f"{label}.{robot}")
    return lines
