"""Independent checks of the quasi-static bearing-set model (issue 25 §2-3).

Each check compares the set solve with something computed another way: the single-bearing model's
own load-deflection curves and solutions, or finite differences of the solved equilibrium.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from solver import parse_case, set_result_warnings, solve, solve_quasistatic
from solver.models.quasistatic import solve_quasistatic_state
from solver.models.quasistatic.bearing_set import solve_set_state

BEARING = """
[bearing]
designation = "7008C-class hybrid"
provenance = "estimated"
ball_count = 18
ball_diameter_mm = 7.144
pitch_diameter_mm = 54.0
inner_groove_radius_ratio = 0.54
outer_groove_radius_ratio = 0.53
free_contact_angle_deg = 15.0
ball_material = "silicon_nitride"
ring_material = "bearing_steel"
"""


def single_case(
    speed_rpm,
    axial=0.0,
    radial=0.0,
    angle=0.0,
    moment=None,
    moment_axis=0.0,
    ball_speeds="race_control",
):
    text = f'title = "one"\n{BEARING}\n[operating]\ninner_ring_speed_rpm = {speed_rpm!r}\n'
    text += f"axial_load_N = {float(axial)!r}\nradial_load_N = {float(radial)!r}\n"
    text += f"radial_load_angle_deg = {float(angle)!r}\n"
    if moment is not None:
        text += f"tilting_moment_Nm = {float(moment)!r}\nmoment_axis_deg = {float(moment_axis)!r}\n"
    text += f'[simulation]\nquasistatic_ball_speeds = "{ball_speeds}"\n'
    return parse_case(text)


def set_case(speed_rpm, set_table, ball_speeds="race_control"):
    text = f'title = "set"\n{BEARING}\n[operating]\ninner_ring_speed_rpm = {speed_rpm!r}\n'
    text += f'[simulation]\nquasistatic_ball_speeds = "{ball_speeds}"\n{set_table}'
    return parse_case(text)


def axial_approach(speed_rpm, load):
    """The single-bearing model's axial approach [m] of the inner ring under a pure axial load."""
    return solve_quasistatic_state(single_case(speed_rpm, axial=load)).inner_ring_offset[0]


@pytest.mark.parametrize("speed_rpm", [0.0, 12000.0])
def test_db_pair_splits_axial_load_as_the_single_bearing_curves_predict(speed_rpm):
    offset_um, thrust = 20.0, 400.0
    ds = solve(
        set_case(
            speed_rpm,
            f"""[set]
arrangement = "DB"
width_mm = 15.0
[set.preload]
kind = "offset"
offset_um = {offset_um}
[set.load]
force_N = [{thrust}, 0.0, 0.0]
""",
        )
    )
    # compatibility by hand: the approaches of the two bearings sum to the offset, and their
    # axial loads differ by the thrust (bearing 1 faces +x and takes it)
    offset = offset_um * 1e-6

    def gap(f2):
        return axial_approach(speed_rpm, thrust + f2) + axial_approach(speed_rpm, f2) - offset

    f2 = brentq(gap, 1.0, 2000.0, xtol=1e-10, rtol=1e-12)
    loads = ds["bearing_axial_load"].values
    assert loads == pytest.approx([thrust + f2, f2], rel=1e-7)
    assert ds["bearing_force"].sum("bearing").values == pytest.approx(
        [-thrust, 0.0, 0.0], abs=1e-7 * thrust
    )


@pytest.mark.parametrize("speed_rpm", [0.0, 15000.0])
def test_symmetric_pair_without_load_has_no_net_force_and_equal_preloads(speed_rpm):
    preload = 250.0
    ds = solve(
        set_case(
            speed_rpm,
            f"""[set]
arrangement = "DF"
width_mm = 15.0
[set.preload]
kind = "force"
force_N = {preload}
""",
        )
    )
    force = ds["bearing_force"].sum("bearing").values
    moment = ds["bearing_moment"].sum("bearing").values
    assert np.abs(force).max() <= 1e-9 * preload
    assert np.abs(moment).max() <= 1e-9 * preload * 0.015
    loads = ds["bearing_axial_load"].values
    assert loads[0] == pytest.approx(loads[1], rel=1e-9)
    if speed_rpm == 0.0:  # the fixed-position offset was solved for this force at rest
        assert loads == pytest.approx([preload, preload], rel=1e-9)
    else:  # the balls' centrifugal forces raise a fixed-position preload
        assert loads[0] > preload
    assert ds["shaft_offset"].values == pytest.approx([0.0, 0.0, 0.0], abs=1e-15)


def _solved_shaft(speed_rpm, table, force, moment):
    force = [float(x) for x in force]
    moment = [float(x) for x in moment]
    case = set_case(speed_rpm, table + f"[set.load]\nforce_N = {force}\nmoment_Nm = {moment}\n")
    return solve_set_state(case)


