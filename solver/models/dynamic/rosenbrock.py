"""Linearly implicit Rosenbrock-W integrator with a block-diagonal Jacobian, compiled with numba.

The stiff modes of the dynamic model are local to each body (docs/numerics.md): a ball's normal
contact vibration and the traction's slope against slip on its spin and roll. The matrix ``W`` of
the method is therefore block-diagonal: one 13 x 13 block per ball, one block for the inner ring
and one for the cage, formed by forward finite differences of the right-hand side with the blocks
of a group perturbed together (a ball's own derivatives do not depend on the other balls' states,
so all balls take 13 evaluations; ring and cage another 12). A W-method keeps its order with any
matrix, so the blocks are reused over several steps and the neglected ball-ring coupling costs
accuracy control, not correctness.

Method (Rang & Angermann 2005, ROS34PW2): 4 stages, order 3 for any W, embedded order 2,
stiffly accurate and L-stable for W = J. Written in the transformed form (Hairer & Wanner IV.7):

    (I / (h gamma) - W) U_i = f(y + sum_j a_ij U_j) + sum_j (c_ij / h) U_j,
    y_new = y + sum_i m_i U_i,   error = sum_i e_i U_i.

Error norm and status codes as in ``integrator`` (max over components of |err_i| / (tol scale_i)).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from . import layout as L
from .integrator import (
    STATUS_BALL_ESCAPED,
    STATUS_NOT_FINITE,
    STATUS_OK,
    STATUS_STEP_COLLAPSE,
    STATUS_TOO_MANY_STEPS,
)
from .kernels import post_step, rhs

#: largest block of the block-diagonal W (a ball's 13 state slots)
MAX_BLOCK = L.BALL_STRIDE


class RosenbrockTableau(NamedTuple):
    """Coefficients of the transformed form (arrays, ``stages`` x ``stages`` lower triangular)."""

    gamma: float
    a: np.ndarray
    c: np.ndarray
    m: np.ndarray
    e: np.ndarray
    order: int  # order of the embedded solution + 1: exponent of the step control is 1 / order


def transformed_tableau(gamma, alpha, gam, b, b_hat) -> RosenbrockTableau:
    """Transformed coefficients from the standard form
    k_i = h f(y + sum alpha_ij k_j) + h W sum gam_ij k_j (gam_ii = gamma), y1 = y + sum b_i k_i."""
    alpha = np.asarray(alpha, dtype=float)
    big_g = np.asarray(gam, dtype=float) + gamma * np.eye(len(b))
    g_inv = np.linalg.inv(big_g)
    a = alpha @ g_inv
    c = np.diag(np.diag(g_inv)) - g_inv
    m = np.asarray(b, dtype=float) @ g_inv
    m_hat = np.asarray(b_hat, dtype=float) @ g_inv
    return RosenbrockTableau(float(gamma), a, np.tril(c, -1), m, m - m_hat, 3)


def ros34pw2() -> RosenbrockTableau:
    """ROS34PW2 (Rang & Angermann, BIT 45, 2005): W-method of order 3(2), 4 stages."""
    gamma = 4.3586652150845900e-01
    alpha = np.zeros((4, 4))
    alpha[1, 0] = 8.7173304301691801e-01
    alpha[2, 0] = 8.4457060015369423e-01
    alpha[2, 1] = -1.1299064236484185e-01
    alpha[3, 2] = 1.0
    gam = np.zeros((4, 4))
    gam[1, 0] = -8.7173304301691801e-01
    gam[2, 0] = -9.0338057013044082e-01
    gam[2, 1] = 5.4180672388095326e-02
    gam[3, 0] = 2.4212380706095346e-01
    gam[3, 1] = -1.2232505839045147e00
    gam[3, 2] = 5.4526025533510214e-01
    b = (
        2.4212380706095346e-01,
        -1.2232505839045147e00,
        1.5452602553351020e00,
        4.3586652150845900e-01,
    )
    b_hat = (
        3.7810903145819369e-01,
        -9.6042292212423178e-02,
        0.5,
        2.1793326075422950e-01,
    )
    return transformed_tableau(gamma, alpha, gam, b, b_hat)


def block_structure(ball_count: int):
    """(starts, sizes, groups) of the diagonal blocks: one per ball (group 0), the inner ring and
    the cage (group 1). The blocks of a group are perturbed together when W is formed."""
    z = int(ball_count)
    starts = np.array([L.ball_base(j) for j in range(z)] + [L.ring_base(z), L.cage_base(z)])
    sizes = np.array([L.BALL_STRIDE] * z + [L.RING_SIZE, L.CAGE_SIZE])
    groups = np.array([0] * z + [1, 1])
    return starts.astype(np.int64), sizes.astype(np.int64), groups.astype(np.int64)


class RosenbrockWork(NamedTuple):
    """Scratch arrays of :func:`advance_rosenbrock`, allocated once per run."""

    jac: np.ndarray  # (blocks, 13, 13) W blocks
    lu: np.ndarray  # (blocks, 13, 13) LU factors of I/(h gamma) - W
    piv: np.ndarray  # (blocks, 13) pivot rows
    stages: np.ndarray  # (4, n) U_i
    f0: np.ndarray  # (n,) f(y)
    yt: np.ndarray  # (n,)
    ft: np.ndarray  # (n,)
    rec_inner: np.ndarray  # contact records of the Jacobian evaluations
    rec_outer: np.ndarray
    pocket: np.ndarray


def rosenbrock_work(ball_count: int, stages: int = 4) -> RosenbrockWork:
    z = int(ball_count)
    n = L.state_size(z)
    nb = z + 2
    return RosenbrockWork(
        np.zeros((nb, MAX_BLOCK, MAX_BLOCK)),
        np.zeros((nb, MAX_BLOCK, MAX_BLOCK)),
        np.zeros((nb, MAX_BLOCK), dtype=np.int64),
        np.zeros((stages, n)),
        np.zeros(n),
        np.zeros(n),
        np.zeros(n),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros(z),
    )


@njit(cache=True)
def jacobian_blocks(y, f0, par, quad, scale, starts, sizes, groups, work, counters):
    """Diagonal blocks of df/dy at ``y`` (``f0`` = f(y)) into ``work.jac`` by forward differences;
    the blocks of one group are perturbed in the same evaluation."""
    n = y.shape[0]
    yp = work.yt
    fp = work.ft
    nb = starts.shape[0]
    for g in range(2):
        for col in range(MAX_BLOCK):
            for i in range(n):
                yp[i] = y[i]
            touched = False
            for b in range(nb):
                if groups[b] == g and col < sizes[b]:
                    k = starts[b] + col
                    yp[k] = y[k] + (1e-5 * scale[k] + 1e-8 * abs(y[k]))
                    touched = True
            if not touched:
                continue
            rhs(yp, par, quad, fp, work.rec_inner, work.rec_outer, work.pocket)
            counters[2] += 1
            for b in range(nb):
                if groups[b] == g and col < sizes[b]:
                    k = starts[b] + col
                    inv = 1.0 / (yp[k] - y[k])
                    s = starts[b]
                    for r in range(sizes[b]):
                        work.jac[b, r, col] = (fp[s + r] - f0[s + r]) * inv
                    for r in range(sizes[b], MAX_BLOCK):
                        work.jac[b, r, col] = 0.0


@njit(cache=True)
def factor_blocks(jac, lu, piv, sizes, diag):
    """LU factors (partial pivoting, in place in ``lu``) of diag * I - jac, block by block.
    Returns False when a block is singular."""
    for b in range(sizes.shape[0]):
        m = sizes[b]
        for r in range(m):
            for c in range(m):
                lu[b, r, c] = -jac[b, r, c]
            lu[b, r, r] += diag
        for k in range(m):
            p = k
            big = abs(lu[b, k, k])
            for r in range(k + 1, m):
                if abs(lu[b, r, k]) > big:
                    big = abs(lu[b, r, k])
                    p = r
            piv[b, k] = p
            if p != k:
                for c in range(m):
                    tmp = lu[b, k, c]
                    lu[b, k, c] = lu[b, p, c]
                    lu[b, p, c] = tmp
            d = lu[b, k, k]
            if d == 0.0:
                return False
            for r in range(k + 1, m):
                f = lu[b, r, k] / d
                lu[b, r, k] = f
                for c in range(k + 1, m):
                    lu[b, r, c] -= f * lu[b, k, c]
    return True


@njit(cache=True)
def solve_blocks(lu, piv, starts, sizes, x):
    """Solve (diag I - jac) u = x in place, block by block, with the factors of factor_blocks."""
    for b in range(starts.shape[0]):
        s = starts[b]
        m = sizes[b]
        for k in range(m):
            p = piv[b, k]
            if p != k:
                tmp = x[s + k]
                x[s + k] = x[s + p]
                x[s + p] = tmp
        for r in range(1, m):
            acc = x[s + r]
            for c in range(r):
                acc -= lu[b, r, c] * x[s + c]
            x[s + r] = acc
        for r in range(m - 1, -1, -1):
            acc = x[s + r]
            for c in range(r + 1, m):
                acc -= lu[b, r, c] * x[s + c]
            x[s + r] = acc / lu[b, r, r]


@njit(cache=True)
def advance_rosenbrock(
    y,
    t,
    h,
    t_out,
    out_states,
    par,
    quad,
    scale,
    tol,
    h_min,
    max_steps,
    counters,
    rec_inner,
    rec_outer,
    pocket,
    tab_gamma,
    tab_a,
    tab_c,
    tab_m,
    tab_e,
    tab_order,
    starts,
    sizes,
    groups,
    jac_every,
    work,
):
    """Integrate from ``t`` through every time in ``t_out`` like ``integrator.advance`` (same
    arguments, outputs and status codes), with the Rosenbrock-W method ``tab_*`` and the W blocks
    ``starts``/``sizes``/``groups`` re-formed every ``jac_every`` accepted steps and after a
    rejected step."""
    n = y.shape[0]
    ns = tab_m.shape[0]
    u = work.stages
    f0 = work.f0
    yt = work.yt
    ft = work.ft
    rhs(y, par, quad, f0, rec_inner, rec_outer, pocket)
    counters[2] += 1
    jac_age = jac_every  # form W on the first step
    h_factored = -1.0
    err_old = 1.0
    h_old = h
    expo = 1.0 / tab_order
    steps = 0
    n_done = 0
    for k in range(t_out.shape[0]):
        t_target = t_out[k]
        while t < t_target:
            if steps >= max_steps:
                return STATUS_TOO_MANY_STEPS, t, h, n_done
            clipped = False
            hs = h
            if t + hs >= t_target:
                hs = t_target - t
                clipped = True
            if jac_age >= jac_every:
                jacobian_blocks(y, f0, par, quad, scale, starts, sizes, groups, work, counters)
                jac_age = 0
                h_factored = -1.0
            if hs != h_factored:
                if not factor_blocks(work.jac, work.lu, work.piv, sizes, 1.0 / (hs * tab_gamma)):
                    return STATUS_NOT_FINITE, t, h, n_done
                h_factored = hs
            for s in range(ns):
                if s == 0:
                    for i in range(n):
                        ft[i] = f0[i]
                else:
                    for i in range(n):
                        acc = y[i]
                        for j in range(s):
                            acc += tab_a[s, j] * u[j, i]
                        yt[i] = acc
                    rhs(yt, par, quad, ft, rec_inner, rec_outer, pocket)
                    counters[2] += 1
                for i in range(n):
                    acc = ft[i]
                    for j in range(s):
                        acc += tab_c[s, j] / hs * u[j, i]
                    u[s, i] = acc
                solve_blocks(work.lu, work.piv, starts, sizes, u[s])
            steps += 1
            err = 0.0
            for i in range(n):
                acc = 0.0
                for j in range(ns):
                    acc += tab_e[j] * u[j, i]
                r = abs(acc) / (tol * scale[i])
                if r > err or r != r:
                    err = r
                    if r != r:
                        break
            if not (err < 1e300):
                h = 0.1 * hs
                counters[1] += 1
                jac_age = jac_every
                if h < h_min:
                    return STATUS_NOT_FINITE, t, h, n_done
                continue
            if err <= 1.0:
                # accept; Gustafsson's predictive controller (Hairer & Wanner IV.8, (8.21))
                fac = 0.9 * err ** (-expo) if err > 0.0 else 5.0
                if err > 0.0 and steps > 1:
                    fac = min(fac, fac * (hs / h_old) * (err_old / err) ** expo)
                fac = min(5.0, max(0.2, fac))
                h_old = hs
                err_old = max(err, 1e-2)
                t = t_target if clipped else t + hs
                for i in range(n):
                    acc = y[i]
                    for j in range(ns):
                        acc += tab_m[j] * u[j, i]
                    y[i] = acc
                if not post_step(y, par, rec_inner, rec_outer):
                    return STATUS_BALL_ESCAPED, t, h, n_done
                rhs(y, par, quad, f0, rec_inner, rec_outer, pocket)
                counters[2] += 1
                counters[0] += 1
                jac_age += 1
                if not clipped or hs * fac > h:
                    h = hs * fac
            else:
                h = hs * max(0.2, 0.9 * err ** (-expo))
                counters[1] += 1
                jac_age = jac_every
                if h < h_min:
                    return STATUS_STEP_COLLAPSE, t, h, n_done
        for i in range(n):
            out_states[k, i] = y[i]
        n_done += 1
    return STATUS_OK, t, h, n_done
