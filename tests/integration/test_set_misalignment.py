"""An imposed misalignment of a bearing set (``set.misalignment_deg``): the shaft's tilt in the
housing is imposed, not solved (docs/case-format.md, "Bearing sets").

Independent checks: a set of one bearing under an imposed tilt is the single-bearing model's
misalignment (a separate implementation); the moment the set reports as holding the tilt, applied
as a moment load to the free set, tilts it by the same angle; the face-to-face pair, whose pressure
centres nearly coincide, changes its bearings' loads far less under a tilt than the back-to-back
pair, whose pressure centres lie about 29 mm apart.
"""

import math

import numpy as np
import pytest

from solver import CaseError, parse_case, solve, solve_quasistatic

from .test_bearing_set import BEARING, set_case, single_case

PAIR = """[set]
arrangement = "{arrangement}"
width_mm = 15.0
{misalignment}
[set.preload]
kind = "force"
force_N = 100.0
[set.load]
position_mm = 7.5
force_N = [0.0, 0.0, 0.0]
{moment}
"""


def pair(arrangement, tilt_deg=None, moment_Nm=None, speed_rpm=12000.0):
    misalignment = "" if tilt_deg is None else f"misalignment_deg = [0.0, {tilt_deg!r}]"
    moment = (
        ""
        if moment_Nm is None
        else f"moment_Nm = [{float(moment_Nm[0])!r}, {float(moment_Nm[1])!r}]"
    )
    return set_case(
        speed_rpm, PAIR.format(arrangement=arrangement, misalignment=misalignment, moment=moment)
    )


def test_set_of_one_bearing_under_a_tilt_is_the_single_bearing_misalignment():
    speed, axial, tilt = 12000.0, 300.0, 0.05
    single = solve_quasistatic(
        single_case(speed, axial=axial).with_values(
            {
                "operating.misalignment_deg": tilt,
                "operating.misalignment_axis_deg": 90.0,
                "operating.misalignment_frame": "space",
            }
        )
    )
    one = solve(
        set_case(
            speed,
            f"""[set]
width_mm = 15.0
misalignment_deg = [0.0, {tilt}]
[[set.bearing]]
direction = "+x"
position_mm = 0.0
[set.load]
force_N = [{axial}, 0.0, 0.0]
""",
        )
    ).isel(bearing=0)
    assert np.allclose(one["shaft_tilt"].values, [0.0, tilt], atol=1e-12)
    for name in ("contact_load", "contact_angle"):
        a, b = one[name].values, single[name].values
        assert np.allclose(a, b, rtol=0.0, atol=1e-7 * np.abs(b).max()), name
    # the moment the single bearing's inner ring needs for its tilt holds the set's shaft
    expected = single["inner_ring_moment"].values
    assert abs(expected[1]) > 0.1  # N m
    assert np.allclose(one["misalignment_moment"].values, expected, rtol=1e-7, atol=1e-9)


def test_the_holding_moment_applied_as_a_load_tilts_the_free_set_as_much():
    tilt = 0.03
    imposed = solve(pair("DB", tilt_deg=tilt))
    moment = imposed["misalignment_moment"].values
    assert abs(moment[1]) > 10.0  # N m: a DB pair is stiff in tilt
    free = solve(pair("DB", moment_Nm=moment))
    assert np.allclose(free["shaft_tilt"].values, [0.0, tilt], rtol=0.0, atol=1e-6 * tilt)
    assert np.allclose(
        free["bearing_axial_load"].values, imposed["bearing_axial_load"].values, rtol=1e-6
    )


def test_a_small_tilt_needs_the_moment_of_the_tilt_stiffness():
    tilt = 0.002  # deg: small enough for the stiffness at zero tilt to hold
    untilted = solve(pair("DB", tilt_deg=0.0))
    moment = solve(pair("DB", tilt_deg=tilt))["misalignment_moment"].values
    k = untilted["set_stiffness"].values
    expected = k[3:5, 4] * math.radians(tilt)
    assert np.allclose(moment, expected, rtol=0.03, atol=0.03 * abs(expected[1]))


def test_face_to_face_tolerates_a_tilt_with_less_load_change_than_back_to_back():
    tilt = 0.02
    change = {}
    for arrangement in ("DB", "DF"):
        at_rest = solve(pair(arrangement, tilt_deg=0.0))["bearing_axial_load"].values
        tilted = solve(pair(arrangement, tilt_deg=tilt))
        change[arrangement] = float(
            np.max(np.abs(tilted["bearing_axial_load"].values - at_rest) / at_rest)
        )
    # the pressure-centre spreads: DB about 15 mm + 2 x 7 mm, DF about 15 mm - 2 x 7 mm
    assert change["DB"] > 0.5  # the DB pair's preload more than 1.5 x under 0.02 deg
    assert change["DF"] < 0.1 * change["DB"]


@pytest.mark.parametrize(
    ("extra", "expected"),
    [
        ("misalignment_deg = 0.1", "set.misalignment_deg = 0.1: give 2 numbers [y, z]"),
        ("misalignment_deg = [0.0, 2.0]", "each tilt must lie within ±1 deg"),
        (
            "misalignment_deg = [0.0, 0.1]\n[set.load]\nmoment_Nm = [0.0, 1.0]",
            "set.load.moment_Nm is not read when set.misalignment_deg imposes",
        ),
    ],
)
def test_a_bad_misalignment_names_its_key(extra, expected):
    text = f'title = "set"\n{BEARING}\n[operating]\ninner_ring_speed_rpm = 0.0\n'
    text += f'[set]\narrangement = "DF"\nwidth_mm = 15.0\n{extra}\n'
    with pytest.raises(CaseError) as info:
        parse_case(text)
    assert expected in str(info.value)