def test_stiffness_matches_finite_differences_of_the_solved_equilibrium():
    table = """[set]
arrangement = "DB"
width_mm = 15.0
spacing_mm = 40.0
[set.preload]
kind = "force"
force_N = 200.0
"""
    speed = 10000.0
    force, moment = np.array([150.0, 300.0, -100.0]), np.array([2.0, -1.0])
    base = _solved_shaft(speed, table, force, moment)
    stiffness = base.set_stiffness
    loads = np.concatenate([force, moment])
    steps = np.array([1.0, 1.0, 1.0, 0.01, 0.01])  # N and N m: small against the loads
    compliance = np.empty((5, 5))
    for j in range(5):
        up, down = loads.copy(), loads.copy()
        up[j] += steps[j]
        down[j] -= steps[j]
        u_up = _solved_shaft(speed, table, up[:3], up[3:]).shaft
        u_down = _solved_shaft(speed, table, down[:3], down[3:]).shaft
        compliance[:, j] = (u_up - u_down) / (2.0 * steps[j])
    # the applied load F balances the bearings: K du = dF
    expected = np.linalg.inv(stiffness)
    scale = np.sqrt(np.abs(np.outer(np.diag(expected), np.diag(expected))))
    assert np.max(np.abs(compliance - expected) / scale) <= 1e-4


def test_each_bearing_stiffness_sums_to_the_set_stiffness():
    table = """[set]
arrangement = "TBT"
width_mm = 15.0
[set.preload]
kind = "force"
force_N = 300.0
"""
    state = _solved_shaft(8000.0, table, [100.0, 200.0, 0.0], [0.0, 0.0])
    from solver.models.quasistatic.bearing_set import lever

    total = sum(
        lever(m.arm).T @ k @ lever(m.arm)
        for m, k in zip(state.members, state.stiffness, strict=True)
    )
    assert np.allclose(total, state.set_stiffness, rtol=1e-9, atol=1e-9 * np.abs(total).max())
    # at rest with no friction the stiffness is symmetric
    rest = _solved_shaft(0.0, table, [100.0, 200.0, 0.0], [0.0, 0.0]).set_stiffness
    d = np.sqrt(np.abs(np.diag(rest)))
    scaled = rest / np.outer(d, d)
    assert np.max(np.abs(scaled - scaled.T)) < 1e-5  # the kernel's FD Jacobian: ~1e-6


def _assert_same(one, single):
    """Every numeric variable of the single-bearing Dataset, and its per-ball strings, agree."""
    compared = 0
    for name, var in single.data_vars.items():
        assert name in one, name
        a, b = one[name].values, var.values
        if b.dtype.kind in "fiu":
            finite = np.abs(b[np.isfinite(b)])  # NaN: e.g. no shoulder given (truncation)
            scale = float(finite.max()) if finite.size else 0.0
            # a variable that is exactly zero in the single bearing (the moment-free tilt's
            # moment): the set's round-off, in N m, against loads of hundreds of N
            atol = 1e-8 * scale if scale > 0.0 else 1e-9
            assert np.allclose(a, b, rtol=0.0, atol=atol, equal_nan=True), name
        else:
            assert np.array_equal(a, b), name
        compared += 1
    assert compared > 30


@pytest.mark.parametrize("ball_speeds", ["race_control", "traction"])
def test_set_of_one_bearing_reproduces_the_single_bearing_model(ball_speeds):
    speed, axial, radial = 12000.0, 300.0, 200.0
    single = solve_quasistatic(
        single_case(speed, axial=axial, radial=radial, moment=0.0, ball_speeds=ball_speeds)
    )
    one = solve(
        set_case(
            speed,
            f"""[set]
width_mm = 15.0
[[set.bearing]]
direction = "+x"
position_mm = 0.0
[set.load]
force_N = [{axial}, {radial}, 0.0]
""",
            ball_speeds,
        )
    )
    assert one.sizes["bearing"] == 1
    _assert_same(one.isel(bearing=0), single)


def test_set_of_one_mirrored_and_away_from_the_load_point():
    """A bearing facing -x, 20 mm from where the loads act: the single bearing sees the thrust
    with its sign turned and the radial load's moment about its own plane."""
    speed, thrust, radial, arm = 9000.0, -250.0, 150.0, 0.020
    one = solve(
        set_case(
            speed,
            f"""[set]
width_mm = 15.0
[[set.bearing]]
direction = "-x"
position_mm = {arm * 1e3}
[set.load]
position_mm = 0.0
force_N = [{thrust}, {radial}, 0.0]
""",
        )
    )
    # moment of the radial load (at x = 0) about the bearing plane (x = arm): (-arm e_x) x F
    # = (0, 0, -arm Fy); in the mirrored frame (x -> -x) the moment's y, z change sign
    mz = arm * radial
    single = solve_quasistatic(
        single_case(
            speed,
            axial=-thrust,
            radial=radial,
            moment=abs(mz),
            moment_axis=90.0 if mz > 0 else -90.0,
        )
    )
    _assert_same(one.isel(bearing=0), single)
    assert math.isclose(float(one["bearing_axial_load"][0]), -thrust, rel_tol=1e-9)


