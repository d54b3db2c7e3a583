"""A real terminal for tests, in pure Python: a pseudo-terminal plus the ``pyte`` emulator.

:class:`PtyTerminal` starts a program on the slave side of a pty whose window size is set
with ``TIOCSWINSZ`` (so the program sizes itself from the terminal, as it would in
xterm), keeps reading the master side in a background thread (a program writing to a
pty nobody reads blocks once the kernel's buffer is full), feeds every byte to a
``pyte`` screen and also keeps the raw bytes, which show exactly which escape codes the
program emitted. Keys are sent as the bytes a terminal would send (``"\\x1b[C"`` for →).

``pyte`` ignores sequences it does not know (synchronized output ``?2026``, mouse,
focus and bracketed-paste modes, mode queries ``$p``, OSC 22); it has a single screen
buffer, so an alternate-screen switch (``?1049``) draws on the one screen, which is what
a test wants. Queries the program sends (device attributes, mode reports) are not
answered, so Textual, which asks whether the terminal supports synchronized output,
draws without it. One sequence ``pyte`` 0.8 misreads: the kitty keyboard protocol's
"pop flags" ``ESC [ < u`` (Textual sends it when it stops), where it takes ``<`` for the
final byte and prints the ``u``; those sequences are dropped before ``pyte`` sees them
(the raw output keeps them).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import re
import select
import signal
import struct
import subprocess
import termios
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import pyte

POLL_S = 0.1  # how often the waits look at the screen again, and the reader at its stop flag

# Kitty keyboard protocol "pop flags" (``CSI < n u``), which pyte would print as "u"
KITTY_POP = re.compile(rb"\x1b\[<[0-9]*u")
# The end of a chunk that may be the start of such a sequence, held back until the next one
KITTY_POP_PREFIX = re.compile(rb"\x1b(?:\[(?:<[0-9]*)?)?\Z")


class PtyTerminal:
    """One program in a ``columns`` × ``rows`` pseudo-terminal, rendered by ``pyte``.

    Use as a context manager (or call :meth:`close` in a ``finally``), so that a failing
    test leaves neither a process nor a file descriptor behind.
    """

    def __init__(self) -> None:
        self._process: subprocess.Popen[bytes] | None = None
        self._master: int | None = None
        self._reader: threading.Thread | None = None
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self._raw = bytearray()
        self._held = b""  # an incomplete escape sequence not yet given to pyte
        self._reader_error: BaseException | None = None
        self._screen: pyte.Screen | None = None
        self._stream: pyte.ByteStream | None = None

    def __enter__(self) -> PtyTerminal:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def start(
        self,
        argv: Sequence[str],
        env: Mapping[str, str],
        cwd: str | Path,
        columns: int = 80,
        rows: int = 24,
    ) -> None:
        """Run ``argv`` (with exactly the environment ``env``, in ``cwd``) on a new pty.

        The program gets the pty's slave side as stdin, stdout and stderr, runs in a new
        session (so :meth:`close` can kill its whole process group) and finds its window
        size with ``TIOCGWINSZ``; ``env`` should not set ``COLUMNS``/``LINES``, which
        would take precedence over the pty's size.
        """
        if self._process is not None:
            raise RuntimeError("this terminal already runs a program")
        self._screen = pyte.Screen(columns, rows)
        self._stream = pyte.ByteStream(self._screen)
        master, slave = os.openpty()
        self._master = master
        try:
            fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", rows, columns, 0, 0))
            self._process = subprocess.Popen(
                list(argv),
                stdin=slave,
                stdout=slave,
                stderr=slave,
                cwd=cwd,
                env=dict(env),
                start_new_session=True,
            )
        finally:
            os.close(slave)  # the child has its copies; reads see EIO once they are closed
        self._reader = threading.Thread(target=self._read_loop, name="pty-reader", daemon=True)
        self._reader.start()

    def _read_loop(self) -> None:
        """Copy everything the program writes into the raw buffer and the ``pyte`` screen."""
        assert self._master is not None and self._stream is not None
        try:
            while not self._stop.is_set():
                ready, _, _ = select.select([self._master], [], [], POLL_S)
                if not ready:
                    continue
                try:
                    data = os.read(self._master, 65536)
                except OSError:  # EIO: the program (and all it started) closed the pty
                    return
                if not data:
                    return
                with self._lock:
                    self._raw += data
                    self._feed_screen(data)
        except BaseException as error:  # reported by the waits, with the screen
            self._reader_error = error

    def _feed_screen(self, data: bytes) -> None:
        """Give ``data`` to ``pyte``, without the sequences it misreads (see the module)."""
        assert self._stream is not None
        data = KITTY_POP.sub(b"", self._held + data)
        held = KITTY_POP_PREFIX.search(data)
        cut = held.start() if held else len(data)
        self._held = data[cut:]
        self._stream.feed(data[:cut])

    def send(self, text: str | bytes) -> None:
        """Type ``text``: write it, UTF-8 encoded, to the program's terminal input."""
        if self._master is None:
            raise RuntimeError("no program started")
        data = text.encode() if isinstance(text, str) else text
        while data:
            written = os.write(self._master, data)
            data = data[written:]

    def screen_text(self) -> str:
        """The screen as ``pyte`` renders it now: one line per row, trailing blanks cut."""
        if self._screen is None:
            return ""
        with self._lock:
            lines = list(self._screen.display)
        return "\n".join(line.rstrip() for line in lines)

    def raw_output(self) -> bytes:
        """Every byte the program has written so far, escape codes included."""
        with self._lock:
            return bytes(self._raw)

    def _check_reader(self) -> None:
        if self._reader_error is not None:
            raise AssertionError(
                f"reading the terminal failed: {self._reader_error!r}; screen was:\n"
                f"{self.screen_text()}"
            ) from self._reader_error

    def wait_for(self, predicate: Callable[[str], bool], timeout_s: float, what: str) -> str:
        """Poll the screen until ``predicate(screen_text)`` holds and return that text.

        Raises ``AssertionError`` naming ``what`` and showing the screen if ``timeout_s``
        passes first or the program exits before the screen matches.
        """
        if self._process is None:
            raise RuntimeError("no program started")
        deadline = time.monotonic() + timeout_s
        while True:
            self._check_reader()
            exited = self._process.poll()
            if exited is not None and self._reader is not None:
                self._reader.join(1.0)  # take in what it wrote last before judging
            screen = self.screen_text()
            if predicate(screen):
                return screen
            if exited is not None:
                raise AssertionError(
                    f"the program exited with status {exited} while waiting for {what}; "
                    f"screen was:\n{screen}"
                )
            if time.monotonic() >= deadline:
                raise AssertionError(
                    f"timed out after {timeout_s} s waiting for {what}; screen was:\n{screen}"
                )
            time.sleep(POLL_S)

    def wait_exit(self, timeout_s: float) -> int:
        """Wait up to ``timeout_s`` for the program to end and return its exit status
        (negative: killed by that signal); ``AssertionError`` with the screen if it does not."""
        if self._process is None:
            raise RuntimeError("no program started")
        try:
            return self._process.wait(timeout_s)
        except subprocess.TimeoutExpired:
            raise AssertionError(
                f"the program did not exit within {timeout_s} s; screen was:\n{self.screen_text()}"
            ) from None

    def close(self) -> None:
        """Kill the program's process group if it still runs, reap it, stop the reader and
        close the pty. Safe to call more than once."""
        process, self._process = self._process, None
        if process is not None:
            if process.poll() is None:
                with contextlib.suppress(ProcessLookupError):  # it ended meanwhile
                    os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        self._stop.set()
        if self._reader is not None:
            self._reader.join()
            self._reader = None
        if self._master is not None:
            os.close(self._master)
            self._master = None
