"""Help pages printed from a cache: ``planar-tui --help`` without importing Typer or Rich.

A help page (``planar-tui --help``, ``planar-tui run --help``, ``planar-tui simulate
--help`` ...) is the same text every time for the same program and terminal, but rendering
it imports Typer, Click and Rich and builds every command: about 0.2 s, of which importing
Typer and Rich alone is 0.12 s. The first time a help page is asked for it is rendered as
usual and its exact output saved; later requests print those bytes and exit, in about the
time of a bare interpreter.

The saved page is found by a key (:func:`help_key`) over everything its text can depend
on, so a changed input renders afresh rather than printing a stale page:

* the arguments, the Python interpreter and planar-tui's version;
* every source file of the ``planar_tui`` package and the ``typer``, ``click`` and
  ``rich`` packages' entry files (path, size and modification time: an edit, a new file or
  an upgrade changes it);
* the terminal: whether each of stdin, stdout and stderr is one and its size, and the
  encoding of stdout;
* the environment variables that Rich, Click, Typer or planar-tui read for colour, width
  or terminal detection (:data:`ENVIRONMENT_NAMES`, :data:`ENVIRONMENT_PREFIXES`).

Only a page that ended with exit code 0 and wrote nothing on stderr is saved (a mistyped
command's error is never cached). Pages live in ``help-pages/`` in planar-tui's user cache
folder (:func:`planar_tui.runtime.user_cache_folder`), or in ``$PLANAR_TUI_HELP_CACHE_DIR``
when set (set empty, it turns the cache off: every page rendered), one file per key,
written through a temporary file and a rename; a folder that cannot be written only means
no page is saved. Deleting the folder is always safe.

This module imports nothing beyond the standard library until a page is saved, so that
the cached path stays near the interpreter's own start-up.
"""

from __future__ import annotations

import hashlib
import os
import re
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TextIO

from planar_tui import __version__

#: Moves the saved pages' folder (set empty: no cache).
FOLDER_ENV_VAR = "PLANAR_TUI_HELP_CACHE_DIR"
#: Environment variables read by Rich, Click or Typer when they render help.
ENVIRONMENT_NAMES = frozenset(
    {
        "CLICOLOR",
        "CLICOLOR_FORCE",
        "COLORTERM",
        "COLUMNS",
        "DATABRICKS_RUNTIME_VERSION",
        "FORCE_COLOR",
        "GITHUB_ACTIONS",
        "JUPYTER_COLUMNS",
        "JUPYTER_LINES",
        "LANG",
        "LC_ALL",
        "LC_CTYPE",
        "LINES",
        "NO_COLOR",
        "PYTHONIOENCODING",
        "PY_COLORS",
        "TERM",
        "TERMINAL_WIDTH",
        "TTY_COMPATIBLE",
        "TTY_INTERACTIVE",
    }
)
#: Prefixes of further such variables (Typer's own, and planar-tui's).
ENVIRONMENT_PREFIXES = ("TYPER", "_TYPER", "RICH", "PLANAR_TUI")
#: The help requests that are cached: up to two command words, then ``--help``.
_WORD = re.compile(r"[a-z][a-z0-9-]*\Z")
_RENDERERS = ("typer", "click", "rich")


def is_help_request(arguments: Sequence[str]) -> bool:
    """Whether ``arguments`` (``sys.argv[1:]``) only ask for a help page: at most two
    command words and ``--help`` last (any other option could change what runs)."""
    if not arguments or arguments[-1] != "--help" or len(arguments) > 3:
        return False
    return all(_WORD.match(word) for word in arguments[:-1])


def _package_files() -> Iterator[tuple[str, int, int]]:
    """``(path, size, mtime_ns)`` of every source file of ``planar_tui``."""
    stack = [os.path.dirname(os.path.abspath(__file__))]
    while stack:
        with os.scandir(stack.pop()) as entries:
            for entry in entries:
                if entry.is_dir(follow_symlinks=False):
                    if entry.name != "__pycache__":
                        stack.append(entry.path)
                elif entry.name.endswith((".py", ".toml")):
                    info = entry.stat()
                    yield entry.path, info.st_size, info.st_mtime_ns


def _renderer_files() -> Iterator[tuple[str, int, int]]:
    """``(path, size, mtime_ns)`` of the Typer, Click and Rich packages' entry files
    (found by path, not imported)."""
    import importlib.util

    for name in _RENDERERS:
        spec = importlib.util.find_spec(name)
        origin = None if spec is None else spec.origin
        if origin is None:
            yield name, -1, -1
            continue
        info = os.stat(origin)
        yield origin, info.st_size, info.st_mtime_ns


def _terminal() -> list[object]:
    """Whether each standard stream is a terminal, its size, and stdout's encoding."""
    described: list[object] = []
    for descriptor in (0, 1, 2):
        try:
            described.append((os.isatty(descriptor), tuple(os.get_terminal_size(descriptor))))
        except (OSError, ValueError):
            described.append((False, None))
    stream = sys.stdout
    described.append((getattr(stream, "encoding", None), getattr(stream, "errors", None)))
    return described


