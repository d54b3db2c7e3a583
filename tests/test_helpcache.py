"""Help pages printed from the cache (:mod:`planar_tui.helpcache`, issue 21's ``--help``
goal): the same bytes as the rendered page, in a pipe and in a colour terminal, without
importing Typer or Rich; a new page for anything that changes the text; nothing saved
for an error; a cache that cannot be written changes nothing."""

from __future__ import annotations

import fcntl
import json
import os
import pty
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

import pytest

from planar_tui import helpcache

REPO = Path(__file__).resolve().parent.parent

#: The console script's entry point, then which renderers the process imported (stderr).
ENTRY = """
import json, sys
from planar_tui.entry import main

sys.argv[0] = "planar-tui"
try:
    main()
finally:
    sys.stderr.write(json.dumps([m for m in ("typer", "click", "rich") if m in sys.modules]))
"""

REQUESTS = [["--help"], ["run", "--help"], ["simulate", "--help"], ["sweep", "--help"]]


def run_entry(arguments: list[str], pages: Path | str, **extra: str):
    """The entry point in a fresh process (stdout a pipe): (exit code, stdout bytes,
    renderers imported)."""
    env = dict(os.environ, PYTHONPATH=str(REPO), PLANAR_TUI_HELP_CACHE_DIR=str(pages), **extra)
    done = subprocess.run(
        [sys.executable, "-c", ENTRY, *arguments], capture_output=True, env=env, timeout=120
    )
    last = done.stderr.decode().strip().splitlines()[-1]
    return done.returncode, done.stdout, json.loads(last[last.index("[") :])


@pytest.mark.parametrize("arguments", REQUESTS, ids=" ".join)
def test_a_cached_page_is_the_rendered_page_byte_for_byte_without_typer_or_rich(
    tmp_path, arguments
):
    pages = tmp_path / "pages"
    code, rendered, imported = run_entry(arguments, pages)
    assert code == 0 and b"Usage: planar-tui" in rendered and "typer" in imported
    assert len(list(pages.glob("*.txt"))) == 1  # the page was saved
    code, cached, imported = run_entry(arguments, pages)
    assert code == 0 and imported == []  # printed from the cache
    assert cached == rendered
    code, uncached, imported = run_entry(arguments, "")  # the cache turned off
    assert code == 0 and "typer" in imported and uncached == rendered


def run_in_terminal(arguments: list[str], pages: Path, columns: int) -> bytes:
    """The console script's output in a pseudo-terminal ``columns`` wide (colour on)."""
    leader, follower = pty.openpty()
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 40, columns, 0, 0))
    env = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "COLUMNS", "LINES")}
    env.update(PYTHONPATH=str(REPO), PLANAR_TUI_HELP_CACHE_DIR=str(pages), TERM="xterm-256color")
    process = subprocess.Popen(
        [sys.executable, "-c", ENTRY, *arguments],
        stdin=follower,
        stdout=follower,
        stderr=subprocess.DEVNULL,
        env=env,
        close_fds=True,
    )
    os.close(follower)
    output = bytearray()
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        try:
            chunk = os.read(leader, 65536)
        except OSError:  # the terminal closed: the process ended
            break
        if not chunk:
            break
        output += chunk
    os.close(leader)
    assert process.wait(timeout=60) == 0
    return bytes(output)


def test_a_cached_page_in_a_colour_terminal_is_the_rendered_page(tmp_path):
    pages = tmp_path / "pages"
    rendered = run_in_terminal(["--help"], pages, columns=100)
    assert b"\x1b[" in rendered  # colour
    assert max(len(line) for line in rendered.decode().splitlines()) > 80  # the full width
    cached = run_in_terminal(["--help"], pages, columns=100)
    assert cached == rendered
    assert len(list(pages.glob("*.txt"))) == 1
    # another width is another page
    narrow = run_in_terminal(["--help"], pages, columns=60)
    assert narrow != rendered and len(list(pages.glob("*.txt"))) == 2


