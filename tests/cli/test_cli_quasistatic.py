"""``racetrace quasistatic``: exit codes 0/2/3, table and JSON output, NetCDF output, warnings on
stderr (subprocesses)."""

import json
import subprocess
import sys

import pytest

from tests.helpers.cases import CONTRACT_EXAMPLE, case_text

NO_SOLUTION_CASE = case_text(
    "218 at an absurd speed with 1 N preload",
    {
        "designation": "218",
        "provenance": "literature",
        "ball_count": 16,
        "ball_diameter_mm": 22.225,
        "pitch_diameter_mm": 125.26,
        "inner_groove_radius_ratio": 0.5232,
        "outer_groove_radius_ratio": 0.5232,
        "free_contact_angle_deg": 40.0,
        "ball_material": "bearing_steel",
        "ring_material": "bearing_steel",
    },
    {"inner_ring_speed_rpm": 200000.0, "axial_load_N": 1.0},
)


def run(*args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", "quasistatic", *args],
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_solve_is_the_same_command():
    solve = subprocess.run(
        [sys.executable, "-m", "racetrace", "solve", "spindle-combined-load", "--json"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert solve.returncode == 0, solve.stderr
    quasistatic = run("spindle-combined-load", "--json")
    assert json.loads(solve.stdout) == json.loads(quasistatic.stdout)
    listed = subprocess.run(
        [sys.executable, "-m", "racetrace", "--help"], capture_output=True, text=True, timeout=60
    )
    assert "quasistatic (solve)" in listed.stdout


def test_table_for_a_catalogue_case():
    result = run("spindle-combined-load")
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "Q_i" in out and "a_o" in out and "control" in out
    assert "GPa" in out or "MPa" in out
    assert "cage speed:" in out and "um" in out
    rows = [
        line
        for line in out.splitlines()
        if line.strip().endswith(("outer", "inner", "traction")) and line.strip()[0].isdigit()
    ]
    assert len(rows) == 18
    # rating lives: ISO 281 hand-worked in tests/unit/physics/test_life.py and
    # tests/unit/results/test_life.py (5 354 million revolutions, 4 462 h at 20 000 rpm, C_r
    # 14 049 N with f_c reduced for f_i = 0.54, P_r 803 N)
    assert (
        "L10  (ISO 281, applied loads):       5354 million revolutions = 4462 h "
        "(C_r 14049 N, P_r 803 N)" in out
    )
    assert "L10r (ISO/TS 16281, contact loads): " in out
    assert "note: ISO 281 and ISO/TS 16281 rate rings and balls of bearing steel" in out


def test_json_summary_and_netcdf_output(tmp_path):
    target = tmp_path / "result.nc"
    result = run("218-heavy-combined", "--json", "--output", str(target))
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    assert len(summary["balls"]) == 16
    assert summary["inner_ring_speed_rpm"] == pytest.approx(10000.0)
    assert summary["max_contact_load_N"]["inner"] > 17800.0 / 16
    assert 0.4 < summary["cage_to_shaft_speed_ratio"] < 0.5
    assert summary["output"] == str(target)
    from solver.results.io import load_dataset

    ds = load_dataset(target)
    assert ds.attrs["model"] == "quasistatic"
    assert ds.sizes["ball"] == 16
    assert max(b["contact_load_N"]["inner"] for b in summary["balls"]) == pytest.approx(
        float(ds.contact_load.values[:, 0].max())
    )
    life = summary["life"]
    assert life["L10r_million_revolutions"] == pytest.approx(float(ds.reference_rating_life) / 1e6)
    # hours = revolutions / (10 000 rev/min * 60 min/h)
    assert life["L10_hours"] == pytest.approx(life["L10_million_revolutions"] * 1e6 / 6e5)
    assert life["L10r_hours"] == pytest.approx(life["L10r_million_revolutions"] * 1e6 / 6e5)
    assert life["notes"] == []  # steel balls and rings, 40 deg: inside both standards


def test_invalid_case_exits_2_without_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(NO_SOLUTION_CASE.replace("ball_count = 16\n", ""))
    result = run(str(bad))
    assert result.returncode == 2
    assert "ball_count" in result.stderr
    assert "Traceback" not in result.stderr
    result = run("no-such-case-anywhere")
    assert result.returncode == 2
    assert "Traceback" not in result.stderr


def test_no_solution_exits_3_with_reason_and_remedy(tmp_path):
    case = tmp_path / "fast.toml"
    case.write_text(NO_SOLUTION_CASE)
    result = run(str(case))
    assert result.returncode == 3
    assert "no solution" in result.stderr
    assert "rpm" in result.stderr and "axial preload" in result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout == ""


def test_output_into_a_missing_directory_exits_2(tmp_path):
    result = run("209-radial", "--output", str(tmp_path / "missing" / "r.nc"))
    assert result.returncode == 2
    assert "does not exist" in result.stderr and "Traceback" not in result.stderr


def test_contract_example_solves_and_warns_about_its_lands(tmp_path):
    path = tmp_path / "example.toml"
    path.write_text(CONTRACT_EXAMPLE)
    out = run(str(path))
    assert out.returncode == 0, out.stderr
    assert "Traceback" not in out.stderr
    assert "inner_shoulder_diameter_mm = 45.9" in out.stderr
    assert "outer_shoulder_diameter_mm = 62.2" in out.stderr
    header = next(line for line in out.stdout.splitlines() if line.startswith("ball"))
    assert header.split()[:4] == ["ball", "psi", "alpha_i", "alpha_o"]
    assert "-0 " not in out.stdout


def test_result_outside_the_model_is_warned_on_stderr(tmp_path):
    """209 deep groove at 1e9 N axial (an absurd load on a real case): still exit 0, but stderr says
    the pressure is beyond the ISO 76 static limit and the contact too large for Hertz theory."""
    from solver.catalogue import resolve_case

    case = resolve_case("209-radial").with_values({"operating.axial_load_N": 1e9})
    path = tmp_path / "absurd.toml"
    path.write_text(case.to_toml())
    out = run(str(path))
    assert out.returncode == 0, out.stderr
    lines = out.stderr.splitlines()
    for race in ("inner", "outer"):
        assert any(
            line.startswith(f"warning: {race} race: peak contact pressure") and "4.2 GPa" in line
            for line in lines
        ), out.stderr
        assert any(
            line.startswith(f"warning: {race} race: contact too large for Hertz theory")
            for line in lines
        ), out.stderr
    assert "Traceback" not in out.stderr
    assert "ball" in out.stdout  # the table is still printed


def test_catalogue_case_gives_only_its_documented_warning():
    """The heavy 218 case warns once: its traction balance finds no steady spin for the most
    loaded ball (thermally softened traction), so race control sets the ball speeds
    (docs/traction.md); the spindle case gives no warning."""
    out = run("218-heavy-combined")
    assert out.returncode == 0, out.stderr
    warnings = [line for line in out.stderr.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 1, out.stderr
    assert warnings[0].startswith("warning: quasi-static ball speeds: the traction balance")
    out = run("spindle-combined-load")
    assert out.returncode == 0 and "warning:" not in out.stderr, out.stderr


def test_contract_example_lands_give_truncation_warnings(tmp_path):
    """Lands that do not rise above their grooves: the case warning and, from the result, every
    loaded contact truncated on both races (case-format.md)."""
    path = tmp_path / "example.toml"
    path.write_text(CONTRACT_EXAMPLE)
    out = run(str(path))
    assert out.returncode == 0, out.stderr
    for race in ("inner", "outer"):
        assert f"warning: {race} race: the contact ellipse runs over the shoulder" in out.stderr
