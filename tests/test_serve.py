"""``planar-tui serve``: the workbench in a browser through textual-serve."""

from __future__ import annotations

import asyncio
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
def served(tmp_path, port: int, *options: str):
    """A ``planar-tui serve paper-a-table1 OPTIONS`` process on ``port``: yields (the page
    it answers at 127.0.0.1, the log file); stopped by SIGTERM after, exit 0."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
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
    assert command.split()[1:4] == ["-m", "planar_tui", "tui"]
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
