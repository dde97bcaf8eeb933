"""IMEX additive Runge–Kutta method (solver.models.dynamic.integrate.imex) and the outputs inside a
step of both adaptive methods: tableau order against an independent reference solution, the order
kept with any implicit matrix, the cage-velocity Jacobian against differences of the whole
right-hand side, and short runs against the explicit method."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions, simulate
from solver.models.dynamic import layout as L
from solver.models.dynamic.integrate.imex import ark436l2sa, cage_velocity_jacobian
from solver.models.dynamic.kernels import rhs_into, rhs_work
from solver.models.dynamic.params import drive_at_start
from solver.models.dynamic.simulate import state_scales
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import evaluate, integrate_states, start


def _problem():
    """A nonlinear, mildly stiff 3-state problem: y' = f(t, y)."""

    def f(t, y):
        return np.array(
            [
                -50.0 * (y[0] - np.cos(t)) + y[1] * y[2],
                -y[1] + 0.5 * np.sin(y[0]),
                -2.0 * y[2] + y[0] * y[1],
            ]
        )

    y0 = np.array([1.0, 0.5, -0.3])
    return f, y0


def _ark_step(tab, f, t, y, h, a_matrix):
    """One step of the additive method in numpy with f_I(Y) = A (Y - y) on every component."""
    ns = tab.b.shape[0]
    n = y.shape[0]
    k = np.zeros((ns, n))
    fi = np.zeros((ns, n))
    c = tab.explicit.sum(axis=1)
    gamma = tab.implicit[1, 1]
    lhs = np.eye(n) - h * gamma * a_matrix
    for s in range(ns):
        if s == 0:
            ys = y
        else:
            rhs_s = y + h * (tab.explicit[s, :s] @ (k[:s] - fi[:s]) + tab.implicit[s, :s] @ fi[:s])
            ys = y + np.linalg.solve(lhs, rhs_s - y)
        fi[s] = a_matrix @ (ys - y)
        k[s] = f(t + c[s] * h, ys)
    return y + h * tab.b @ k, h * tab.e @ k


def _errors(a_matrix, steps_list=(40, 80, 160)):
    f, y0 = _problem()
    t_end = 0.5
    exact = solve_ivp(f, (0.0, t_end), y0, rtol=1e-12, atol=1e-13, method="DOP853").y[:, -1]
    tab = ark436l2sa()
    errors = []
    for steps in steps_list:
        h = t_end / steps
        y = y0.copy()
        for i in range(steps):
            y, _ = _ark_step(tab, f, i * h, y, h, a_matrix)
        errors.append(np.abs(y - exact).max())
    return errors


def test_ark436_is_fourth_order_with_the_stiff_part_implicit():
    a_matrix = np.diag([-50.0, -1.0, -2.0])
    e = _errors(a_matrix)
    orders = np.log2(np.array(e[:-1]) / np.array(e[1:]))
    assert orders.min() > 3.6, orders


def test_ark436_keeps_its_order_with_any_implicit_matrix():
    """The split f = (f - A y) + A y is exact: the order does not depend on A."""
    rng = np.random.default_rng(3)
    a_matrix = -np.eye(3) * 20.0 + rng.normal(size=(3, 3))
    e = _errors(a_matrix)
    orders = np.log2(np.array(e[:-1]) / np.array(e[1:]))
    assert orders.min() > 3.6, orders


def test_embedded_estimate_is_third_order():
    f, y0 = _problem()
    tab = ark436l2sa()
    a_matrix = np.diag([-50.0, -1.0, -2.0])
    est = [np.abs(_ark_step(tab, f, 0.0, y0, h, a_matrix)[1]).max() for h in (0.004, 0.002)]
    assert 3.5 < math.log2(est[0] / est[1]) < 4.5  # local error of order 3 + 1


def test_tableau_weights_and_nodes():
    tab = ark436l2sa()
    c = tab.explicit.sum(axis=1)
    np.testing.assert_allclose(tab.implicit.sum(axis=1), c, atol=1e-15)
    np.testing.assert_allclose(tab.implicit[-1], tab.b)  # stiffly accurate
    assert abs(tab.b.sum() - 1.0) < 1e-15
    assert abs(tab.e.sum()) < 1e-15  # both weights sum to one
    for q in range(1, 5):
        assert abs(tab.b @ c ** (q - 1) - 1.0 / q) < 1e-14


