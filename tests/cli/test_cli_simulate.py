"""``racetrace simulate``: case warnings and result warnings on stderr, exit code unchanged; the
rating lives on stdout."""

import subprocess
import sys

from tests.helpers.cases import CONTRACT_EXAMPLE


def test_simulate_prints_case_and_result_warnings(tmp_path):
    """The contract example's lands do not rise above their grooves: the case warning, then the
    result's truncation warnings for both races, as ``warning: ...`` lines; the run exits 0."""
    case = tmp_path / "example.toml"
    case.write_text(CONTRACT_EXAMPLE)
    output = tmp_path / "run.nc"
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "racetrace",
            "simulate",
            str(case),
            "--output",
            str(output),
            "--revolutions",
            "0.05",
            "--samples-per-revolution",
            "40",
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr
    assert output.exists()
    lines = out.stderr.splitlines()
    assert any(
        line.startswith("warning: bearing.inner_shoulder_diameter_mm = 45.9") for line in lines
    )
    for race in ("inner", "outer"):
        assert any(
            line.startswith(f"warning: {race} race: the contact ellipse runs over the shoulder")
            and "time samples" in line
            for line in lines
        ), out.stderr
    assert "Traceback" not in out.stderr
    life = [line for line in out.stdout.splitlines() if line.startswith("  L10")]
    assert len(life) == 2, out.stdout
    assert "million revolutions" in life[1] and "over the analysed window" in life[1]
