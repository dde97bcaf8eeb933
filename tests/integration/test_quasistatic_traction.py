"""The quasi-static model with the ball speeds from the traction balance
(solver.models.quasistatic.traction_balance): moment and cage balances from the outputs, the
low-speed limit, the fall-back to race control, and (slow) the comparison with the dynamic model at
steady state that made it the default (docs/quasistatic-traction.md)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import solver
from solver.catalogue import resolve_case
from solver.inputs import rpm_to_rad_s, to_inputs
from solver.models.quasistatic import kernels, solve_operating_point, solve_quasistatic_state
from solver.models.quasistatic import traction_balance as balance_module
from solver.models.quasistatic.solver import _fixed_point_settled, _Problem
from solver.models.quasistatic.traction_balance import traction_balance, traction_setup


@pytest.fixture(scope="module")
def combined():
    inputs = to_inputs(resolve_case("spindle-combined-load"))
    return inputs, solve_operating_point(
        inputs.geometry, inputs.operating, traction_lubricant=inputs.lubricant
    )


def test_transverse_tractions_supply_the_gyroscopic_moment(combined):
    """About e_theta only the transverse frictions act (the rolling tractions lie along e_theta,
    the spin moments about the contact normals in the meridian plane): rho_i tau_i + rho_o tau_o =
    M_g, with rho = D/2 - delta/2 from the ball centre to the contact. Left to the tractions, the
    split is near even (lambda_i ~ 0.9, lambda_o ~ 1.1), not the (0, 2) of outer-race control."""
    inputs, sol = combined
    assert set(sol.race_control) == {"traction"} and sol.ball_speeds == "traction"
    D = inputs.geometry.ball_diameter
    reach = 0.5 * D - 0.5 * sol.contact_deflection
    moment = np.sum(reach * sol.race_traction, axis=1)
    # residual: the normal components of the tractions on the curved contact surface
    np.testing.assert_allclose(moment, sol.gyroscopic_moment, rtol=5e-3)
    lam = sol.race_traction * D / sol.gyroscopic_moment[:, None]
    assert np.all((lam[:, 0] > 0.7) & (lam[:, 0] < 1.0) & (lam[:, 1] > 1.0) & (lam[:, 1] < 1.3))


def test_one_cage_speed_and_pocket_forces_in_balance(combined):
    """Every ball orbits at the cage speed, and the traction balance's pocket forces sum to zero
    (the cage is in equilibrium) while each ball's is not zero under the radial load."""
    inputs, sol = combined
    assert np.ptp(sol.orbital_speed) == 0.0  # one orbital speed for every ball
    # the cage speed is their mean: equal but for the rounding of the mean (the host's vector
    # width decides the order of the sum)
    np.testing.assert_allclose(sol.orbital_speed, sol.cage_speed, rtol=4 * np.finfo(float).eps)
    problem = _Problem(inputs.geometry, inputs.operating)
    model = problem.model(1.0)
    q = np.concatenate([sol.inner_ring_offset, sol.inner_ring_tilt])
    control = kernels.race_control_rows(np.zeros(problem.azimuth.size, dtype=bool))
    states = kernels.evaluate_balls(q, problem.azimuth, sol.ball_position, control, model)
    curve, nodes = traction_setup(inputs.lubricant)
    out, pocket = traction_balance(
        inputs.geometry, model, states, sol.ball_position, q, problem.azimuth, control, curve, nodes
    )
    assert np.max(np.abs(pocket)) > 0.01  # N: the radial load makes the balls push the cage
    assert abs(pocket.sum()) < 1e-6 * np.max(np.abs(pocket))
    # from the converged positions the balance returns the solution's own cage speed
    assert out[0, kernels.CONTROL_ORBITAL] == pytest.approx(sol.cage_speed, rel=1e-7)


def test_low_speed_limit_is_rolling_kinematics():
    """At 2 000 rpm the gyroscopic moment is small and both contacts nearly roll: the traction
    balance and race control give the same cage speed and contact angles."""
    inputs = to_inputs(resolve_case("spindle-combined-load"))
    op = dataclasses.replace(inputs.operating, inner_ring_speed=rpm_to_rad_s(2000.0))
    race = solve_operating_point(inputs.geometry, op)
    balance = solve_operating_point(inputs.geometry, op, traction_lubricant=inputs.lubricant)
    assert balance.cage_speed == pytest.approx(race.cage_speed, rel=2e-3)
    np.testing.assert_allclose(balance.contact_angle, race.contact_angle, atol=np.radians(0.05))


