"""Integrator: accuracy against a tighter run, divergence detection (NaN, ball escape)."""

from __future__ import annotations

import math

import numpy as np

from solver.models.dynamic import layout as L
from solver.models.dynamic.integrator import (
    STATUS_BALL_ESCAPED,
    STATUS_NOT_FINITE,
    advance,
)
from solver.models.dynamic.kernels import post_step
from solver.models.dynamic.simulate import state_scales
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import integrate_states, start


def test_local_error_control_converges():
    """Deflection-scale error after 0.2 shaft revolution: tolerance 1e-4 agrees with a 1e-8
    reference to a small fraction of the deflection, and 1e-2 is visibly worse (the control
    works)."""
    par, quad, y0 = start(spindle_inputs(radial=300.0))
    period = 2 * math.pi / par.inner_speed
    times = np.array([0.0, 0.2 * period])
    ref, _ = integrate_states(par, quad, y0, times, tolerance=1e-8)
    scale = state_scales(par, y0)
    errors = {}
    for tol in (1e-2, 1e-4):
        run, _ = integrate_states(par, quad, y0, times, tolerance=tol)
        pos = [L.ball_base(j) + k for j in range(18) for k in range(3)]
        errors[tol] = np.abs(run[-1, pos] - ref[-1, pos]).max() / scale[0]
    assert errors[1e-4] < 0.01  # below 1 % of the largest deflection
    assert errors[1e-2] > 3 * errors[1e-4]


def test_ball_escape_is_detected():
    par, quad, y0 = start(spindle_inputs())
    z = 18
    rec = np.zeros((z, L.N_CONTACT_RECORD))
    y = y0.copy()
    assert post_step(y, par, rec, rec)
    b = L.ball_base(5)
    y[b + 1 : b + 3] *= 1.0 + 0.3 * par.ball_diameter / (0.5 * par.pitch_diameter)
    assert not post_step(y, par, rec, rec)


def test_non_finite_state_stops_with_status():
    par, quad, y0 = start(spindle_inputs())
    y = y0.copy()
    y[L.ball_base(2) + L.B_VEL] = np.nan
    z = 18
    scale = state_scales(par, y0)
    out = np.empty((1, y.shape[0]))
    status, t, h, n = advance(
        y,
        0.0,
        1e-7,
        np.array([1e-5]),
        out,
        par,
        quad,
        scale,
        1e-4,
        1e-12,
        1000,
        np.zeros(3, dtype=np.int64),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros(z),
    )
    assert status == STATUS_NOT_FINITE and n == 0


def test_escape_status_from_advance():
    """A ball thrown outwards at 50 m/s leaves the raceways within microseconds: the integrator
    returns STATUS_BALL_ESCAPED instead of integrating garbage (traction/cage off so nothing else
    intervenes first)."""
    par, quad, y0 = start(spindle_inputs(), traction=False, cage=False, damping_ratio=0.0)
    y = y0.copy()
    b = L.ball_base(0)
    par = par._replace(eprime=par.eprime * 1e-6)  # a soft race lets the ball through
    y[b + L.B_VEL + 1] += 50.0
    z = 18
    scale = state_scales(par, y0)
    out = np.empty((1, y.shape[0]))
    status, *_ = advance(
        y,
        0.0,
        1e-8,
        np.array([1e-3]),
        out,
        par,
        quad,
        scale,
        1e-4,
        1e-16,
        10_000_000,
        np.zeros(3, dtype=np.int64),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros(z),
    )
    assert status == STATUS_BALL_ESCAPED
