"""``planar-tui serve``: the workbench in a browser through textual-serve."""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from contextlib import contextmanager

import pytest

from planar_tui.cli.serve import public_url, server_command
from tests.conftest import PRESETS, REPO
from tests.processes import alive, descendants, wait_until_gone


async def first_screen(url: str, timeout_s: float = 120.0) -> bytes:
    """What the served app sends a browser at 80×24 until its validation line shows (the
    terminal output, as the page's xterm.js would draw it); the bound only catches a hang."""
    import aiohttp

    seen = b""
    async with aiohttp.ClientSession() as session, session.ws_connect(url) as ws:
        await ws.send_json(["resize", {"width": 80, "height": 24}])
        deadline = time.monotonic() + timeout_s
        while b"jobs valid" not in seen and time.monotonic() < deadline:
            message = await ws.receive(timeout=timeout_s)
            if message.type == aiohttp.WSMsgType.BINARY:
                seen += message.data
            elif message.type != aiohttp.WSMsgType.TEXT:
                break
    return seen


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@contextmanager
def served(tmp_path, port: int, *options: str, cold: bool = False):
    """A ``planar-tui serve paper-a-table1 OPTIONS`` process on ``port``: yields (the page
    it answers at 127.0.0.1, the log file); stopped by SIGTERM after, exit 0. ``cold``: an
    empty kernel cache, so that the apps it starts compile for minutes."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    if cold:
        env["NUMBA_CACHE_DIR"] = str(tmp_path / "empty-kernel-cache")
    log = tmp_path / "server.log"
    command = [sys.executable, "-m", "planar_tui", "serve", "paper-a-table1", "--port", str(port)]
    with log.open("wb") as output:
        server = subprocess.Popen(
            [*command, *options], cwd=tmp_path, env=env, stdout=output, stderr=subprocess.STDOUT
        )
    try:
        page, deadline = None, time.monotonic() + 120  # a busy machine: the bound is a hang
        while page is None:
            assert server.poll() is None, log.read_text()
            assert time.monotonic() < deadline, "the server did not answer in time"
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=5) as answer:
                    assert answer.status == 200
                    page = answer.read().decode()
            except (urllib.error.URLError, ConnectionError):
                time.sleep(0.2)
        yield page, log
    finally:
        server.send_signal(signal.SIGTERM)
        try:
            server.wait(timeout=120)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait(timeout=10)
            pytest.fail("the server did not stop on SIGTERM")
    assert server.returncode == 0, log.read_text()


@pytest.mark.slow
def test_serve_answers_with_the_app_page_on_localhost_and_stops(tmp_path):
    port = free_port()
    with served(tmp_path, port) as (page, log):
        assert "<div>planar-tui</div>" in page  # the app's name on the page
        assert f"ws://127.0.0.1:{port}/ws" in page  # the terminal's websocket, same server
        assert "textual.js" in page
        screen = asyncio.run(first_screen(f"http://127.0.0.1:{port}/ws"))
        assert b"ok: paper-a-table1, 3 jobs valid" in screen  # the app itself, validated
    assert "serving on http://127.0.0.1:" in log.read_text()


@pytest.mark.slow
def test_on_every_interface_the_page_names_the_public_url_for_its_websocket(tmp_path):
    """Bound to 0.0.0.0 the page must not send the browser to ws://0.0.0.0 (unreachable):
    it names ``--public-url``, here this machine's loopback address."""
    port = free_port()
    public = f"http://127.0.0.1:{port}"
    with served(tmp_path, port, "--host", "0.0.0.0", "--public-url", public) as (page, log):
        assert "ws://0.0.0.0" not in page
        assert f"ws://127.0.0.1:{port}/ws" in page  # the browser's websocket, reachable
    assert f"browsers open {public}" in log.read_text()


def test_the_public_url_is_checked_and_defaults_to_a_reachable_name():
    import socket

    assert public_url("127.0.0.1", 8000, None) == "http://127.0.0.1:8000"
    assert public_url("0.0.0.0", 8001, None) == f"http://{socket.getfqdn()}:8001"
    assert public_url("::1", 8002, None) == "http://[::1]:8002"
    assert public_url("0.0.0.0", 8000, "https://lab.example/") == "https://lab.example"


def test_a_bad_public_url_is_one_line_exit_2(cli):
    result = cli("serve", "--public-url", "ftp://x")
    assert result.exit_code == 2
    assert result.stderr == (
        "error: command line: --public-url: is 'ftp://x' (expected an http:// or https:// URL)\n"
    )


def test_the_served_command_opens_the_preset_by_absolute_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "mine.toml").write_text("")
    command = server_command("mine.toml", ["r.csv"])
    assert command.split()[1:4] == ["-m", "planar_tui.cli.served_app", "tui"]
    assert str(tmp_path / "mine.toml") in command
    assert f"--open {tmp_path / 'r.csv'}" in command
    assert str(PRESETS / "paper-a-table1.toml") in server_command("paper-a-table1", [])