def test_without_a_steady_balance_race_control_is_used_and_said():
    """218 heavy combined load with the ADORE slip curve: the most loaded balls' tractions reach
    the falling branch of the traction curve and no cage speed balances them; asked for the
    traction balance, the result uses race control and says so."""
    case = resolve_case("218-heavy-combined")
    ds = solver.solve_quasistatic(
        case.with_values(
            {
                "simulation.quasistatic_ball_speeds": "traction",
                "lubricant.traction_model": "slip_curve",
            }
        )
    )
    assert ds.attrs["kinematics"] == "race_control"
    assert "no steady ball speeds" in ds.attrs["kinematics_note"]
    assert set(ds.race_control.values) <= {"inner", "outer"}
    warnings = ds.racetrace.warnings()
    assert any(w.startswith("quasi-static ball speeds: the traction balance") for w in warnings)


def test_the_isothermal_rheology_balances_the_heavy_case():
    """The shipped 218 heavy case (the default oil's rheology, the default traction balance) with
    an isothermal film (lubricant.thermal_softening = false): the film's traction stays at its
    limiting shear stress, holds the most loaded balls, the balance has a steady solution and no
    result warning is given."""
    case = resolve_case("218-heavy-combined")
    assert case.lubricant.traction_model == "rheology"
    assert case.simulation.quasistatic_ball_speeds == "traction"
    ds = solver.solve_quasistatic(case.with_values({"lubricant.thermal_softening": False}))
    assert ds.attrs["kinematics"] == "traction"
    assert ds.racetrace.warnings() == []
    assert 0.4 < float(ds.cage_speed) / rpm_to_rad_s(10000.0) < 0.5


def test_thermal_softening_leaves_the_heavy_case_spin_without_a_steady_balance():
    """With the film's thermal softening (the default, docs/traction.md) the spin tractions of the
    218 heavy case's most loaded ball reach the falling branch of the softened traction law: the
    balance finds no steady ball speeds, says why, and the result uses race control with a
    warning (docs/quasistatic-traction.md)."""
    case = resolve_case("218-heavy-combined")
    assert case.lubricant.thermal_softening
    ds = solver.solve_quasistatic(case)
    assert ds.attrs["kinematics"] == "race_control"
    assert "falling branch of the traction law" in ds.attrs["kinematics_note"]
    warnings = ds.racetrace.warnings()
    assert any(w.startswith("quasi-static ball speeds: the traction balance") for w in warnings)


def test_the_case_switch_selects_race_control():
    case = resolve_case("spindle-combined-load")
    race = case.with_values({"simulation.quasistatic_ball_speeds": "race_control"})
    assert set(solve_quasistatic_state(race).race_control) == {"outer"}
    assert set(solve_quasistatic_state(case).race_control) == {"traction"}


