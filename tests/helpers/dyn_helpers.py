"""Shared setup for the dynamic-model tests: operating history, parameters, quadrature and the
initial state."""

from __future__ import annotations

import numpy as np

from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state
from solver.models.dynamic.kernels import rhs
from solver.models.dynamic.options import SimulationOptions
from solver.models.dynamic.params import build_params, build_quadrature, model_history


def setup(inputs, **option_changes):
    """(operating history, parameters, quadrature, options) of ``inputs``."""
    options = SimulationOptions(**option_changes)
    par = build_params(inputs, options)
    quad = build_quadrature(options, par)
    return model_history(inputs), par, quad, options


def evaluate(y, history, par, quad, t=0.0):
    """(dydt, inner records, outer records, pocket forces) at state y and time t [s]."""
    z = int(par.ball_count)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    dydt = np.zeros_like(y)
    rhs(y, float(t), history, par, quad, dydt, rec_i, rec_o, pocket)
    return dydt, rec_i, rec_o, pocket


def start(inputs, **option_changes):
    """(operating history, parameters, quadrature, initial state) of ``inputs``."""
    history, par, quad, options = setup(inputs, **option_changes)
    return history, par, quad, initial_state(history, par, quad)


def advance(
    method,
    history,
    par,
    quad,
    y,
    times,
    outputs,
    tolerance,
    h,
    h_min,
    max_steps,
    scale=None,
    events=(),
):
    """Run the stepper of ``method`` once from t = 0 with first step ``h`` (``y`` updated in place,
    ``outputs`` filled); returns its progress record (solver.models.dynamic.integrate.control)."""
    from solver.models.dynamic.integrate import run
    from solver.models.dynamic.integrate.control import step_control
    from solver.models.dynamic.simulate import state_scales

    if scale is None:
        scale = state_scales(history, par, y)
    control = step_control(tolerance, scale, h_min, max_steps, events)
    return run(method, history, par, quad, y, np.asarray(times, float), outputs, control, h)


def integrate_states(history, par, quad, y0, times, tolerance=1e-3, method="dopri5"):
    """(States at ``times`` (times[0] = 0 is y0) integrated with the stepper of ``method``, its
    progress record)."""
    from solver.models.dynamic.integrate.control import STATUS_OK
    from solver.models.dynamic.simulate import state_scales

    scale = state_scales(history, par, y0)
    y = y0.copy()
    states = np.empty((len(times), y.shape[0]))
    states[0] = y
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    progress = advance(
        method, history, par, quad, y, times[1:], states[1:], tolerance, h, 1e-6 * h, 10**7
    )
    assert progress["status"] == STATUS_OK, progress
    return states, progress
