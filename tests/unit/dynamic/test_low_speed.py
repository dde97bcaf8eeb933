"""The dynamic model at vanishing entrainment speed (docs/numerics.md, "Low entrainment speed"):
below u_min the contacts keep the film and transit time of u_min, so the traction of the rheology
stays a finite, continuous function of the speeds down to rest; the reported film and the inlet
rolling force keep their own speed laws; a bearing at rest under load integrates without NaN."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from solver.errors import CaseError
from solver.history import CH_INNER_SPEED, CH_OUTER_SPEED
from solver.models.dynamic import SimulationOptions, simulate
from solver.models.dynamic import layout as L
from solver.models.dynamic.params import drive_at_start
from solver.physics.rheology import ENTRAINMENT_FLOOR
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import evaluate, integrate_states, start


def _at_speed(inputs, rpm: float):
    op = dataclasses.replace(inputs.operating, inner_ring_speed=rpm * math.pi / 30.0)
    return dataclasses.replace(inputs, operating=op)


@pytest.fixture(scope="module")
def rheology_bearing():
    """The test spindle (the default oil: rheology traction) at 20 000 rpm under 500 N preload:
    parameters, quadrature and its initial state."""
    inputs = spindle_inputs(axial=500.0)
    assert inputs.lubricant.traction_model == "rheology"
    return start(inputs)


def _scaled(history, par, y0, factor):
    """Operating history and state with every speed (rings, balls, cage) times ``factor``: the
    same contact geometry and loads, every slip and entrainment speed times ``factor``."""
    values = history.values.copy()
    values[[CH_INNER_SPEED, CH_OUTER_SPEED]] *= factor
    z = int(par.ball_count)
    y = y0.copy()
    for j in range(z):
        b = L.ball_base(j)
        y[b + L.B_VEL : b + L.B_VEL + 3] *= factor
        y[b + L.B_OMEGA : b + L.B_OMEGA + 3] *= factor
    y[L.cage_base(z) + L.C_SPEED] *= factor
    return history._replace(values=values), y


def _inner_contact(history, par, quad, y0, factor):
    """(tangential force on ball 0 at the inner race [N, inertial], film [m], entrainment
    [m/s]) of one right-hand-side evaluation with every speed times ``factor``."""
    history, y = _scaled(history, par, y0, factor)
    _, rec_i, _, _ = evaluate(y, history, par, quad)
    r = rec_i[0]
    n = r[L.K_NORMAL : L.K_NORMAL + 3]
    force = r[L.K_F_BALL : L.K_F_BALL + 3]
    return force - np.dot(force, n) * n, r[L.K_FILM], r[L.K_ENTRAIN]


def test_the_rheology_traction_goes_to_zero_with_the_speeds_linearly_below_the_floor(
    rheology_bearing,
):
    history, par, quad, y0 = rheology_bearing
    factors = np.logspace(-8, 0, 49)
    forces, films, speeds = [], [], []
    for factor in factors:
        force, film, speed = _inner_contact(history, par, quad, y0, factor)
        forces.append(force)
        films.append(film)
        speeds.append(speed)
    forces, films, speeds = np.array(forces), np.array(films), np.array(speeds)
    assert np.isfinite(forces).all() and np.isfinite(films).all()
    assert speeds[0] < 1e-6 < ENTRAINMENT_FLOOR < speeds[-1]
    # every slip is proportional to the factor, and below u_min the law is the one of u_min,
    # linear at small slips (the first 8 factors: slips below about 1e-7 of the running ones):
    # force / factor is one vector there. Without the floor the film vanishes with the speed,
    # the law's slope grows as the film thins and the force saturates at the limiting shear
    # stress instead.
    small = factors < 3e-7
    assert small.sum() >= 8 and (speeds[small] < 0.1 * ENTRAINMENT_FLOOR).all()
    per_factor = forces[small] / factors[small, None]
    np.testing.assert_allclose(
        per_factor, np.broadcast_to(per_factor[0], per_factor.shape), rtol=1e-3, atol=1e-6
    )
    assert np.linalg.norm(forces[0]) < 1e-4 * np.abs(forces).max()  # 3e-5 at a factor 1e-8
    # no jump: between neighbouring factors (1.47x apart) the force changes by less than that
    ratio = np.linalg.norm(forces[1:], axis=1) / np.linalg.norm(forces[:-1], axis=1)
    assert (ratio < 1.5).all() and (ratio > 0.5).all()
    # the film reported keeps the Hamrock-Dowson law of the contact's own speed, and the force
    # and film are continuous through the floor
    film_running, speed_running = films[-1], speeds[-1]
    floor = ENTRAINMENT_FLOOR / speed_running  # the factor that puts the speed at the floor
    _, film_a, speed_a = _inner_contact(history, par, quad, y0, 0.5 * floor)
    _, film_b, speed_b = _inner_contact(history, par, quad, y0, 0.5e-3 * floor)
    assert speed_a < ENTRAINMENT_FLOOR
    # (to 1e-4: the inlet thermal reduction of u_min reads the slide-to-roll ratio)
    assert film_b / film_a == pytest.approx((speed_b / speed_a) ** 0.67, rel=1e-4)
    # continuous through the floor: just below and just above it
    under = _inner_contact(history, par, quad, y0, floor * (1.0 - 1e-9))
    over = _inner_contact(history, par, quad, y0, floor * (1.0 + 1e-9))
    assert under[2] < ENTRAINMENT_FLOOR < over[2]
    assert under[1] == pytest.approx(over[1], rel=1e-6)
    np.testing.assert_allclose(under[0], over[0], rtol=1e-6, atol=1e-9)
    assert 0.0 < film_a < film_running


def test_a_bearing_at_rest_under_load_stays_put_and_feels_no_friction_jump():
    """The spindle (rheology) at rest under its 500 N preload and gravity: 0.1 ms from its
    equilibrium (about 2 200 steps: at rest the traction's slope at u_min sets the step), and a
    ball turning by a few nm/s at its contacts feels a traction in proportion (without the
    floor, a contact at rest has no film, and any slip above 1 nm/s met the full limiting shear
    stress: a jump of about 0.07 of the load at zero slip)."""
    history, par, quad, y0 = start(_at_speed(spindle_inputs(axial=500.0), 0.0))
    times = np.linspace(0.0, 1e-4, 6)
    states, progress = integrate_states(
        history, par, quad, y0, times, tolerance=1e-4, method="auto"
    )
    assert np.isfinite(states).all()
    z = int(par.ball_count)
    assert np.abs(states[:, L.cage_base(z) + L.C_SPEED]).max() < 1e-6  # rad/s: nothing drives it
    _, rec_i, rec_o, _ = evaluate(states[-1], history, par, quad)
    loads = np.concatenate((rec_i[:, L.K_LOAD], rec_o[:, L.K_LOAD]))
    assert loads.min() > 0.0  # every ball still held by the preload
    assert int(progress["accepted"]) < 3000
    forces = []
    for spin in (1e-6, 2e-6):  # rad/s about the bearing axis: slips of 3.6 and 7.2 nm/s
        y = y0.copy()
        y[L.ball_base(0) + L.B_OMEGA] = spin
        force, _, _ = _inner_contact(history, par, quad, y, 1.0)
        forces.append(np.linalg.norm(force))
    load = evaluate(y0, history, par, quad)[1][0, L.K_LOAD]
    assert 0.0 < forces[0] < 1e-3 * load
    assert forces[1] == pytest.approx(2.0 * forces[0], rel=1e-3)


def test_a_run_at_one_rpm_with_load_stays_finite_and_rolling():
    """The spindle (rheology) at 1 rpm, every contact below u_min: 0.1 ms; the regularised law
    costs fewer steps than the vanishing film did."""
    history, par, quad, y0 = start(_at_speed(spindle_inputs(axial=500.0), 1.0))
    times = np.linspace(0.0, 1e-4, 6)
    states, progress = integrate_states(
        history, par, quad, y0, times, tolerance=1e-4, method="auto"
    )
    assert np.isfinite(states).all()
    cage = states[:, L.cage_base(int(par.ball_count)) + L.C_SPEED]
    assert cage[-1] == pytest.approx(cage[0], rel=0.01)  # the rolling speed, about half the shaft's
    inner_speed = drive_at_start(history).inner_speed
    assert 0.4 * inner_speed < cage[0] < 0.5 * inner_speed
    assert int(progress["accepted"]) < 3000  # 2 340 (without the floor: 5 141)


def test_a_steady_case_at_rest_is_refused_with_a_pointer_to_a_history():
    inputs = _at_speed(spindle_inputs(axial=500.0), 0.0)
    with pytest.raises(CaseError) as info:
        simulate(inputs, options=SimulationOptions(shaft_revolutions=1.0))
    message = str(info.value)
    assert "turn relative to each other" in message
    assert "simulation.duration_s" in message and "history" in message
