"""racetrace study: invalid input is named (exit 2) before any cluster starts; study show."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from racetrace import cli
from tests.helpers.studies import two_run_study_folder

STUDY_RESULTS = Path(__file__).resolve().parents[2] / "assets" / "studies" / "results"


def test_invalid_study_names_the_key_and_exits_2(tmp_path, capsys):
    study = tmp_path / "bad.toml"
    study.write_text(
        'base = "spindle-axial-preload"\ncombine = "zip"\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n"operating.axial_lod_N" = [1.0]\n'
    )
    assert cli.main(["study", str(study), "--output", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "vary.operating.axial_lod_N" in err and "operating.axial_load_N" in err
    assert not (tmp_path / "out").exists()


def test_output_is_required_and_workers_positive(tmp_path, capsys):
    assert cli.main(["study", "seed-spindle"]) == 2
    assert "--output DIR is required" in capsys.readouterr().err
    assert cli.main(["study", "seed-spindle", "-o", str(tmp_path / "o"), "--workers", "0"]) == 2
    assert "--workers 0" in capsys.readouterr().err


def test_show_needs_a_study_folder(tmp_path, capsys):
    assert cli.main(["study", "show"]) == 2
    assert cli.main(["study", "show", str(tmp_path)]) == 2
    assert "not a study folder" in capsys.readouterr().err


def test_show_prints_the_points_of_a_folder(tmp_path, capsys):
    two_run_study_folder(
        tmp_path / "s",
        'title = "shown"\nbase = "spindle-axial-preload"\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n',
        "quasistatic",
        "no solution",
    )
    assert cli.main(["study", "show", str(tmp_path / "s"), "--wide"]) == 0
    out = capsys.readouterr().out
    lines = out.splitlines()
    p1 = next(line for line in lines if line.startswith("p0001"))
    assert "done" in p1 and "1.2500" in p1 and "2.5000" in p1
    assert "p0002 quasistatic: no solution" in out
    manifest = json.loads((tmp_path / "s" / "study.json").read_text())
    assert [p["name"] for p in manifest["points"]] == ["p0001", "p0002"]


@pytest.mark.parametrize("name", ["seed-spindle", "218-radial-load"])
def test_show_reads_a_shipped_study_file_and_fits_120_columns(capsys, name):
    """A shipped ``*.study.nc`` is read as ``racetrace report`` reads it; the default table fits a
    120-column terminal, shows band width and says how to get every column."""
    import solver

    path = STUDY_RESULTS / f"{name}.study.nc"
    assert cli.main(["study", "show", str(path)]) == 0
    out = capsys.readouterr().out
    assert max(len(line) for line in out.splitlines()) <= 120
    header = next(line for line in out.splitlines() if line.startswith("point"))
    assert "width_i deg" in header and "width_o deg" in header
    assert "racetrace study show DIR --wide" in out
    ds = solver.load_dataset(path)
    width = float(ds["band_width"].sel(model="dynamic", race="outer").values[-1])
    last = [line for line in out.splitlines() if line.startswith(str(ds["point"].values[-1]))]
    assert any(f"{width:.4f}" in line for line in last), last
    assert cli.main(["study", "show", str(path), "--wide"]) == 0
    wide = capsys.readouterr().out
    assert "exc_i deg" in wide and "settle ms" in wide and "width_o deg" in wide


def test_show_of_a_run_result_says_it_is_not_a_study(capsys):
    run = STUDY_RESULTS.parents[1] / "lessons" / "results" / "06-overload--heavy.nc"
    assert cli.main(["study", "show", str(run)]) == 2
    assert "a run result, not a study" in capsys.readouterr().err


# ---- robustness: exit 2 with a message, never a traceback or a hang --------------------------
@pytest.mark.parametrize(
    "address", ["http://127.0.0.1:8786", "127.0.0.1", "tcp://127.0.0.1:", "tcp://:8786", "a b:1"]
)
def test_a_malformed_scheduler_address_names_the_form(tmp_path, capsys, address):
    code = cli.main(["study", "seed-spindle", "-o", str(tmp_path / "o"), "--scheduler", address])
    assert code == 2
    assert "tcp://HOST:PORT" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


class _Server:
    """A TCP server on 127.0.0.1 that accepts connections and then says nothing (``answer`` None)
    or answers every connection with ``answer`` (an HTTP error page, as a web server would)."""

    def __init__(self, answer: bytes | None = None):
        import socket
        import threading

        self.answer = answer
        self.sock = socket.create_server(("127.0.0.1", 0))
        self.port = self.sock.getsockname()[1]
        self.conns = []
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.conns.append(conn)
            if self.answer is not None:
                try:
                    conn.recv(65536)
                    conn.sendall(self.answer)
                except OSError:
                    pass

    def close(self):
        self.sock.close()
        for conn in self.conns:
            conn.close()


HTTP_ANSWER = (
    b"HTTP/1.1 400 Bad Request\r\nContent-Type: text/html\r\nContent-Length: 22\r\n\r\n"
    b"<html>bad request</html>"
)


@pytest.mark.parametrize("answer", [None, HTTP_ANSWER], ids=["silent", "http"])
def test_a_server_that_is_not_a_dask_scheduler_is_named_within_the_deadline(
    tmp_path, capsys, monkeypatch, answer
):
    import time

    from solver.study import runner

    pytest.importorskip("distributed")
    monkeypatch.setattr(runner, "CONNECT_TIMEOUT_S", 3.0)
    server = _Server(answer)
    address = f"tcp://127.0.0.1:{server.port}"
    try:
        start = time.monotonic()
        code = cli.main(
            ["study", "seed-spindle", "-o", str(tmp_path / "o"), "--scheduler", address]
        )
        spent = time.monotonic() - start
    finally:
        server.close()
    assert code == 2
    err = capsys.readouterr().err
    assert f"no Dask scheduler answered at {address}" in err and "Traceback" not in err
    assert spent < 30
    assert not (tmp_path / "o").exists()


def test_a_web_server_is_not_a_dask_scheduler(tmp_path, capsys, monkeypatch):
    """A real HTTP server (the standard library's) on 127.0.0.1."""
    import http.server
    import threading

    from solver.study import runner

    pytest.importorskip("distributed")
    monkeypatch.setattr(runner, "CONNECT_TIMEOUT_S", 3.0)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    address = f"tcp://127.0.0.1:{server.server_address[1]}"
    try:
        code = cli.main(
            ["study", "seed-spindle", "-o", str(tmp_path / "o"), "--scheduler", address]
        )
    finally:
        server.shutdown()
        server.server_close()
    assert code == 2
    assert f"no Dask scheduler answered at {address}" in capsys.readouterr().err


@pytest.mark.parametrize(
    "nesting",
    [
        '[vary]\n"operating.radial_load_N" = ' + "[" * 5000 + "1.0" + "]" * 5000,
        "vary." + ".".join(["a"] * 5000) + " = [1.0]",
        "[vary]\nx = " + "{a = " * 3000 + "1" + "}" * 3000,
    ],
    ids=["vary lists", "dotted keys", "inline tables"],
)
def test_a_study_file_nested_thousands_deep_is_invalid_input(tmp_path, capsys, nesting):
    study = tmp_path / "deep.toml"
    study.write_text('base = "spindle-axial-preload"\n' + nesting + "\n")
    assert cli.main(["study", str(study), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "levels deep" in err and "Traceback" not in err


@pytest.mark.parametrize(
    "manifest",
    ["{not json", "[]", '{"title": "t", "base": "b", "varied_keys": []}', '{"points": [[]]}'],
    ids=["not JSON", "a list", "no points", "point is a list"],
)
@pytest.mark.parametrize("command", ["study show", "report"])
def test_a_broken_study_folder_is_not_a_study_folder(tmp_path, capsys, manifest, command):
    folder = tmp_path / "s"
    folder.mkdir()
    (folder / "study.json").write_text(manifest)
    args = (
        ["study", "show", str(folder)]
        if command == "study show"
        else ["report", str(folder), "--output", str(tmp_path / "r.html")]
    )
    assert cli.main(args) == 2
    err = capsys.readouterr().err
    assert "not a study folder" in err and "Traceback" not in err
