"""``planar-tui serve``: the same Textual workbench in a web browser, through
``textual-serve`` (the ``serve`` extra: ``pip install "planar-tui[serve]"``).

Each browser tab that opens the page starts its own ``planar-tui tui`` process on the
preset; the server binds to ``127.0.0.1`` by default, so only this machine reaches it. From
a laptop, tunnel the port over SSH (``ssh -L 8000:localhost:8000 HOST``) and open
``http://localhost:8000``. Bound to every interface (``--host 0.0.0.0``), the page must
name an address the browser can reach for its websocket: ``--public-url`` (default
``http://HOSTNAME:PORT`` with this machine's name, :func:`public_url`).

Nothing outlives the server or its browser session (:mod:`planar_tui.cli.served`): each
app runs in a process group of its own, ended (``quit``, then SIGTERM, then SIGKILL) when
its browser disconnects, even while the app is still starting, and when the server stops;
the app itself exits when the server is gone. Until the app draws, the page says that it
is starting and for how long.
"""

from __future__ import annotations

import shlex
import sys
from typing import Annotated

import typer

from planar_tui.cli.output import fail, reported_errors, stderr
from planar_tui.errors import ExitCode, PresetError
from planar_tui.resources import resolve_preset


def server_command(preset: str | None, opened: list[str]) -> str:
    """The command the server runs per browser session: this Python, ``-m
    planar_tui.cli.served_app tui`` (the CLI with a watchdog), the preset (an absolute path, so the server's folder does not
    matter) and the ``--open`` results."""
    from pathlib import Path

    words = [sys.executable, "-m", "planar_tui.cli.served_app", "tui"]
    if preset is not None:
        words.append(str(resolve_preset(preset).absolute()))
    for path in opened:
        words += ["--open", str(Path(path).absolute())]
    return shlex.join(words)


#: Addresses that bind every interface: no browser can connect to them.
WILDCARD_HOSTS = ("0.0.0.0", "::", "")


def public_url(host: str, port: int, given: str | None) -> str:
    """The URL the served page gives the browser for its websocket: ``given`` (checked:
    ``http://`` or ``https://`` and a host), else ``http://HOST:PORT``, with this machine's
    name (:func:`socket.getfqdn`) in place of a wildcard ``HOST``."""
    import socket
    from urllib.parse import urlsplit

    if given is not None:
        parts = urlsplit(given)
        if parts.scheme not in ("http", "https") or not parts.hostname:
            raise PresetError(
                "command line", "--public-url", f"is {given!r}", "an http:// or https:// URL"
            )
        return given.rstrip("/")
    shown = socket.getfqdn() if host in WILDCARD_HOSTS else host
    shown = f"[{shown}]" if ":" in shown else shown
    return f"http://{shown}:{port}"


#: The preset argument of ``tui`` and ``serve``.
AppPresetArg = Annotated[
    str | None,
    typer.Argument(help="Preset file or bundled preset name (default: paper-a-table1)."),
]
#: The ``--open`` option of ``tui`` and ``serve``.
OpenOption = Annotated[
    list[str] | None,
    typer.Option(
        "--open",
        metavar="RESULT.csv",
        help="A result CSV to open into the run history (repeatable); its sidecar "
        "RESULT.csv.json gives its settings.",
    ),
]


def serve(
    preset: AppPresetArg = None,
    host: Annotated[
        str,
        typer.Option("--host", help="Address to bind (default 127.0.0.1: this machine only)."),
    ] = "127.0.0.1",
    port: Annotated[int, typer.Option("--port", help="TCP port (1-65535).")] = 8000,
    open_results: OpenOption = None,
    public: Annotated[
        str | None,
        typer.Option(
            "--public-url",
            metavar="URL",
            help="The address browsers reach the server at (default http://HOST:PORT, this "
            "machine's name for --host 0.0.0.0).",
        ),
    ] = None,
) -> None:
    """Serve the workbench in a web browser (textual-serve), on http://HOST:PORT; from a
    laptop: ssh -L 8000:localhost:8000 HOST, then open http://localhost:8000."""
    with reported_errors():
        if not 1 <= port <= 65535:
            raise PresetError("command line", "--port", f"is {port}", "a port from 1 to 65535")
        url = public_url(host, port, public)
        command = server_command(preset, list(open_results or ()))
    try:
        from planar_tui.cli.served import SessionServer
    except ImportError:
        raise fail(
            'error: planar-tui serve needs textual-serve: pip install "planar-tui[serve]"',
            ExitCode.BAD_INPUT,
        ) from None
    server = SessionServer(command, host=host, port=port, title="planar-tui", public_url=url)
    reached = "" if url == f"http://{host}:{port}" else f", browsers open {url}"
    stderr.print(
        f"planar-tui: serving on http://{host}:{port}{reached} (Ctrl-C stops)",
        markup=False,
        soft_wrap=True,  # a URL is never cut by a line break
    )
    try:
        server.serve()
    except OSError as error:
        raise fail(f"error: cannot serve on {host}:{port}: {error.strerror or error}") from None
    raise typer.Exit(0)