@pytest.mark.parametrize(
    ("name", "values"),
    [
        ("spindle-combined-load", {}),
        # with the film's thermal softening the heavy case's most loaded ball has no steady
        # spin at the bracket's cage speeds (test_thermal_softening_leaves_...); its isothermal
        # film balances
        ("218-heavy-combined", {"lubricant.thermal_softening": False}),
    ],
)
def test_joint_newton_lands_on_the_bracketed_balance(name, values, monkeypatch):
    """The first traction balance (from the race-control solution, the farthest start) is solved
    by the joint Newton on the balls' spins and the cage speed without its fall-back, and gives
    the balance that the fall-back (cage speed bracketed and found by Brent's method, each ball
    solved on its own) gives: the same cage speed, spins, attitudes and pocket forces within the
    solvers' tolerances."""
    inputs = to_inputs(resolve_case(name).with_values(values))
    problem = _Problem(inputs.geometry, inputs.operating)
    model = problem.model(1.0)
    race = solve_operating_point(inputs.geometry, inputs.operating)
    q = np.concatenate([race.inner_ring_offset, race.inner_ring_tilt])
    control = kernels.race_control_rows(np.asarray(race.race_control) == "inner")
    states = kernels.evaluate_balls(q, problem.azimuth, race.ball_position, control, model)
    curve, nodes = traction_setup(inputs.lubricant)
    args = (inputs.geometry, model, states, race.ball_position, q, problem.azimuth, control)
    fallbacks = []
    pocket_force_sum = balance_module.pocket_force_sum

    def counted(*a):
        fallbacks.append(a[0])
        return pocket_force_sum(*a)

    monkeypatch.setattr(balance_module, "pocket_force_sum", counted)
    joint, joint_pocket = traction_balance(*args, curve, nodes)
    assert fallbacks == []
    monkeypatch.setattr(balance_module, "solve_balance", lambda w, omega_c, *a: (omega_c, False))
    bracketed, bracketed_pocket = traction_balance(*args, curve, nodes)
    assert len(fallbacks) > 2  # the bracket and Brent's method ran
    ring = abs(inputs.operating.inner_ring_speed - inputs.operating.outer_ring_speed)
    cage = kernels.CONTROL_ORBITAL
    assert joint[0, cage] == pytest.approx(bracketed[0, cage], rel=1e-9)
    assert joint[0, cage] != pytest.approx(race.cage_speed, rel=1e-4)  # it moved from the start
    spin, attitude = kernels.CONTROL_SPIN, kernels.CONTROL_ATTITUDE
    np.testing.assert_allclose(joint[:, spin], bracketed[:, spin], rtol=0, atol=1e-8 * ring)
    np.testing.assert_allclose(joint[:, attitude], bracketed[:, attitude], rtol=0, atol=1e-8)
    scale = np.max(np.abs(bracketed_pocket))
    np.testing.assert_allclose(joint_pocket, bracketed_pocket, rtol=0, atol=1e-6 * scale)


def test_joint_newton_gives_up_when_its_merit_stalls(monkeypatch):
    """The shipped 218 heavy case (thermal softening): the joint Newton's merit crawls (0.16 to
    0.12 in 10 steps) and it never converges. It gives up after STALL_WINDOW steps, not after
    MAX_BALANCE_ITERATIONS; the fall-back then finds no balance and says why, as before."""
    inputs = to_inputs(resolve_case("218-heavy-combined"))
    problem = _Problem(inputs.geometry, inputs.operating)
    model = problem.model(1.0)
    race = solve_operating_point(inputs.geometry, inputs.operating)
    q = np.concatenate([race.inner_ring_offset, race.inner_ring_tilt])
    control = kernels.race_control_rows(np.asarray(race.race_control) == "inner")
    states = kernels.evaluate_balls(q, problem.azimuth, race.ball_position, control, model)
    curve, nodes = traction_setup(inputs.lubricant)
    steps = []
    balance_step = balance_module._balance_step

    def counted(*a):
        steps.append(1)
        return balance_step(*a)

    # the Python body of the jitted solve, calling the jitted steps through the module (counted)
    monkeypatch.setattr(balance_module, "_balance_step", counted)
    monkeypatch.setattr(balance_module, "solve_balance", balance_module.solve_balance.py_func)
    args = (inputs.geometry, model, states, race.ball_position, q, problem.azimuth, control)
    with pytest.raises(balance_module.BalanceFailed, match="falling branch"):
        traction_balance(*args, curve, nodes)
    assert balance_module.STALL_WINDOW <= len(steps) <= balance_module.STALL_WINDOW + 2
    assert len(steps) < balance_module.MAX_BALANCE_ITERATIONS


def test_fixed_point_stops_on_its_distance_to_the_limit():
    """The traction fixed point stops when its last change (in tolerances) is within the
    tolerance, or when the contraction of the last changes puts the limit within it."""
    assert _fixed_point_settled([1e3, 10.0, 0.9])  # the last change is within the tolerance
    # contracting by 1/100: the limit is 0.5 tolerances beyond the last change of 50
    assert _fixed_point_settled([1e6, 1e4, 50.0])
    assert not _fixed_point_settled([1e3, 1e2, 10.0])  # by 1/10: still 1.1 tolerances to go
    assert not _fixed_point_settled([1e2, 90.0, 2.0])  # one slow ratio: no estimate
    assert not _fixed_point_settled([1e10, 1e7, 500.0])  # too large a change to extrapolate
    assert not _fixed_point_settled([5.0, 2.0])  # two changes: one ratio only


