"""Shared setup for dynamic-model unit tests: parameters, quadrature and the initial state."""

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
    quad = build_quadrature(options)
    return par, quad, options


def evaluate(y, par, quad):
    """(dydt, inner records, outer records, pocket forces) at state y."""
    z = int(par[L.P_Z])
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    pocket = np.zeros(z)
    dydt = np.zeros_like(y)
    rhs(y, par, quad, dydt, rec_i, rec_o, pocket)
    return dydt, rec_i, rec_o, pocket


def start(inputs, **option_changes):
    par, quad, options = setup(inputs, **option_changes)
    return par, quad, initial_state(par, quad)
