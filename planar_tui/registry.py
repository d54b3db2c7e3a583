"""The registries of robot kinds and job kinds: one line per kind.

A new job kind is one module in its domain package ending with a
:class:`~planar_tui.jobkind.JobKind` named ``JOB_KIND``, plus one line in :data:`JOB_KINDS`
(its name and its module); the preset loader, the batch service, the run plan, sweeps, the
CLI (its ``run`` and the kind's own command), preset saving, figures, warm-up and the app
(the kind's tab) pick it up. A robot kind likewise (``ROBOT_KIND``, :data:`ROBOT_KINDS`).

A kind's module is imported when the kind is first looked up (``JOB_KINDS["workspace"]``,
or iterating over the values), never before: listing the names (``in``, iterating over
the keys) imports nothing, so ``planar-tui run`` loads only the kinds of the jobs it runs
and their dependencies. Nothing imported by a kind's module loads numpy, numba, SALib or
Textual (runners import them when they run), so ``planar-tui --help`` can list every
kind's command at once.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, MutableMapping
from contextlib import contextmanager
from typing import Generic, Protocol, TypeVar

from planar_tui.jobkind import JobKind, RobotKind, resolve


class _Named(Protocol):
    @property
    def name(self) -> str: ...


KindT = TypeVar("KindT", bound=_Named)


class Registry(MutableMapping[str, KindT], Generic[KindT]):
    """Kinds by name, in declaration order, each read from its module's ``attribute``
    when first looked up (then kept). A kind whose declared name differs from its line's
    is a programming error (:class:`RuntimeError`, caught by the tests). Setting a name
    registers that kind object itself (no module to import), in place of the line's or
    last; deleting one removes it (tests: :func:`registered`, ``monkeypatch.setitem``)."""

    def __init__(self, attribute: str, modules: Mapping[str, str]):
        self._attribute = attribute
        self._modules: dict[str, str | None] = dict(modules)
        self._loaded: dict[str, KindT] = {}

    def __getitem__(self, name: str) -> KindT:
        kind = self._loaded.get(name)
        if kind is not None:
            return kind
        module = self._modules[name]  # KeyError: no such kind
        assert module is not None  # a kind registered as an object is in _loaded
        kind = resolve(f"{module}:{self._attribute}")
        if kind.name != name:
            raise RuntimeError(f"{module}.{self._attribute} is named {kind.name!r}, not {name!r}")
        self._loaded[name] = kind
        return kind

    def __iter__(self) -> Iterator[str]:
        return iter(self._modules)

    def __len__(self) -> int:
        return len(self._modules)

    def __contains__(self, name: object) -> bool:
        return name in self._modules

    def loaded(self) -> tuple[str, ...]:
        """The names of the kinds looked up so far (their modules imported)."""
        return tuple(name for name in self._modules if name in self._loaded)

    def __setitem__(self, name: str, kind: KindT) -> None:
        self._modules.setdefault(name, None)
        self._loaded[name] = kind

    def __delitem__(self, name: str) -> None:
        del self._modules[name]
        self._loaded.pop(name, None)


ROBOT_KINDS: Registry[RobotKind] = Registry(
    "ROBOT_KIND",
    {
        "robot": "planar_tui.dynamics.robot",
        "robot3rrr": "planar_tui.workspace.rrr.robot",
        "robot3rpr": "planar_tui.workspace.rpr.robot",
        "robot3prr": "planar_tui.workspace.prr.robot",
        "robot5r": "planar_tui.workspace.fivebar.robot",
    },
)

JOB_KINDS: Registry[JobKind] = Registry(
    "JOB_KIND",
    {
        "simulate": "planar_tui.dynamics.simulate",
        "torques": "planar_tui.dynamics.torques",
        "sensitivity": "planar_tui.sensitivity.job",
        "workspace": "planar_tui.workspace.rrr.job",
        "workspace5r": "planar_tui.workspace.fivebar.job",
        "motion_uncertainty": "planar_tui.motion.job",
        "workspace3rpr": "planar_tui.workspace.rpr.job",
        "workspace3prr": "planar_tui.workspace.prr.job",
        "path3rrr": "planar_tui.workspace.rrr.path",
        "path5r": "planar_tui.workspace.fivebar.path",
        "path3rpr": "planar_tui.workspace.rpr.path",
        "path3prr": "planar_tui.workspace.prr.path",
        "path3rrr_sensitivity": "planar_tui.pathsensitivity.rrr",
        "path5r_sensitivity": "planar_tui.pathsensitivity.fivebar",
        "path3rpr_sensitivity": "planar_tui.pathsensitivity.rpr",
        "path3prr_sensitivity": "planar_tui.pathsensitivity.prr",
    },
)


@contextmanager
def registered(kind: JobKind) -> Iterator[JobKind]:
    """Register ``kind`` while the block runs, then remove it (for tests: a kind defined in
    a test file alone). Front ends read the registry when they are built (the CLI's
    :func:`planar_tui.cli.build_app`, the app's tabs), so build them inside the block."""
    if kind.name in JOB_KINDS:
        raise ValueError(f"a job kind named {kind.name!r} is registered already")
    if kind.robot_kind not in ROBOT_KINDS:
        raise ValueError(f"{kind.name}: no robot kind {kind.robot_kind!r}")
    JOB_KINDS[kind.name] = kind
    try:
        yield kind
    finally:
        del JOB_KINDS[kind.name]


__all__ = ["JOB_KINDS", "ROBOT_KINDS", "Registry", "registered"]
