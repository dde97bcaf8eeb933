"""Rosenbrock-W integrator: tableau order, block LU against numpy, the arrow Jacobian against
full differences, the arrow solve against a dense solve."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

from solver.models.dynamic import layout as L
from solver.models.dynamic.rosenbrock import (
    MAX_BLOCK,
    block_structure,
    factor_arrow,
    factor_blocks,
    jacobian_arrow,
    ros34pw2,
    rosenbrock_work,
    solve_arrow,
    solve_blocks,
)
from solver.models.dynamic.simulate import state_scales
from tests.helpers.cases import spindle_inputs
from tests.helpers.dyn_helpers import evaluate, start


def _step(tab, f, w, y, h):
    """One step of the transformed form in numpy (the reference of the numba kernel's formulas)."""
    n = y.shape[0]
    ns = tab.m.shape[0]
    lhs = np.eye(n) / (h * tab.gamma) - w
    u = np.zeros((ns, n))
    for s in range(ns):
        rhs = f(y + tab.a[s, :s] @ u[:s]) + (tab.c[s, :s] / h) @ u[:s]
        u[s] = np.linalg.solve(lhs, rhs)
    return y + tab.m @ u, tab.e @ u


def _observed_order(tab, f, w_of, y0, t_end, exact):
    errors = []
    for steps in (20, 40, 80):
        h = t_end / steps
        y = y0.copy()
        for _ in range(steps):
            y, _ = _step(tab, f, w_of(y), y, h)
        errors.append(np.abs(y - exact).max())
    return np.log2(errors[0] / errors[1]), np.log2(errors[1] / errors[2])


def _nonlinear():
    """y' = (-y1 + y2^2, -y2): exact solution known, Jacobian known."""

    def f(y):
        return np.array([-y[0] + y[1] ** 2, -y[1]])

    def jac(y):
        return np.array([[-1.0, 2.0 * y[1]], [0.0, -1.0]])

    y0 = np.array([1.0, 1.0])
    t = 1.0
    # y2 = e^-t, y1 = (y1(0) + y2(0)^2) e^-t - e^-2t
    exact = np.array([2.0 * np.exp(-t) - np.exp(-2 * t), np.exp(-t)])
    return f, jac, y0, t, exact


def test_ros34pw2_is_third_order_with_the_exact_jacobian():
    f, jac, y0, t, exact = _nonlinear()
    orders = _observed_order(ros34pw2(), f, jac, y0, t, exact)
    assert min(orders) > 2.8, orders


def test_ros34pw2_keeps_third_order_with_any_matrix():
    """W-method: the order holds with W = 0 (explicit) and with a wrong matrix."""
    f, jac, y0, t, exact = _nonlinear()
    tab = ros34pw2()
    zero = _observed_order(tab, f, lambda y: np.zeros((2, 2)), y0, t, exact)
    wrong = _observed_order(tab, f, lambda y: 0.5 * jac(y) + 0.3, y0, t, exact)
    assert min(zero) > 2.8 and min(wrong) > 2.8, (zero, wrong)


def test_embedded_error_estimate_is_second_order():
    f, jac, y0, _, _ = _nonlinear()
    tab = ros34pw2()
    est = [np.abs(_step(tab, f, jac(y0), y0, h)[1]).max() for h in (0.02, 0.01)]
    assert 2.7 < np.log2(est[0] / est[1]) < 3.3  # local error of the order-2 solution ~ h^3


def test_stiff_linear_problem_is_damped_at_large_steps():
    """L-stability: a very stiff decaying mode stays bounded and decays at h |lambda| = 1e4."""
    a = np.array([[-1.0e4, 1.0], [0.0, -1.0]])
    tab = ros34pw2()
    y = np.array([1.0, 1.0])
    for _ in range(10):
        y, _ = _step(tab, lambda v: a @ v, a, y, 1.0)
    exact = expm(10.0 * a) @ np.array([1.0, 1.0])
    assert abs(y[0]) < 1e-3 and abs(y[1] - exact[1]) < 1e-3


@pytest.mark.parametrize("sizes", [(13, 13, 12, 12), (3, 13, 1)])
def test_block_lu_matches_numpy(sizes):
    rng = np.random.default_rng(3)
    nb = len(sizes)
    sizes = np.array(sizes, dtype=np.int64)
    starts = np.concatenate(([0], np.cumsum(sizes)[:-1])).astype(np.int64)
    jac = rng.normal(size=(nb, MAX_BLOCK, MAX_BLOCK)) * 1e5
    lu = np.zeros_like(jac)
    piv = np.zeros((nb, MAX_BLOCK), dtype=np.int64)
    diag = 2.0e3
    assert factor_blocks(jac, lu, piv, sizes, diag)
    x = rng.normal(size=int(sizes.sum()))
    got = x.copy()
    solve_blocks(lu, piv, starts, sizes, got)
    for b in range(nb):
        s, m = starts[b], sizes[b]
        mat = diag * np.eye(m) - jac[b, :m, :m]
        np.testing.assert_allclose(got[s : s + m], np.linalg.solve(mat, x[s : s + m]), rtol=1e-9)


def test_singular_block_is_reported():
    jac = np.zeros((1, MAX_BLOCK, MAX_BLOCK))
    jac[0, 0, 0] = 1.0
    ok = factor_blocks(
        jac, np.zeros_like(jac), np.zeros((1, MAX_BLOCK), dtype=np.int64), np.array([2]), 1.0
    )
    assert not ok


def test_ball_blocks_cover_the_ball_slots_once():
    z = 18
    starts, sizes = block_structure(z)
    covered = np.zeros(L.state_size(z), dtype=int)
    for s, m in zip(starts, sizes, strict=True):
        covered[s : s + m] += 1
    nb = L.BALL_STRIDE * z
    assert (covered[:nb] == 1).all() and (covered[nb:] == 0).all()


def test_arrow_jacobian_matches_the_full_difference_jacobian():
    """D, B, C, E of jacobian_arrow against central differences of the whole right-hand side at
    the spindle's start (radial load and cage on: every coupling is active)."""
    par, quad, y = start(spindle_inputs(radial=300.0))
    scale = state_scales(par, y)
    z = int(par.ball_count)
    n = y.shape[0]
    nb = L.BALL_STRIDE * z
    work = rosenbrock_work(z)
    jacobian_arrow(y, par, quad, scale, work, np.zeros(3, dtype=np.int64))
    full = np.empty((n, n))
    for k in range(n):
        e = 1e-4 * scale[k]
        yp, ym = y.copy(), y.copy()
        yp[k] += e
        ym[k] -= e
        full[:, k] = (evaluate(yp, par, quad)[0] - evaluate(ym, par, quad)[0]) / (2 * e)
    # compare in the scaled variables (rows and columns by the characteristic magnitudes)
    js = full * scale[None, :] / scale[:, None]
    norm = np.abs(js).max()

    def scaled(block, rows, cols):
        return block * scale[cols][None, :] / scale[rows][:, None]

    balls, rest = np.arange(nb), np.arange(nb, n)
    for j in (0, 7):
        idx = np.arange(L.BALL_STRIDE * j, L.BALL_STRIDE * (j + 1))
        got = scaled(work.d[j], idx, idx)
        np.testing.assert_allclose(got, js[np.ix_(idx, idx)], atol=2e-3 * norm)
    np.testing.assert_allclose(
        scaled(work.b, balls, rest), js[np.ix_(balls, rest)], atol=2e-3 * norm
    )
    np.testing.assert_allclose(
        scaled(work.c, rest, balls), js[np.ix_(rest, balls)], atol=2e-3 * norm
    )
    np.testing.assert_allclose(scaled(work.e, rest, rest), js[np.ix_(rest, rest)], atol=2e-3 * norm)
    assert np.abs(work.c).max() > 0.0 and np.abs(work.b).max() > 0.0


def test_arrow_solve_matches_a_dense_solve():
    par, quad, y = start(spindle_inputs(radial=300.0))
    scale = state_scales(par, y)
    z = int(par.ball_count)
    work = rosenbrock_work(z)
    jacobian_arrow(y, par, quad, scale, work, np.zeros(3, dtype=np.int64))
    starts, sizes = block_structure(z)
    diag = 1.0 / (2e-6 * 0.4358665215)
    assert factor_arrow(work, diag, starts, sizes)
    nb = L.BALL_STRIDE * z
    dense = np.zeros((y.shape[0], y.shape[0]))
    for j in range(z):
        s = L.BALL_STRIDE * j
        dense[s : s + 13, s : s + 13] = work.d[j]
    dense[:nb, nb:] = work.b
    dense[nb:, :nb] = work.c
    dense[nb:, nb:] = work.e
    x = np.random.default_rng(1).normal(size=y.shape[0])
    got = x.copy()
    solve_arrow(work, starts, sizes, got)
    want = np.linalg.solve(diag * np.eye(y.shape[0]) - dense, x)
    np.testing.assert_allclose(got, want, rtol=1e-8, atol=1e-12 * np.abs(want).max())
