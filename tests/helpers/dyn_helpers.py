"""Shared setup for the dynamic-model tests: parameters, quadrature and the initial state."""

from __future__ import annotations

import numpy as np

from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state
from solver.models.dynamic.kernels import rhs
from solver.models.dynamic.options import SimulationOptions
from solver.models.dynamic.params import build_params, build_quadrature


def setup(inputs, **option_changes):
    options = SimulationOptions(**option_changes)
    par = build_params(inputs, options)
    quad = build_quadrature(options, par)
    return par, quad, options


def evaluate(y, par, quad):
    """(dydt, inner records, outer records, pocket forces) at state y."""
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    dydt = np.zeros_like(y)
    rhs(y, par, quad, dydt, rec_i, rec_o, pocket)
    return dydt, rec_i, rec_o, pocket


def start(inputs, **option_changes):
    par, quad, options = setup(inputs, **option_changes)
    return par, quad, initial_state(par, quad)


def integrate_states(par, quad, y0, times, tolerance=1e-3):
    """States at ``times`` (times[0] = 0 is y0) integrated with the model's integrator."""
    from solver.models.dynamic.integrator import STATUS_OK, advance
    from solver.models.dynamic.simulate import state_scales

    z = int(par.ball_count)
    scale = state_scales(par, y0)
    y = y0.copy()
    states = np.empty((len(times), y.shape[0]))
    states[0] = y
    counters = np.zeros(3, dtype=np.int64)
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    status, t, h, n = advance(
        y,
        0.0,
        h,
        np.asarray(times[1:], float),
        states[1:],
        par,
        quad,
        scale,
        tolerance,
        1e-6 * h,
        10_000_000,
        counters,
        rec_i,
        rec_o,
        np.zeros(z),
    )
    assert status == STATUS_OK, status
    return states, counters