def test_serve_refuses_a_bad_port_or_preset_in_one_line(cli):
    result = cli("serve", "--port", "70000")
    assert result.exit_code == 2
    assert (
        result.stderr == "error: command line: --port: is 70000 (expected a port from 1 to 65535)\n"
    )
    result = cli("serve", "no-such-preset")
    assert result.exit_code == 2 and result.stderr.startswith(
        "error: no-such-preset: (file): no such file"
    )


async def connect_and_leave(url: str, stay_s: float = 1.0) -> bytes:
    """A browser that opens the app's websocket and closes it after ``stay_s``, while the
    app is still starting: what the server sent meanwhile."""
    import aiohttp

    seen = b""
    async with aiohttp.ClientSession() as session, session.ws_connect(url) as ws:
        await ws.send_json(["resize", {"width": 80, "height": 24}])
        deadline = time.monotonic() + stay_s
        while (left := deadline - time.monotonic()) > 0:
            try:
                message = await ws.receive(timeout=left)
            except TimeoutError:
                break
            if message.type == aiohttp.WSMsgType.BINARY:
                seen += message.data
    return seen


def server_pid(port: int) -> int:
    """The pid of the process listening on 127.0.0.1:``port`` (the test's server)."""
    (pid,) = [p for p in descendants(os.getpid()) if f":{port:04X} " in listening(p)]
    return pid


def listening(pid: int) -> str:
    """The listening sockets' lines of /proc/PID/net/tcp that belong to ``pid``."""
    try:
        inodes = {
            os.readlink(f"/proc/{pid}/fd/{fd}")[8:-1]
            for fd in os.listdir(f"/proc/{pid}/fd")
            if os.readlink(f"/proc/{pid}/fd/{fd}").startswith("socket:")
        }
        with open(f"/proc/{pid}/net/tcp") as table:
            return "".join(
                line for line in table if line.split()[9] in inodes and line.split()[3] == "0A"
            )
    except OSError:
        return ""


@pytest.mark.slow
def test_a_browser_leaving_while_the_app_starts_leaves_no_process_behind(tmp_path):
    """The app's process (and anything it started) ends with its browser session, even
    while the app is still starting; meanwhile the page says that it is starting."""
    port = free_port()
    with served(tmp_path, port, cold=True):
        server = server_pid(port)
        sent = asyncio.run(connect_and_leave(f"http://127.0.0.1:{port}/ws"))
        started = descendants(server)
        assert started, "the session started no app"
        left = wait_until_gone(started, timeout_s=30)  # quit, SIGTERM, SIGKILL: 4 s
        assert not left, f"still running after the browser left: {left}"
    assert b"planar-tui is starting" in sent  # not a black page


@pytest.mark.slow
def test_stopping_the_server_ends_the_apps_of_open_sessions(tmp_path):
    """A server stopped (SIGTERM, exit 0) while a browser is connected and its app is
    still starting leaves no app behind."""
    import threading

    leave = threading.Event()

    async def stay_connected(url: str) -> None:
        import aiohttp

        async with aiohttp.ClientSession() as session, session.ws_connect(url) as ws:
            await ws.send_json(["resize", {"width": 80, "height": 24}])
            while not leave.is_set() and not ws.closed:
                with contextlib.suppress(TimeoutError):
                    await ws.receive(timeout=0.2)

    port = free_port()
    browser = threading.Thread(
        target=asyncio.run, args=(stay_connected(f"http://127.0.0.1:{port}/ws"),), daemon=True
    )
    try:
        with served(tmp_path, port, cold=True):
            server = server_pid(port)
            browser.start()
            deadline = time.monotonic() + 60
            while not (started := descendants(server)) and time.monotonic() < deadline:
                time.sleep(0.1)
            assert started, "the session started no app"
        # the server stopped (SIGTERM, exit 0) with the browser still connected
        left = wait_until_gone(started, timeout_s=30)
        assert not left, f"still running after the server stopped: {left}"
    finally:
        leave.set()
        browser.join(timeout=30)


def test_a_served_app_exits_when_its_server_is_gone(tmp_path):
    """The watchdog of :mod:`planar_tui.cli.served_app`: a server killed by SIGKILL (it can
    end nothing) still leaves no app behind."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    pid_file = tmp_path / "app.pid"
    app = (
        "import os, sys, time; from planar_tui.cli.served_app import watch_parent; "
        f"watch_parent(os.getppid()); open({str(pid_file)!r}, 'w').write(str(os.getpid())); "
        "time.sleep(120)"
    )
    parent = subprocess.Popen(
        [
            sys.executable,
            "-c",
            f"import subprocess, sys, time; subprocess.Popen([sys.executable, '-c', {app!r}]); time.sleep(120)",
        ],
        env=env,
    )
    try:
        deadline = time.monotonic() + 60
        while not pid_file.exists() or not pid_file.read_text():
            assert time.monotonic() < deadline, "the app did not start"
            time.sleep(0.05)
        child = int(pid_file.read_text())
        assert alive({child}) == {child}
        parent.kill()  # SIGKILL: the server ends nothing
        parent.wait(timeout=10)
        assert not wait_until_gone({child}, timeout_s=10)  # 0.5 s checks
    finally:
        parent.kill()
