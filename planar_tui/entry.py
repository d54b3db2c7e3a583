"""The console entry point (``planar-tui``, ``python -m planar_tui``): the first code of
the process, kept free of imports so that Ctrl-C (or SIGTERM) while the CLI's modules are
still loading ends the process with one line instead of a traceback.

Until :func:`planar_tui.cli.main` takes over (it installs the run-time handling: Ctrl-C
raises ``KeyboardInterrupt``, a batch run turns SIGTERM into
:class:`~planar_tui.errors.Terminated`), either signal exits at once: nothing has been
run or written yet.
"""

import gc
import os
import signal
import sys

#: What the process prints and returns when a signal arrives while it starts.
_START_EXITS = {
    signal.SIGINT: (b"interrupted: nothing was run\n", 130),
    signal.SIGTERM: (b"terminated: nothing was run\n", 143),
}


def _exit_while_starting(signum, frame) -> None:
    message, code = _START_EXITS[signum]
    os.write(2, message)
    os._exit(code)


def main() -> None:
    """Install the start-up signal handling, then import and run the CLI."""
    for signum in _START_EXITS:
        signal.signal(signum, _exit_while_starting)
    # Loading the CLI makes many objects and next to no garbage cycles: no cyclic garbage
    # collection until a command runs (:func:`planar_tui.cli.root` turns it back on), about
    # 6 % of `planar-tui --help`.
    gc.disable()
    from planar_tui import helpcache

    path = helpcache.page_path(sys.argv[1:])  # None: not a help request (or no cache)
    page = helpcache.cached_page(path)  # a help page printed before: no Typer, no Rich
    if page is not None:
        helpcache.print_page(page)
        sys.exit(0)
    from planar_tui.cli import main as cli_main

    with helpcache.recording(path):
        cli_main()
