"""The results-variable registry covers the schema with UDUNITS units and angles in degree."""

import re
from pathlib import Path

import pytest

from solver.models.dynamic.set_output import SET_DYNAMIC_VARIABLES
from solver.models.quasistatic.set_result import SET_VARIABLES
from solver.results.metrics import METRICS
from solver.results.variables import (
    COORDINATES,
    DIMENSION_COORDINATES,
    DIMENSION_VALUES,
    VARIABLES,
    variable,
)

SCHEMA = Path(__file__).resolve().parents[3] / "docs" / "results-schema.md"
ALLOWED_UNITS = {"m", "N", "N m", "Pa", "rad/s", "s", "degree", "1", "m/s", "kg m-3", "W", "J"}


def test_every_variable_has_units_names_and_known_dims():
    dims = {"ball", "race", "axis", "tilt_axis", "quaternion", "frame", "body", "ring_angle"}
    dims |= {"ball_loss_source", "loss_source"}
    for name, spec in {**VARIABLES, **COORDINATES, **DIMENSION_COORDINATES}.items():
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
        "trajectory_excursion",
        "trajectory_band_thickness",
        "quasistatic_ball_azimuth",
        "quasistatic_contact_angle",
    ):
        assert VARIABLES[name].units == "degree", name
    for name in (
        "radial_load_angle",
        "misalignment",
        "misalignment_axis",
        "moment_axis",
        "free_contact_angle",
    ):
        assert COORDINATES[name].units == "degree", name


def test_coordinates_and_variables_do_not_share_a_name():
    assert not set(VARIABLES) & set(COORDINATES)
    assert variable("inner_ring_speed").units == "rad/s"
    assert variable("groove_radius").dims == ("race",)


def test_dynamic_dims_append_time_except_summary_metrics():
    assert variable("contact_load").dims_for("dynamic") == ("ball", "race", "time")
    assert variable("contact_load").dims_for("quasistatic") == ("ball", "race")
    assert variable("cage_speed").dims_for("dynamic") == ("time",)
    assert variable("trajectory_band_width").dims_for("dynamic") == ("race",)
    with pytest.raises(KeyError, match="known"):
        variable("contact_lode")


#: Attributes and words in backquotes in the schema document that are not registry names.
SCHEMA_WORDS = {
    "friction_torque_palmgren_note",
    "friction_torque_skf_note",
    "model",
    "case",
    "software",
    "created",
    "complete",
    "stop_reason",
    "analysed_window",
    "shaft_period_s",
    "note",
    "units",
    "long_name",
    "description",
    "quasistatic",
    "dynamic",
    "time",
    "degree",
    "m",
    "N",
    "Pa",
    "s",
    "quasistatic_speed_sweep",
    "solve_over_revolution",
    "quasistatic_along_history",
    "along_history",
    "history_time",
    "racetrace",
    "result_warnings",
    "kinematics",
    "kinematics_note",
    "title",
    "bearing_provenance",
    "phase_boundaries_s",
    "phase_labels",
    "phase",
    "phase_start_time",
    "phase_end_time",
    "phase_label",
    "live_ramp_s",  # a live chunk's attribute (docs/live.md)
}
#: The bearing set's coordinates and attributes (results-schema.md, "Bearing sets").
SET_WORDS = {
    "bearing",
    "set_model",
    "preload_offset_m",
    "bearing_position",
    "bearing_direction",
    "ball_count",
    "load_position",
    "dof",
    "dof_",
    "bearing_set",
    "set_note",
    "solver_iterations",
    "solver_residual",
    "stiffness_symmetry",
    "unloaded_at_rest",
    "preload_force",
}


def test_registry_covers_every_name_in_the_schema_document():
    """docs/results-schema.md is in the repository (never skipped): every name it puts in
    backquotes is a registered variable or coordinate, a dimension or its label, a metric of the
    metrics table or a listed attribute."""
    text = SCHEMA.read_text(encoding="utf-8")
    names = set(re.findall(r"`([a-z_]+)`", text))
    labels = set(DIMENSION_VALUES) | {v for values in DIMENSION_VALUES.values() for v in values}
    known = set(VARIABLES) | set(COORDINATES) | set(DIMENSION_COORDINATES) | labels
    known |= SCHEMA_WORDS | {"ball"} | set(METRICS) | set(SET_VARIABLES) | SET_WORDS
    known |= set(SET_DYNAMIC_VARIABLES)
    missing = sorted(names - known)
    assert not missing, missing


def test_schema_document_names_every_set_variable():
    text = SCHEMA.read_text(encoding="utf-8")
    documented = set(re.findall(r"`([a-z_]+)`", text))
    assert not sorted(set(SET_VARIABLES) - documented)


def test_schema_document_names_every_dynamic_set_variable():
    """Each variable of a set's dynamic result (e.g. a spring preload's ``spring_shift`` and
    ``spring_force``) is named in the dynamic set's section of docs/results-schema.md."""
    text = SCHEMA.read_text(encoding="utf-8")
    section = text[text.index("### Dynamic results of a bearing set") :]
    section = section[: section.index("\n## ")]
    documented = set(re.findall(r"`([a-z_]+)`", section))
    assert not sorted(set(SET_DYNAMIC_VARIABLES) - documented)


def test_schema_document_names_every_registered_name():
    text = SCHEMA.read_text(encoding="utf-8")
    documented = set(re.findall(r"`([a-z_]+)`", text))
    registered = set(VARIABLES) | set(COORDINATES) | set(DIMENSION_COORDINATES)
    missing = sorted(n for n in registered if n not in documented)
    assert not missing, missing
