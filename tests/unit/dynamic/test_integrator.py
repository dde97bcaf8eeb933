"""Integrator: accuracy against a tighter run, divergence detection (NaN, ball escape)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.models.dynamic import layout as L
from solver.models.dynamic.integrate import METHODS
from solver.models.dynamic.integrate.control import STATUS_BALL_ESCAPED, STATUS_NOT_FINITE
from solver.models.dynamic.kernels import post_step
from solver.models.dynamic.params import drive_at_start
from solver.models.dynamic.simulate import state_scales
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import advance, integrate_states, start


def test_local_error_control_converges():
    """Deflection-scale error after 0.2 shaft revolution: tolerance 1e-4 agrees with a 1e-8
    reference to a small fraction of the deflection, and 1e-2 is visibly worse (the control
    works)."""
    history, par, quad, y0 = start(spindle_inputs(radial=300.0))
    period = 2 * math.pi / drive_at_start(history).inner_speed
    times = np.array([0.0, 0.2 * period])
    ref, _ = integrate_states(history, par, quad, y0, times, tolerance=1e-8)
    scale = state_scales(history, par, y0)
    errors = {}
    for tol in (1e-2, 1e-4):
        run, _ = integrate_states(history, par, quad, y0, times, tolerance=tol)
        pos = [L.ball_base(j) + k for j in range(18) for k in range(3)]
        errors[tol] = np.abs(run[-1, pos] - ref[-1, pos]).max() / scale[0]
    assert errors[1e-4] < 0.01  # below 1 % of the largest deflection
    assert errors[1e-2] > 3 * errors[1e-4]


def test_ball_escape_is_detected():
    history, par, quad, y0 = start(spindle_inputs())
    z = 18
    rec = np.zeros((z, L.N_CONTACT_RECORD))
    y = y0.copy()
    assert post_step(y, par, rec, rec)
    b = L.ball_base(5)
    y[b + 1 : b + 3] *= 1.0 + 0.3 * par.ball_diameter / (0.5 * par.pitch_diameter)
    assert not post_step(y, par, rec, rec)


def test_non_finite_state_stops_with_status():
    history, par, quad, y0 = start(spindle_inputs())
    y = y0.copy()
    y[L.ball_base(2) + L.B_VEL] = np.nan
    scale = state_scales(history, par, y0)
    out = np.empty((1, y.shape[0]))
    for method in METHODS:
        progress = advance(
            method, history, par, quad, y.copy(), [1e-5], out, 1e-4, 1e-7, 1e-12, 1000, scale
        )
        assert progress["status"] == STATUS_NOT_FINITE and progress["written"] == 0, method


def test_escape_status_from_advance():
    """A ball thrown outwards at 50 m/s leaves the raceways within microseconds: the integrator
    returns STATUS_BALL_ESCAPED instead of integrating garbage (traction/cage off so nothing else
    intervenes first)."""
    history, par, quad, y0 = start(spindle_inputs(), traction=False, cage=False, damping_ratio=0.0)
    y = y0.copy()
    b = L.ball_base(0)
    par = par._replace(eprime=par.eprime * 1e-6)  # a soft race lets the ball through
    y[b + L.B_VEL + 1] += 50.0
    scale = state_scales(history, par, y0)
    out = np.empty((1, y.shape[0]))
    for method in METHODS:
        progress = advance(
            method, history, par, quad, y.copy(), [1e-3], out, 1e-4, 1e-8, 1e-16, 10**7, scale
        )
        assert progress["status"] == STATUS_BALL_ESCAPED, method


def test_steps_end_on_event_times_and_never_pass_them():
    """Every method lands exactly on each time of ``StepControl.event_times`` and no accepted step
    passes one (one step per call, the time reached recorded after each); without events the
    steps pass them."""
    from solver.models.dynamic.integrate import stepper
    from solver.models.dynamic.integrate.control import STATUS_OK, step_control
    from solver.models.dynamic.integrate.model import bearing_model

    history, par, quad, y0 = start(spindle_inputs())
    scale = state_scales(history, par, y0)
    h0 = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    t_end = 60.0 * h0
    events = t_end * np.array([0.3141, 0.6789])

    def reached_times(method, event_times):
        method = stepper(method)
        model = bearing_model(history, par, quad)
        y = y0.copy()
        work = method.workspace(model, y.shape[0], 0.0, h0)
        control = step_control(1e-4, scale, 1e-6 * h0, 1, event_times)
        out = np.empty((1, y.shape[0]))
        reached = [0.0]
        for _ in range(1000):
            method.advance(y, np.array([t_end]), out, control, work, model)
            if work.progress[0]["t"] != reached[-1]:
                reached.append(float(work.progress[0]["t"]))
            if work.progress[0]["status"] == STATUS_OK:
                return np.array(reached)
        raise AssertionError("did not reach the end")

    for method in METHODS:
        with_events = reached_times(method, events)
        assert with_events[-1] == t_end
        for event in events:
            assert event in with_events, method  # a step ends exactly on it
            assert not np.any((with_events[:-1] < event) & (with_events[1:] > event)), method
        free = reached_times(method, ())
        assert not any(event in free for event in events), method


def test_event_times_must_increase():
    from solver.models.dynamic.integrate.control import step_control

    with pytest.raises(ValueError, match="strictly increasing"):
        step_control(1e-4, np.ones(3), 1e-9, 10, [2.0, 1.0])
