"""``racetrace simulate``'s progress: "compiling (first run only)" on a cold cache, and no ETA
until the progress rate is known."""

from __future__ import annotations

import io

from racetrace.commands import simulate as simulate_command


def test_no_eta_until_the_rate_is_known(monkeypatch):
    clock = iter([0.0, 10.0, 10.5, 12.0])  # start; compiling took 10 s before the first report
    monkeypatch.setattr(simulate_command.time, "perf_counter", lambda: next(clock))
    out = io.StringIO()
    bar = simulate_command.ProgressBar(stream=out)
    bar(0.01, 1e-4)
    assert out.getvalue().rstrip().endswith("ETA --")
    bar(0.02, 2e-4)  # 0.5 s after the first report: still too early
    assert out.getvalue().rstrip().endswith("ETA --")
    bar(0.03, 3e-4)  # 2 s for 2 %: 97 s left (the 10 s of compiling are not counted)
    assert out.getvalue().rstrip().endswith("ETA 97 s")


def test_a_cold_cache_says_compiling(tmp_path, monkeypatch, capsys):
    import solver.compiled
    from racetrace.cli import main
    from tests.helpers.cases import CONTRACT_EXAMPLE

    monkeypatch.setattr(solver.compiled, "dynamic_model_compiled", lambda: False)
    case = tmp_path / "example.toml"
    case.write_text(CONTRACT_EXAMPLE)
    args = ["simulate", str(case), "--output", str(tmp_path / "run.nc"), "--revolutions", "0.02"]
    assert main(args) == 0
    assert "compiling the dynamic model (first run only)" in capsys.readouterr().err