def test_cage_velocity_jacobian_matches_the_whole_right_hand_side():
    """The land and pocket forces are all that the cage's acceleration takes from its velocity:
    the 3 x 3 block equals forward differences of the whole right-hand side."""
    history, par, quad, y0 = start(spindle_inputs(radial=300.0))
    y = y0.copy()
    z = int(par.ball_count)
    cb = L.cage_base(z)
    # push the cage towards its land and a ball into its pocket: land film and pocket contact on
    y[cb + L.C_POS + 1] = 0.9 * par.land_clearance
    y[cb + L.C_VEL + 1] = 0.01
    y[cb + L.C_VEL + 2] = -0.02
    scale = state_scales(history, par, y0)
    dv = 1e-4 * scale[cb + L.C_VEL]
    scratch = rhs_work(int(par.ball_count))
    f0 = np.empty_like(y)
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    rhs_into(y, 0.0, history, par, quad, f0, rec_i, rec_o, np.zeros(z), scratch, True)
    jac = np.zeros((3, 3))
    cage_velocity_jacobian(y, cb, par, scratch, dv, True, np.empty(3), np.empty(3), jac)
    reference = np.zeros((3, 3))
    for c in range(3):
        yp = y.copy()
        yp[cb + L.C_VEL + c] += dv
        fp = evaluate(yp, history, par, quad)[0]
        reference[:, c] = (fp - f0)[cb + L.C_VEL : cb + L.C_VEL + 3] / dv
    assert np.abs(reference).max() > 100.0  # the land film damps the cage: a block worth testing
    np.testing.assert_allclose(jac, reference, rtol=1e-6, atol=1e-6 * np.abs(reference).max())


def test_dopri5_outputs_inside_steps_match_stopping_on_each_output():
    """Continuous extension: states at output times filled inside steps agree with a run that
    stops exactly on every output time, to a small fraction of the deflection scale."""
    history, par, quad, y0 = start(spindle_inputs(radial=300.0))
    period = 2 * math.pi / drive_at_start(history).inner_speed
    times = np.linspace(0.0, 0.05 * period, 13)
    dense, _ = integrate_states(history, par, quad, y0, times, tolerance=1e-6)
    stops = [y0]
    y = y0
    for i in range(1, len(times)):
        part, _ = integrate_states(history, par, quad, y, times[i - 1 : i + 1] - times[i - 1], 1e-6)
        y = part[-1]
        stops.append(y)
    scale = state_scales(history, par, y0)
    pos = [L.ball_base(j) + k for j in range(int(par.ball_count)) for k in range(3)]
    diff = np.abs(dense[:, pos] - np.array(stops)[:, pos]).max() / scale[0]
    assert diff < 1e-3
    # and the samples are not all equal to the end state (they were filled, not copied)
    assert np.abs(dense[5, pos] - dense[-1, pos]).max() > 10 * diff * scale[0]


@pytest.mark.parametrize(("method", "chunk"), [("imex", 1), ("imex", 60), ("auto", 60)])
def test_imex_run_agrees_with_dopri5(method, chunk):
    """A short spindle run with the IMEX and switching methods (outputs from a step end with
    chunk_samples = 1, by interpolation with 60) against the explicit method at a tight
    tolerance."""
    options = dict(shaft_revolutions=0.1, samples_per_revolution=60, chunk_samples=chunk)
    inputs = spindle_inputs(radial=300.0)
    ref = simulate(inputs, options=SimulationOptions(method="dopri5", tolerance=1e-6, **options))
    run = simulate(inputs, options=SimulationOptions(method=method, tolerance=1e-4, **options))
    assert run.attrs["complete"] == 1
    assert "ARK4(3)6L[2]SA" in run.attrs["integrator"]
    load = np.abs(run["contact_load"] - ref["contact_load"]).max()
    assert float(load) < 2e-3 * float(np.abs(ref["contact_load"]).max())
    angle = np.abs(run["contact_angle"] - ref["contact_angle"]).max()
    assert float(angle) < 0.005


def test_auto_takes_fewer_steps_than_dopri5_where_the_land_film_is_stiff():
    """218 heavy case with the rheology traction law from its quasi-static start: the cage runs
    in its guiding land's film (docs/numerics.md: the film's damping sets the explicit step);
    there the switching method takes additive steps and needs fewer steps and rejections than the
    explicit method, with the same loads (0.5 revolution at the default tolerance 1e-4 with the
    thermally softened traction: 348 against 446; at 1e-3 with the isothermal film the two took
    415 and 830)."""
    inputs = to_inputs(resolve_case("218-heavy-combined"))
    lubricant = replace(inputs.lubricant, traction_model="rheology")
    inputs = replace(inputs, lubricant=lubricant)
    options = dict(shaft_revolutions=0.5, samples_per_revolution=60)
    runs = {
        m: simulate(inputs, options=SimulationOptions(method=m, **options))
        for m in ("dopri5", "auto")
    }
    steps = {m: ds.attrs["steps"] + ds.attrs["rejected_steps"] for m, ds in runs.items()}
    assert steps["auto"] < 0.85 * steps["dopri5"], steps
    load = runs["dopri5"]["contact_load"]
    diff = np.abs(runs["auto"]["contact_load"] - load).max()
    # 1.5 %: the explicit run, near its stability limit here (rejected steps), moves its loads by
    # up to 0.5 % of the largest load when the right-hand side changes by rounding alone
    # (measured: 19 N of 4315 N, derivatives within 1e-14 relative); the additive method's move by
    # 3e-4 N. Between the methods: 0.9-1.1 %.
    assert float(diff) < 0.015 * float(np.abs(load).max())
