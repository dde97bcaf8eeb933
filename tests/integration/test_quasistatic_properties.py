"""Property test: random cases either solve with balanced forces or fail with a clear message."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.case import Case
from solver.errors import CaseError, NoSolutionError
from solver.inputs import to_inputs
from solver.models.quasistatic import solve_quasistatic_state

from .test_quasistatic import check_equilibrium


@st.composite
def cases(draw):
    ball_count = draw(st.integers(6, 30))
    ball_diameter = draw(st.floats(3.0, 25.0))
    # pitch diameter from a packing ratio (Z D / (pi d_m) in [0.5, 0.95])
    packing = draw(st.floats(0.5, 0.95))
    pitch = ball_count * ball_diameter / (math.pi * packing)
    bearing = {
        "designation": "random",
        "provenance": "estimated",
        "ball_count": ball_count,
        "ball_diameter_mm": ball_diameter,
        "pitch_diameter_mm": pitch,
        "inner_groove_radius_ratio": draw(st.floats(0.505, 0.57)),
        "outer_groove_radius_ratio": draw(st.floats(0.505, 0.57)),
        "ball_material": draw(st.sampled_from(["bearing_steel", "silicon_nitride"])),
        "ring_material": "bearing_steel",
    }
    if draw(st.booleans()):
        bearing["free_contact_angle_deg"] = draw(st.floats(0.0, 45.0))
    else:
        bearing["diametral_clearance_mm"] = draw(st.floats(0.0, 0.03))
    # loads scaled with the bearing size (basic load ratings scale roughly with Z D^2)
    scale = ball_count * ball_diameter**2
    operating = {
        "inner_ring_speed_rpm": draw(st.sampled_from([0.0, 1.0]))
        * draw(st.floats(0.0, 1.5e6))
        / pitch,  # up to d_m n = 1.5e6 mm rpm
        "axial_load_N": draw(st.floats(0.0, 1.0)) * scale,
        "radial_load_N": draw(st.floats(0.0, 1.0)) * scale,
        "radial_load_angle_deg": draw(st.floats(0.0, 360.0)),
    }
    if operating["axial_load_N"] + operating["radial_load_N"] < 1e-3 * scale:
        operating["axial_load_N"] = 0.1 * scale
    tilt = draw(st.sampled_from(["none", "misalignment", "moment"]))
    if tilt == "misalignment":
        operating["misalignment_deg"] = draw(st.floats(0.0, 0.2))
        operating["misalignment_axis_deg"] = draw(st.floats(0.0, 360.0))
    elif tilt == "moment":
        operating["tilting_moment_Nm"] = draw(st.floats(0.0, 0.05)) * scale * pitch * 1e-3
        operating["moment_axis_deg"] = draw(st.floats(0.0, 360.0))
    return {"title": "random case", "bearing": bearing, "operating": operating}


def check_case(data):
    """Solve a random case: equilibrium to 1e-8, or a clear CaseError / NoSolutionError."""
    try:
        case = Case.from_dict(data)
    except CaseError as error:
        assert str(error).strip()
        return
    try:
        sol = solve_quasistatic_state(case)
    except NoSolutionError as error:
        assert "Try" in str(error)
        return
    check_equilibrium(case.geometry(), to_inputs(case).operating, sol)
    assert np.all(np.isfinite(sol.contact_load))


@settings(max_examples=35, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=cases())
def test_random_cases_solve_in_equilibrium_or_fail_clearly(data):
    check_case(data)


@pytest.mark.slow
@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=cases())
def test_many_random_cases_solve_in_equilibrium_or_fail_clearly(data):
    """The same property on ten times more examples (slow validation run)."""
    check_case(data)
