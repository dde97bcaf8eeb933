"""``racetrace study show`` of a study of bearing sets: each bearing's axial load and the set's
stiffness per point (the shipped assets/studies/results/spindle-pair-db-speed.study.nc)."""

import subprocess
import sys
from pathlib import Path

SHIPPED = (
    Path(__file__).resolve().parents[2]
    / "assets"
    / "studies"
    / "results"
    / "spindle-pair-db-speed.study.nc"
)


def test_study_show_of_a_set_study_gives_the_bearings_loads_and_the_stiffness():
    out = subprocess.run(
        [sys.executable, "-m", "racetrace", "study", "show", str(SHIPPED)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    header = next(line for line in lines if line.startswith("point"))
    for column in ("Fa bearing 1 N", "Fa bearing 2 N", "k_ax N/um", "k_rad N/um"):
        assert column in header
    assert "band_i deg" not in header  # one bearing's metrics have no meaning for a set
    # the spring preload's points: the rear bearing carries the spring's 100 N at every speed
    rows = [line.split() for line in lines if line.startswith("p00")]
    assert len(rows) == 34  # 4 sweeps over 6 speeds, 2 over 5 preload forces
    assert all(row[-4] == "100.0" for row in rows[18:24])  # the fourth sweep: the spring
    assert "Fa = axial load each bearing of the set carries" in out.stdout