def _dynamic_track(ds, race):
    """Bin medians (36 bins) of the steady contact angle against the ball azimuth in space."""
    from solver.results.summary import analysis_start

    first, state = analysis_start(ds)
    assert state.settled
    window = ds.isel(time=slice(first, None))
    azimuth = np.mod(window.ball_azimuth.values, 360.0).ravel()
    angle = window.contact_angle.sel(race=race).transpose("ball", "time").values.ravel()
    index = np.minimum((azimuth // 10.0).astype(int), 35)
    medians = np.array([np.median(angle[index == b]) for b in range(36)])
    return np.arange(36) * 10.0 + 5.0, medians


@pytest.mark.slow
def test_traction_balance_matches_the_dynamic_steady_state():
    """spindle-combined-load, 12 shaft revolutions (settles after 6): the quasi-static contact
    angles of the traction balance lie on the dynamic model's steady track (measured RMS 0.010 deg
    inner, 0.013 deg outer; race control 0.32 / 0.47 deg), and so do its contact-angle ranges
    (0.991 / 1.108 deg against 0.985 / 1.101 deg; race control 1.166 / 1.332 deg) and cage speed
    (914.95 against 914.80 rad/s; race control 916.59)."""
    case = resolve_case("spindle-combined-load")
    ds = solver.simulate(case.with_values({"simulation.shaft_revolutions": 12.0}))
    race_case = case.with_values({"simulation.quasistatic_ball_speeds": "race_control"})
    traction = solver.solve_quasistatic(case)
    race = solver.solve_quasistatic(race_case)
    for name in ("inner", "outer"):
        centres, track = _dynamic_track(ds, name)
        dyn_range = np.ptp(track)
        for qs, rms_limit, range_tol in ((traction, 0.05, 0.02), (race, None, None)):
            angle = qs.contact_angle.sel(race=name).values
            expected = np.interp(qs.ball_azimuth.values, centres, track, period=360.0)
            rms = float(np.sqrt(np.mean((angle - expected) ** 2)))
            if rms_limit is not None:
                assert rms < rms_limit, (name, rms)
                assert np.ptp(angle) == pytest.approx(dyn_range, rel=range_tol)
            else:
                assert rms > 0.2, (name, rms)  # race control: a few tenths of a degree off
                assert np.ptp(angle) > 1.1 * dyn_range
    cage = float(ds.cage_speed.isel(time=slice(-360, None)).mean())
    assert float(traction.cage_speed) == pytest.approx(cage, rel=5e-4)


@pytest.mark.slow
def test_rheology_traction_balance_matches_the_rheology_dynamic_steady_state():
    """With lubricant.traction_model = "rheology" the balance uses the oil's rheology like the
    dynamic model. spindle-combined-load, 12 shaft revolutions: the quasi-static contact angles
    lie within 0.08 deg RMS of the dynamic steady track (measured 0.048 inner, 0.063 outer),
    closer than the balance with the slip curve (0.072 / 0.103), and the cage speed within 2e-4
    (914.86 against 914.78 rad/s; with the slip curve 914.95)."""
    case = resolve_case("spindle-combined-load").with_values(
        {"lubricant.traction_model": "rheology"}
    )
    ds = solver.simulate(case.with_values({"simulation.shaft_revolutions": 12.0}))
    rheology = solver.solve_quasistatic(case)
    curve = solver.solve_quasistatic(case.with_values({"lubricant.traction_model": "slip_curve"}))
    for name in ("inner", "outer"):
        centres, track = _dynamic_track(ds, name)
        rms = {}
        for label, qs in (("rheology", rheology), ("curve", curve)):
            angle = qs.contact_angle.sel(race=name).values
            expected = np.interp(qs.ball_azimuth.values, centres, track, period=360.0)
            rms[label] = float(np.sqrt(np.mean((angle - expected) ** 2)))
        assert rms["rheology"] < 0.08, (name, rms)
        assert rms["rheology"] < rms["curve"], (name, rms)
    cage = float(ds.cage_speed.isel(time=slice(-360, None)).mean())
    assert float(rheology.cage_speed) == pytest.approx(cage, rel=2e-4)
    assert abs(float(rheology.cage_speed) - cage) < abs(float(curve.cage_speed) - cage)