def test_spring_preload_holds_its_side_at_the_spring_force_with_mixed_bearings():
    """The spring side's outer rings float: whatever the load and speed, the bearings the spring
    pushes carry the spring force; the other bearing (16 balls, 25 degree) takes the rest."""
    spring = 120.0
    ds = solve(
        set_case(
            15000.0,
            f"""[set]
width_mm = 15.0
[set.preload]
kind = "spring"
force_N = {spring}
spring_side = "-x"
[set.load]
position_mm = -50.0
force_N = [100.0, 200.0, 0.0]
[[set.bearing]]
name = "front"
position_mm = 0.0
direction = "+x"
[set.bearing.bearing]
ball_count = 16
ball_diameter_mm = 7.144
pitch_diameter_mm = 54.0
inner_groove_radius_ratio = 0.54
outer_groove_radius_ratio = 0.53
free_contact_angle_deg = 25.0
ball_material = "bearing_steel"
ring_material = "bearing_steel"
[[set.bearing]]
name = "rear"
position_mm = 120.0
direction = "-x"
""",
        )
    )
    front, rear = ds["bearing_axial_load"].values
    assert rear == pytest.approx(spring, rel=1e-9)
    assert front == pytest.approx(spring + 100.0, rel=1e-6)  # axial balance of the shaft
    assert list(ds["ball_count"].values) == [16, 18]
    # the 16-ball bearing's two missing balls are padding, not results
    assert np.isnan(ds["contact_load"].sel(bearing="front").values[16:]).all()
    assert np.isfinite(ds["contact_load"].sel(bearing="rear").values).all()
    # the rear inner ring's approach in its own (mirrored) frame: minus the shaft's axial
    # displacement plus the shift of its floating outer ring
    rear_approach = ds["inner_ring_offset"].sel(bearing="rear", axis="x").item()
    shaft_x = ds["shaft_offset"].sel(axis="x").item()
    assert rear_approach == pytest.approx(-shaft_x + ds["spring_shift"].item(), rel=1e-12)
    assert set_result_warnings(ds) == []


def test_stiffness_study_over_preload_and_speed():
    """More preload stiffens the set; each point is the set solve of that preload and speed."""
    from solver.models.quasistatic.bearing_set import set_stiffness_study

    case = set_case(
        0.0,
        """[set]
arrangement = "DB"
width_mm = 15.0
[set.preload]
kind = "force"
force_N = 100.0
""",
    )
    study = set_stiffness_study(case, [50.0, 200.0], [0.0, 20000.0])
    axial = study["axial_stiffness"].values
    assert axial.shape == (2, 2)
    assert (axial[1] > axial[0]).all()  # heavier preload, stiffer at both speeds
    one = solve(
        case.with_values({"set.preload.force_N": 200.0, "operating.inner_ring_speed_rpm": 20000.0})
    )
    assert study["axial_stiffness"].values[1, 1] == pytest.approx(
        float(one["axial_stiffness"]), rel=1e-9
    )
    assert study["bearing_axial_load"].values[0, 0] == pytest.approx([50.0, 50.0], rel=1e-9)


def _db_with_thrust(speed_rpm, thrust):
    return set_case(
        speed_rpm,
        f"""[set]
arrangement = "DB"
width_mm = 15.0
[set.preload]
kind = "force"
force_N = 50.0
[set.load]
force_N = [{thrust}, 0.0, 0.0]
""",
    )


def test_a_bearing_unloaded_by_the_load_is_a_warning_not_an_error():
    """A thrust far above the preload lifts the opposed bearing off its balls at rest (a DB pair
    unloads its second bearing at about 2.8 times the preload): the result says so."""
    ds = solve(_db_with_thrust(0.0, 600.0))
    assert ds["bearing_axial_load"].values[1] == 0.0
    found = set_result_warnings(ds)
    assert any(m.startswith("bearing 2 carries no load at rest") for m in found), found
    assert any("at rest under the case's loads" in m and "bearing 2" in m for m in found), found


def test_preload_lost_at_speed_is_named_and_a_fixed_position_preload_rises_with_speed():
    """With rigid rings the balls' centrifugal forces raise a fixed-position preload with speed;
    a thrust beyond what the preload holds still unloads the opposed bearing at speed."""
    rest = solve(_db_with_thrust(0.0, 100.0))
    fast = solve(_db_with_thrust(40000.0, 100.0))
    assert set_result_warnings(rest) == [] and set_result_warnings(fast) == []
    assert fast["bearing_axial_load"].values[1] > rest["bearing_axial_load"].values[1] > 0.0
    lost = solve(_db_with_thrust(20000.0, 3000.0))
    assert lost["bearing_axial_load"].values[1] == 0.0
    found = set_result_warnings(lost)
    assert any(m.startswith("bearing 2 carries no load at speed") for m in found), found
