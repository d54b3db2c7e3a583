"""The server side of ``planar-tui serve``: textual-serve's server, with sessions that end.

textual-serve starts one app process per browser session (``sh -c COMMAND``) and, when the
browser goes, only asks the app to quit through its stdin; an app still starting (its
kernels compiling, 30-60 s on a cold machine) never reads that, and the server's stop
leaves it running. Here (:class:`SessionServer`):

* each app runs in a new session and process group, without a shell;
* a session ends with its browser: ``quit``, then SIGTERM to the app's group after
  :data:`QUIT_GRACE_S`, then SIGKILL after :data:`TERM_GRACE_S` (:func:`end_group`);
* the server's shutdown ends every app still running the same way;
* the app exits by itself when the server is gone (:mod:`planar_tui.cli.served_app`);
* until the app writes its first screen, the browser's terminal shows
  ``planar-tui is starting … N s`` (:meth:`SessionAppService.announce`).

Imported only by ``planar-tui serve`` (textual-serve and aiohttp are the ``serve`` extra).
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import shlex
import signal
import time
from asyncio.subprocess import Process
from typing import ClassVar

from textual_serve.app_service import AppService
from textual_serve.server import Server

#: Seconds an app has to quit when asked, before SIGTERM.
QUIT_GRACE_S = 2.0
#: Seconds after SIGTERM before SIGKILL.
TERM_GRACE_S = 2.0
#: Seconds between the updates of the starting line.
ANNOUNCE_EVERY_S = 1.0


def starting_line(elapsed_s: float) -> bytes:
    """The terminal text shown while the app starts (it redraws the line in place)."""
    return (
        f"\r\x1b[2Kplanar-tui is starting (the first start compiles kernels: up to a "
        f"minute) ... {elapsed_s:.0f} s"
    ).encode()


async def end_group(process: Process, quit_grace_s: float = QUIT_GRACE_S) -> None:
    """Wait ``quit_grace_s`` for ``process`` (a process group leader) to exit, then
    SIGTERM its group, then after :data:`TERM_GRACE_S` SIGKILL it; returns once the
    process is reaped. Whatever the app started in its group goes with it."""
    for signum, grace_s in (
        (None, quit_grace_s),
        (signal.SIGTERM, TERM_GRACE_S),
        (signal.SIGKILL, None),
    ):
        if signum is not None:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(process.pid, signum)
        try:
            await asyncio.wait_for(process.wait(), grace_s)
            break
        except TimeoutError:
            continue
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(process.pid, signal.SIGKILL)  # the group's other members, if any


class SessionAppService(AppService):
    """One browser session's app process: its own process group, ended with the session."""

    #: The app processes of every session still running (ended at the server's shutdown).
    running: ClassVar[set[Process]] = set()

    async def _open_app_process(self, width: int = 80, height: int = 24) -> Process:
        environment = self._build_environment(width=width, height=height)
        self._process = process = await asyncio.create_subprocess_exec(
            *shlex.split(self.command),
            stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.PIPE,
            env=environment,
            start_new_session=True,  # its own process group: killpg ends all of it
        )
        assert process.stdin is not None
        self._stdin = process.stdin
        self.running.add(process)
        self._drawn = asyncio.Event()
        self._announcer = asyncio.create_task(self.announce())
        return process

    async def announce(self) -> None:
        """Say in the browser's terminal that the app is starting, with the seconds
        elapsed, until its first output (or until the browser is gone)."""
        started = time.monotonic()
        with contextlib.suppress(Exception):  # a closed websocket: nothing to tell
            while not self._drawn.is_set():
                await self.remote_write_bytes(starting_line(time.monotonic() - started))
                with contextlib.suppress(asyncio.TimeoutError):
                    await asyncio.wait_for(self._drawn.wait(), ANNOUNCE_EVERY_S)

    async def on_data(self, payload: bytes) -> None:
        self._drawn.set()
        await super().on_data(payload)

    async def on_meta(self, data: bytes) -> None:
        self._drawn.set()
        await super().on_meta(data)

    async def stop(self) -> None:
        """Ask the app to quit, then end its process group (:func:`end_group`)."""
        process = self._process
        if process is None:
            return
        self._drawn.set()
        self._announcer.cancel()
        with contextlib.suppress(Exception):  # a pipe already closed
            await asyncio.wait_for(self.send_meta({"type": "quit"}), QUIT_GRACE_S)
        await end_group(process)
        self.running.discard(process)
        self._process = None
        if self._task is not None:  # the reader: ends at the closed pipes
            await self._download_manager.cancel_app_downloads(app_service_id=self.app_service_id)
            await self._task
            self._task = None


class SessionServer(Server):
    """textual-serve's server whose sessions are :class:`SessionAppService` and whose
    shutdown ends every app still running."""

    async def _make_app(self):
        app = await super()._make_app()
        app.on_shutdown.append(self.end_sessions)
        return app

    async def end_sessions(self, app) -> None:
        """End every session's app (SIGTERM to each group at once, then SIGKILL)."""
        await asyncio.gather(
            *(end_group(process, 0.0) for process in list(SessionAppService.running))
        )
        SessionAppService.running.clear()

    def serve(self, debug: bool = False) -> None:
        import textual_serve.server as textual_server

        # textual-serve's websocket handler builds its AppService by this module-level name.
        textual_server.AppService = SessionAppService  # type: ignore[misc]
        super().serve(debug)
