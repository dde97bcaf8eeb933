"""`racetrace serve`: registered, arguments, and exit code 2 when off-screen rendering fails."""

from __future__ import annotations

import app.main as app_main
from racetrace import cli
from viz.offscreen import INSTALL_COMMAND, OffscreenCheck


def test_serve_is_registered_with_its_options():
    args = cli.build_parser().parse_args(
        ["serve", "--port", "9001", "--host", "0.0.0.0", "--runs-dir", "/tmp/x", "--open"]
    )
    assert (args.port, args.host, args.runs_dir, args.open) == (9001, "0.0.0.0", "/tmp/x", True)
    defaults = cli.build_parser().parse_args(["serve"])
    assert (defaults.host, defaults.port, defaults.open) == ("127.0.0.1", 8080, False)


def test_no_offscreen_rendering_exits_2_with_the_install_command(monkeypatch, capsys):
    message = app_main.check_offscreen_rendering.__module__  # keep the real function importable
    assert message == "viz.offscreen"
    failed = OffscreenCheck(False, f"racetrace serve: ... \n    {INSTALL_COMMAND}")
    monkeypatch.setattr(app_main, "check_offscreen_rendering", lambda: failed)
    assert cli.main(["serve", "--port", "9002"]) == 2
    assert INSTALL_COMMAND in capsys.readouterr().err


def test_port_in_use_is_named_without_traceback(capsys):
    import socket

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        assert cli.main(["serve", "--port", str(port)]) == 2
    err = capsys.readouterr().err
    assert f"127.0.0.1:{port}" in err and "--port" in err and "Traceback" not in err
    assert cli.main(["serve", "--port", "70000"]) == 2
    assert "between 1 and 65535" in capsys.readouterr().err


def test_closed_connection_errors_are_kept_out_of_the_log():
    import logging
    import sys

    from app.serve.quiet_log import not_a_closed_connection

    def record_of(error):
        try:
            raise error
        except BaseException:
            return logging.LogRecord(
                "aiohttp.server", 40, "", 0, "Error handling request", (), sys.exc_info()
            )

    def send_after_close():
        try:
            raise ConnectionResetError("Cannot write to closing transport")
        except ConnectionResetError:
            raise RuntimeError("while sending an error reply")  # noqa: B904 - chained as aiohttp

    assert not not_a_closed_connection(record_of(ConnectionResetError("closing transport")))
    try:
        send_after_close()
    except RuntimeError as chained:
        assert not not_a_closed_connection(record_of(chained))
    assert not_a_closed_connection(record_of(ValueError("a real problem")))
    plain = logging.LogRecord("aiohttp.server", 20, "", 0, "no exception", (), None)
    assert not_a_closed_connection(plain)


def test_wslink_lines_about_a_closed_browser_are_dropped():
    import logging

    from app.serve.quiet_log import not_a_closed_connection_text

    def record(text):
        return logging.LogRecord("wslink.protocol", 40, "", 0, text, (), None)

    assert not not_a_closed_connection_text(record("Exception raised"))
    assert not not_a_closed_connection_text(
        record("ClientConnectionResetError('Cannot write to closing transport')")
    )
    assert not_a_closed_connection_text(record("KeyError('frame')"))
