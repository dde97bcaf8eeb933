"""`racetrace cases` and `racetrace check` through a real subprocess: exit codes and messages."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.helpers.cases import SPINDLE_BEARING, case_text

GOOD = case_text(
    "cli test", SPINDLE_BEARING, {"inner_ring_speed_rpm": 20000.0, "axial_load_N": 500.0}
)


def racetrace(*args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", *args], capture_output=True, text=True, timeout=120
    )


def write(tmp_path, text, name="case.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_cases_lists_the_catalogue():
    result = racetrace("cases")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].split() == ["NAME", "KIND", "PROVENANCE", "TITLE"]
    assert any(
        line.split()[:3] == ["218-angular-contact", "bearing", "literature"] for line in lines
    )
    assert any(line.split()[:2] == ["spindle-combined-load", "case"] for line in lines)


def test_cases_show_prints_a_valid_case(tmp_path):
    result = racetrace("cases", "show", "turbopump-hybrid")
    assert result.returncode == 0, result.stderr
    check = racetrace("check", write(tmp_path, result.stdout))
    assert check.returncode == 0, check.stderr
    assert "OK: the case is valid" in check.stdout


def test_cases_show_unknown_name():
    result = racetrace("cases", "show", "spindle-combined")
    assert result.returncode == 2
    assert "spindle-combined-load" in result.stderr and "Traceback" not in result.stderr


def test_check_summary(tmp_path):
    result = racetrace("check", write(tmp_path, GOOD))
    assert result.returncode == 0, result.stderr
    assert "free contact angle 15.000 deg (given)" in result.stdout
    assert "axial load 500 N" in result.stdout and "18 balls of 7.144 mm" in result.stdout


def test_check_accepts_catalogue_names():
    result = racetrace("check", "209-radial")
    assert result.returncode == 0, result.stderr
    assert "from the diametral clearance" in result.stdout and "4450 N" in result.stdout


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (GOOD.replace("ball_diameter_mm = 7.144\n", ""), ["bearing.ball_diameter_mm is missing"]),
        (
            GOOD.replace("ball_diameter_mm", "ball_diamter_mm"),
            ["unknown key bearing.ball_diamter_mm", "did you mean bearing.ball_diameter_mm?"],
        ),
        (
            GOOD.replace("ball_count = 18", "ball_count = 40"),
            ["bearing.ball_count = 40", "do not fit"],
        ),
        (
            GOOD.replace("pitch_diameter_mm = 54.0", "pitch_diameter_mm = 5.0"),
            ["bearing.pitch_diameter_mm = 5", "larger than the ball diameter"],
        ),
        (
            GOOD.replace("axial_load_N = 500.0", 'axial_load_N = "500 N"'),
            ['operating.axial_load_N = "500 N"', "must be a number"],
        ),
        (
            GOOD.replace("axial_load_N = 500.0", "axial_load_N = nan"),
            ["operating.axial_load_N = nan", "finite"],
        ),
        ("", ["is empty"]),
        ("[bearing\nball_count = 18\n", ["not valid TOML", "line 1"]),
    ],
)
def test_check_rejects_bad_files(tmp_path, text, expected):
    result = racetrace("check", write(tmp_path, text))
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    for piece in expected:
        assert piece in result.stderr, result.stderr


def test_check_lists_every_problem(tmp_path):
    bad = GOOD.replace("ball_count = 18", "ball_count = 2").replace(
        "axial_load_N = 500.0", "axial_load_N = -5.0"
    )
    result = racetrace("check", write(tmp_path, bad))
    assert result.returncode == 2
    assert (
        "bearing.ball_count = 2" in result.stderr and "operating.axial_load_N = -5" in result.stderr
    )


def test_check_missing_file(tmp_path):
    result = racetrace("check", str(tmp_path / "nope.toml"))
    assert result.returncode == 2
    assert "not found" in result.stderr and "Traceback" not in result.stderr


def test_check_says_why_the_dynamic_model_cannot_run_a_valid_case(tmp_path):
    """Equal ring speeds: valid (the quasi-static model solves it), not for the dynamic model."""
    text = GOOD.replace("axial_load_N = 500.0", "axial_load_N = 500.0\nouter_ring_speed_rpm = 2e4")
    result = racetrace("check", write(tmp_path, text))
    assert result.returncode == 0, result.stderr
    assert "OK: the case is valid" in result.stdout
    (line,) = [line for line in result.stdout.splitlines() if line.startswith("dynamic model: ")]
    assert "turn relative to each other" in line
    assert "dynamic model:" not in racetrace("check", write(tmp_path, GOOD, "good.toml")).stdout


@pytest.mark.parametrize("path", ["/dev/zero", "/dev/null"])
def test_check_refuses_devices_promptly(path):
    result = racetrace("check", path)
    assert result.returncode == 2
    assert "not a case file" in result.stderr and "Traceback" not in result.stderr


def test_check_refuses_a_fifo(tmp_path):
    import os

    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    result = racetrace("check", str(fifo))
    assert result.returncode == 2
    assert "named pipe" in result.stderr and "Traceback" not in result.stderr
