"""The results-variable registry covers the schema with UDUNITS units and angles in degree."""

import re
from pathlib import Path

import pytest

from solver.results.variables import VARIABLES, variable

SCHEMA = Path("/work/shared/design/results-schema.md")
ALLOWED_UNITS = {"m", "N", "N m", "Pa", "rad/s", "s", "degree", "1", "m/s"}


def test_every_variable_has_units_names_and_known_dims():
    dims = {"ball", "race", "axis", "tilt_axis", "quaternion"}
    for name, spec in VARIABLES.items():
        assert spec.units in ALLOWED_UNITS, name
        assert spec.long_name and spec.description, name
        assert set(spec.dims) <= dims, name
        assert set(spec.models) <= {"quasistatic", "dynamic"}


def test_angles_are_in_degree():
    for name in (
        "contact_angle",
        "raceway_azimuth",
        "ball_latitude",
        "ball_longitude",
        "ball_azimuth",
        "attitude_angle",
        "inner_ring_tilt",
        "truncation_margin",
        "trajectory_band_width",
    ):
        assert VARIABLES[name].units == "degree", name


def test_dynamic_dims_append_time_except_summary_metrics():
    assert variable("contact_load").dims_for("dynamic") == ("ball", "race", "time")
    assert variable("contact_load").dims_for("quasistatic") == ("ball", "race")
    assert variable("cage_speed").dims_for("dynamic") == ("time",)
    assert variable("trajectory_band_width").dims_for("dynamic") == ("race",)
    with pytest.raises(KeyError, match="known"):
        variable("contact_lode")


@pytest.mark.skipif(not SCHEMA.exists(), reason="shared schema not available")
def test_registry_covers_every_variable_named_in_the_schema():
    text = SCHEMA.read_text()
    names = set(re.findall(r"`([a-z_]+)`", text))
    not_variables = {
        "ball",
        "race",
        "axis",
        "time",
        "tilt_axis",
        "quaternion",
        "model",
        "case",
        "software",
        "created",
        "complete",
        "inner",
        "outer",
        "x",
        "y",
        "z",
        "w",
        "degree",
        "m",
        "N",
        "Pa",
        "s",
        "units",
        "long_name",
        "quasistatic",
        "dynamic",
    }
    missing = sorted(n for n in names - not_variables if n not in VARIABLES)
    assert not missing, missing