def test_an_error_is_never_saved_and_an_unwritable_cache_changes_nothing(tmp_path):
    pages = tmp_path / "pages"
    code, _, _ = run_entry(["no-such-command", "--help"], pages)
    assert code == 2 and not pages.exists()
    not_a_folder = tmp_path / "file"
    not_a_folder.write_text("a file where the folder should be")
    code, out, imported = run_entry(["--help"], not_a_folder)
    assert code == 0 and b"Usage: planar-tui" in out and "typer" in imported
    assert not_a_folder.read_text() == "a file where the folder should be"


def test_an_ascii_stdout_is_never_recorded(tmp_path):
    """With an ASCII stdout Click writes through its own stream over the binary buffer,
    past the recording: no page is saved, the help is still printed."""
    pages = tmp_path / "pages"
    code, out, imported = run_entry(["--help"], pages, PYTHONIOENCODING="ascii")
    assert code == 0 and b"Usage: planar-tui" in out and "typer" in imported
    assert not pages.exists()


def test_the_folder_keeps_the_newest_pages_and_nothing_else_is_touched(tmp_path):
    pages = tmp_path / "pages"
    pages.mkdir()
    for n in range(helpcache.MAX_PAGES):
        old = pages / f"{n:032x}.txt"
        old.write_text("an old page")
        os.utime(old, ns=(10**9 * n, 10**9 * n))
    (pages / "notes.txt").write_text("not a page")
    code, _, _ = run_entry(["--help"], pages)
    assert code == 0
    saved = sorted(path.name for path in pages.glob("*.txt"))
    assert len(saved) == helpcache.MAX_PAGES + 1  # the pages and the notes
    assert f"{0:032x}.txt" not in saved  # the least recently saved went
    assert f"{1:032x}.txt" in saved and "notes.txt" in saved


def test_only_help_requests_are_cached():
    assert helpcache.is_help_request(["--help"])
    assert helpcache.is_help_request(["run", "--help"])
    assert helpcache.is_help_request(["sweep", "x-y", "--help"])
    for arguments in (
        [],
        ["run"],
        ["--help", "run"],
        ["run", "a.toml", "--help"],
        ["--version", "--help"],
        ["a", "b", "c", "--help"],
        ["-h"],
    ):
        assert not helpcache.is_help_request(arguments), arguments


def test_the_key_changes_with_everything_the_page_depends_on(tmp_path, monkeypatch):
    for name in ("COLUMNS", "NO_COLOR", "FORCE_COLOR", "TERM", "TYPER_USE_RICH"):
        monkeypatch.delenv(name, raising=False)
    key = helpcache.help_key(["--help"])
    assert helpcache.help_key(["--help"]) == key  # the same inputs, the same key
    assert helpcache.help_key(["run", "--help"]) != key
    for name, value in [
        ("COLUMNS", "100"),
        ("NO_COLOR", "1"),
        ("FORCE_COLOR", "1"),
        ("TERM", "dumb"),
        ("TYPER_USE_RICH", "0"),
    ]:
        with monkeypatch.context() as environment:
            environment.setenv(name, value)
            assert helpcache.help_key(["--help"]) != key, name
    assert helpcache.help_key(["--help"]) == key
    # the package's files: a stand-in package folder, one file edited, one added
    package = tmp_path / "planar_tui"
    package.mkdir()
    (package / "helpcache.py").write_text("")
    (package / "cli.py").write_text("HELP = 'one'\n")
    monkeypatch.setattr(helpcache, "__file__", str(package / "helpcache.py"))
    before = helpcache.help_key(["--help"])
    assert before != key
    os.utime(package / "cli.py", ns=(0, 10**18))
    edited = helpcache.help_key(["--help"])
    assert edited != before
    (package / "kinds").mkdir()
    (package / "kinds" / "new.py").write_text("")
    assert helpcache.help_key(["--help"]) not in (before, edited)
