"""``python -m planar_tui.cli.served_app ARGS``: ``planar-tui ARGS`` run by ``planar-tui
serve`` for one browser session, which exits when the server is gone.

The server ends its sessions' apps itself (:mod:`planar_tui.cli.served`); this covers a
server that could not: one killed by SIGKILL, or crashed. A daemon thread checks every
:data:`WATCH_EVERY_S` that the process's parent is still the server that started it and
otherwise ends the process at once (``os._exit``: whatever the app is doing, a kernel
compiling included). On Linux the kernel also sends SIGKILL when the parent dies
(``PR_SET_PDEATHSIG``).
"""

from __future__ import annotations

import os
import sys
import threading
import time

from planar_tui.cli import main as cli_main

#: Seconds between the checks of the parent process.
WATCH_EVERY_S = 0.5


def _kill_with_parent() -> None:
    """Linux: ask the kernel for SIGKILL when the parent dies; elsewhere nothing."""
    if not sys.platform.startswith("linux"):
        return
    import ctypes

    pr_set_pdeathsig, sigkill = 1, 9
    ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, sigkill, 0, 0, 0)


def watch_parent(parent_pid: int, every_s: float = WATCH_EVERY_S) -> threading.Thread:
    """Start the daemon thread that ends this process (exit status 1) once its parent is
    no longer ``parent_pid`` (the parent died: the process was handed to another)."""

    def watch() -> None:
        while os.getppid() == parent_pid:
            time.sleep(every_s)
        os._exit(1)

    thread = threading.Thread(target=watch, name="planar-tui-parent-watch", daemon=True)
    thread.start()
    return thread


def main() -> None:
    """Watch the parent, then run the CLI with this process's arguments."""
    parent_pid = os.getppid()
    _kill_with_parent()
    if os.getppid() != parent_pid:  # the parent died before the request took effect
        os._exit(1)
    watch_parent(parent_pid)

    cli_main()


if __name__ == "__main__":
    main()