def help_key(arguments: Sequence[str]) -> str:
    """The key of the page printed for ``arguments`` here and now (see the module)."""
    environment = sorted(
        (name, value)
        for name, value in os.environ.items()
        if name in ENVIRONMENT_NAMES or name.startswith(ENVIRONMENT_PREFIXES)
    )
    described = repr(
        (
            list(arguments),
            __version__,
            sys.executable,
            sys.version,
            sorted(_package_files()),
            list(_renderer_files()),
            _terminal(),
            environment,
        )
    )
    return hashlib.sha256(described.encode("utf-8", "surrogateescape")).hexdigest()[:32]


def pages_folder() -> Path | None:
    """The folder of the saved pages: ``$PLANAR_TUI_HELP_CACHE_DIR`` if set (``None``, no
    cache, if set empty), else ``help-pages`` in planar-tui's user cache folder (the folder
    of :func:`planar_tui.runtime.user_cache_folder`, not imported here: it loads more)."""
    configured = os.environ.get(FOLDER_ENV_VAR)
    if configured is not None:
        return Path(configured).expanduser() if configured.strip() else None
    import platformdirs

    return Path(platformdirs.user_cache_dir("planar-tui", appauthor=False)) / "help-pages"


def page_path(arguments: Sequence[str]) -> Path | None:
    """Where the page for ``arguments`` is saved (``FOLDER/KEY.txt``), or ``None`` when
    they are not a help request or the cache is off."""
    folder = pages_folder() if is_help_request(arguments) else None
    return None if folder is None else folder / f"{help_key(arguments)}.txt"


def cached_page(path: Path | None) -> bytes | None:
    """The page saved at ``path`` (:func:`page_path`), or ``None`` (no path, nothing saved
    there, or the file unreadable)."""
    if path is None:
        return None
    try:
        return path.read_bytes()
    except OSError:
        return None


def print_page(page: bytes) -> None:
    """Write a saved page to stdout as it was first written."""
    sys.stdout.flush()
    sys.stdout.buffer.write(page)
    sys.stdout.flush()


class _Tee:
    """A text stream that copies what is written to it and passes everything to the
    stream it wraps (so a renderer sees the same terminal, size and encoding)."""

    def __init__(self, stream: TextIO):
        self._stream = stream
        self.written: list[str] = []

    def write(self, text: str) -> int:
        written = self._stream.write(text)  # first: Click probes with b"" for a TypeError
        self.written.append(text)
        return written

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


@contextmanager
def recording(path: Path | None) -> Iterator[None]:
    """Run the block (the CLI) and, given the page's ``path`` (:func:`page_path`; ``None``:
    not a help request or no cache), if the block exits with code 0 having written nothing
    on stderr, save what it wrote on stdout there.

    Only a UTF-8 stdout is recorded: Click writes through a stream of its own over the
    binary buffer when the text stream's encoding is ASCII (a misconfigured locale), which
    this copy would not see."""
    if path is None or not _utf8(getattr(sys.stdout, "encoding", None)):
        yield
        return
    out, err = _Tee(sys.stdout), _Tee(sys.stderr)
    sys.stdout, sys.stderr = out, err
    try:
        yield
    except SystemExit as exit_:
        if exit_.code in (None, 0) and not "".join(err.written) and out.written:
            text = "".join(out.written).replace("\n", os.linesep)  # as the text layer wrote it
            _save(path, text.encode(out.encoding or "utf-8", out.errors or "strict"))
        raise
    finally:
        sys.stdout, sys.stderr = out._stream, err._stream


def _utf8(encoding: str | None) -> bool:
    """Whether ``encoding`` names UTF-8."""
    import codecs

    try:
        return encoding is not None and codecs.lookup(encoding).name == "utf-8"
    except LookupError:
        return False


#: The most pages kept: saving one more removes the least recently saved beyond it.
MAX_PAGES = 64
_PAGE_NAME = re.compile(r"[0-9a-f]{32}\.txt\Z")


def _save(path: Path, page: bytes) -> None:
    """Write the page at ``path`` (temporary file, then rename), then keep the
    :data:`MAX_PAGES` newest pages (only files named as pages are; terminal sizes vary, so
    the folder would otherwise grow without end); errors are ignored."""
    import tempfile

    folder = path.parent
    try:
        folder.mkdir(parents=True, exist_ok=True)
        descriptor, temporary = tempfile.mkstemp(dir=folder, prefix=f".{path.stem}.", suffix=".tmp")
        try:
            with os.fdopen(descriptor, "wb") as file:
                file.write(page)
            os.replace(temporary, path)
        except BaseException:
            os.unlink(temporary)
            raise
        with os.scandir(folder) as entries:
            pages = [entry for entry in entries if _PAGE_NAME.match(entry.name)]
        if len(pages) > MAX_PAGES:
            pages.sort(key=lambda entry: entry.stat().st_mtime_ns, reverse=True)
            for entry in pages[MAX_PAGES:]:
                os.unlink(entry.path)
    except OSError:
        pass
