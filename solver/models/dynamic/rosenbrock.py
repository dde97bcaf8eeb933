"""Linearly implicit Rosenbrock-W integrator with an arrow-structured Jacobian, compiled with numba.

The stiff modes of the dynamic model (docs/numerics.md) are a ball's normal contact vibration, the
traction's slope against slip on its spin and roll, and the ball-pocket friction that couples every
ball to the light cage. A ball's derivatives depend on its own state and on the inner ring's and
the cage's, never on another ball's, so the matrix ``W`` of the method is taken with the arrow
structure of the true Jacobian:

    W = [[D, B], [C, E]]

- ``D``: one 13 x 13 block per ball, all formed by 13 forward differences (the balls perturbed
  together);
- ``B`` (balls x 24) and ``E`` (24 x 24): the columns of the inner ring and the cage (24 slots),
  one difference each;
- ``C`` (24 x balls): the ring's and cage's rates against each ball's state, from each ball's own
  contact and pocket contributions (inner-contact records, :func:`kernels.cage_pocket`) in the
  same 13 perturbed evaluations.

Linear systems (I / (h gamma) - W) u = x are solved by block elimination: the ball blocks, then the
24 x 24 Schur complement. A W-method keeps its order with any matrix, so W is reused over several
steps (``jacobian_every``) and re-formed when a step is rejected with a W older than that step.

Method (Rang & Angermann 2005, ROS34PW2): 4 stages, order 3 for any W, embedded order 2,
L-stable for W = J. Written in the transformed form (Hairer & Wanner IV.7):

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
from .kernels import TRACTION_WORK_SIZE, cage_frame, cage_pocket, post_step, rhs

#: largest block of the block-diagonal W (a ball's 13 state slots)
MAX_BLOCK = L.BALL_STRIDE
#: step control: safety factor and largest growth of the step after an accepted step (contacts
#: and pocket impacts switch within a step: a cautious growth avoids rejected steps)
SAFETY = 0.8
MAX_GROWTH = 2.0


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
    """(starts, sizes) of the ball blocks of W, one per ball."""
    z = int(ball_count)
    starts = np.array([L.ball_base(j) for j in range(z)], dtype=np.int64)
    sizes = np.full(z, L.BALL_STRIDE, dtype=np.int64)
    return starts, sizes


class RosenbrockWork(NamedTuple):
    """Scratch arrays of :func:`advance_rosenbrock`, allocated once per run (Z balls, n states,
    nb = 13 Z ball slots, nr = n - nb = 24 ring and cage slots)."""

    d: np.ndarray  # (Z, 13, 13) ball blocks of W
    lu: np.ndarray  # (Z, 13, 13) LU factors of I/(h gamma) - D
    piv: np.ndarray  # (Z, 13) pivot rows
    b: np.ndarray  # (nb, nr) ring and cage columns of the ball rows
    c: np.ndarray  # (nr, nb) ball columns of the ring and cage rows
    e: np.ndarray  # (nr, nr) ring and cage block
    mb: np.ndarray  # (nb, nr) (I/(h gamma) - D)^-1 B
    s: np.ndarray  # (nr, nr) LU factors of the Schur complement
    spiv: np.ndarray  # (nr,) its pivot rows
    stages: np.ndarray  # (stages, n) U_i
    f0: np.ndarray  # (n,) f(y)
    yt: np.ndarray  # (n,)
    ft: np.ndarray  # (n,)
    fj: np.ndarray  # (n,) f at the Jacobian's base point
    rows: np.ndarray  # (nr,) scratch
    rec_inner: np.ndarray  # contact records of the Jacobian evaluations (perturbed)
    rec_outer: np.ndarray
    rec_inner0: np.ndarray  # ... and at the base point
    rec_outer0: np.ndarray
    pocket: np.ndarray  # (Z,)
    pocket0: np.ndarray  # (Z, 12) pocket outputs at the base point (kernels.cage_pocket)
    pk: np.ndarray  # (12,)
    contact_work: np.ndarray  # (TRACTION_WORK_SIZE,)
    crot: np.ndarray  # (3, 3) cage orientation
    come: np.ndarray  # (3,) cage angular velocity


def rosenbrock_work(ball_count: int, stages: int = 4) -> RosenbrockWork:
    z = int(ball_count)
    n = L.state_size(z)
    nb = L.BALL_STRIDE * z
    nr = n - nb
    return RosenbrockWork(
        np.zeros((z, MAX_BLOCK, MAX_BLOCK)),
        np.zeros((z, MAX_BLOCK, MAX_BLOCK)),
        np.zeros((z, MAX_BLOCK), dtype=np.int64),
        np.zeros((nb, nr)),
        np.zeros((nr, nb)),
        np.zeros((nr, nr)),
        np.zeros((nb, nr)),
        np.zeros((nr, nr)),
        np.zeros(nr, dtype=np.int64),
        np.zeros((stages, n)),
        np.zeros(n),
        np.zeros(n),
        np.zeros(n),
        np.zeros(n),
        np.zeros(nr),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros((z, L.N_CONTACT_RECORD)),
        np.zeros(z),
        np.zeros((z, 12)),
        np.zeros(12),
        np.zeros(TRACTION_WORK_SIZE),
        np.zeros((3, 3)),
        np.zeros(3),
    )


@njit(cache=True)
def body_rows(par, crot, dfr, dmr, dfc, dmc, out):
    """Rates of the inner-ring and cage slots (``out``, 24: ring block then cage block) caused by
    the force ``dfr`` and moment ``dmr`` on the ring and ``dfc``, ``dmc`` on the cage (inertial
    [N], [N m]), as in ``kernels.rhs``; the other slots are zero."""
    for i in range(out.shape[0]):
        out[i] = 0.0
    if par.ring_free:
        for i in range(3):
            out[L.R_VEL + i] = dfr[i] / par.ring_mass
    if par.tilt_mode == L.TILT_FREE:
        out[L.R_TILT_RATE] = dmr[1] / par.ring_diametral_inertia
        out[L.R_TILT_RATE + 1] = dmr[2] / par.ring_diametral_inertia
    if par.cage:
        c = L.RING_SIZE
        for i in range(3):
            out[c + L.C_VEL + i] = dfc[i] / par.cage_mass
        ax = crot[0, 0] * dmc[0] + crot[1, 0] * dmc[1] + crot[2, 0] * dmc[2]
        out[c + L.C_SPEED] = ax / par.cage_polar_inertia
        out[c + L.C_TILT_RATE] = dmc[1] / par.cage_diametral_inertia
        out[c + L.C_TILT_RATE + 1] = dmc[2] / par.cage_diametral_inertia


@njit(cache=True)
def jacobian_arrow(y, par, quad, scale, work, counters):
    """W = [[D, B], [C, E]] of the right-hand side at ``y`` by forward differences (module
    docstring) into ``work``; 1 + 13 + 24 evaluations."""
    n = y.shape[0]
    z = int(par.ball_count)
    nb = L.BALL_STRIDE * z
    nr = n - nb
    cb = nb + L.RING_SIZE
    yp = work.yt
    fp = work.ft
    f0 = work.fj
    rhs(y, par, quad, f0, work.rec_inner0, work.rec_outer0, work.pocket)
    counters[2] += 1
    cage_frame(y, cb, work.crot, work.come)
    if par.cage:
        for j in range(z):
            cage_pocket(
                y, L.BALL_STRIDE * j, cb, j, par, work.crot, work.come, work.contact_work, work.pk
            )
            for i in range(12):
                work.pocket0[j, i] = work.pk[i]
    dfr = np.zeros(3)
    dmr = np.zeros(3)
    dfc = np.zeros(3)
    dmc = np.zeros(3)
    for col in range(L.BALL_STRIDE):
        for i in range(n):
            yp[i] = y[i]
        for j in range(z):
            k = L.BALL_STRIDE * j + col
            yp[k] = y[k] + (1e-5 * scale[k] + 1e-8 * abs(y[k]))
        rhs(yp, par, quad, fp, work.rec_inner, work.rec_outer, work.pocket)
        counters[2] += 1
        for j in range(z):
            s = L.BALL_STRIDE * j
            k = s + col
            inv = 1.0 / (yp[k] - y[k])
            for r in range(L.BALL_STRIDE):
                work.d[j, r, col] = (fp[s + r] - f0[s + r]) * inv
            for i in range(3):
                dfr[i] = work.rec_inner[j, L.K_F_RING + i] - work.rec_inner0[j, L.K_F_RING + i]
                dmr[i] = work.rec_inner[j, L.K_M_RING + i] - work.rec_inner0[j, L.K_M_RING + i]
                dfc[i] = 0.0
                dmc[i] = 0.0
            if par.cage:
                cage_pocket(yp, s, cb, j, par, work.crot, work.come, work.contact_work, work.pk)
                for i in range(3):
                    dfc[i] = work.pk[6 + i] - work.pocket0[j, 6 + i]
                    dmc[i] = work.pk[9 + i] - work.pocket0[j, 9 + i]
            body_rows(par, work.crot, dfr, dmr, dfc, dmc, work.rows)
            for r in range(nr):
                work.c[r, k] = work.rows[r] * inv
    for col in range(nr):
        for i in range(n):
            yp[i] = y[i]
        k = nb + col
        yp[k] = y[k] + (1e-5 * scale[k] + 1e-8 * abs(y[k]))
        rhs(yp, par, quad, fp, work.rec_inner, work.rec_outer, work.pocket)
        counters[2] += 1
        inv = 1.0 / (yp[k] - y[k])
        for r in range(nb):
            work.b[r, col] = (fp[r] - f0[r]) * inv
        for r in range(nr):
            work.e[r, col] = (fp[nb + r] - f0[nb + r]) * inv


@njit(cache=True)
def lu_factor(a, m, piv):
    """LU factors with partial pivoting of the leading m x m part of ``a``, in place (LAPACK
    layout: row swaps in ``piv``). Returns False when it is singular."""
    for k in range(m):
        p = k
        big = abs(a[k, k])
        for r in range(k + 1, m):
            if abs(a[r, k]) > big:
                big = abs(a[r, k])
                p = r
        piv[k] = p
        if p != k:
            for c in range(m):
                tmp = a[k, c]
                a[k, c] = a[p, c]
                a[p, c] = tmp
        d = a[k, k]
        if d == 0.0 or d != d:
            return False
        for r in range(k + 1, m):
            f = a[r, k] / d
            a[r, k] = f
            for c in range(k + 1, m):
                a[r, c] -= f * a[k, c]
    return True


@njit(cache=True)
def lu_solve(a, m, piv, x, s):
    """Solve with the factors of :func:`lu_factor`, in place on x[s : s + m]."""
    for k in range(m):
        p = piv[k]
        if p != k:
            tmp = x[s + k]
            x[s + k] = x[s + p]
            x[s + p] = tmp
    for r in range(1, m):
        acc = x[s + r]
        for c in range(r):
            acc -= a[r, c] * x[s + c]
        x[s + r] = acc
    for r in range(m - 1, -1, -1):
        acc = x[s + r]
        for c in range(r + 1, m):
            acc -= a[r, c] * x[s + c]
        x[s + r] = acc / a[r, r]


@njit(cache=True)
def factor_blocks(jac, lu, piv, sizes, diag):
    """LU factors of diag * I - jac, block by block (``sizes[b]`` x ``sizes[b]`` leading parts).
    Returns False when a block is singular."""
    for b in range(sizes.shape[0]):
        m = sizes[b]
        for r in range(m):
            for c in range(m):
                lu[b, r, c] = -jac[b, r, c]
            lu[b, r, r] += diag
        if not lu_factor(lu[b], m, piv[b]):
            return False
    return True


@njit(cache=True)
def solve_blocks(lu, piv, starts, sizes, x):
    """Solve (diag I - jac) u = x in place, block by block, with the factors of factor_blocks."""
    for b in range(starts.shape[0]):
        lu_solve(lu[b], sizes[b], piv[b], x, starts[b])


@njit(cache=True)
def factor_arrow(work, diag, starts, sizes):
    """Factor diag * I - W (W of :func:`jacobian_arrow`): ball blocks, (diag I - D)^-1 B and the
    Schur complement diag I - E - C (diag I - D)^-1 B. Returns False when singular."""
    if not factor_blocks(work.d, work.lu, work.piv, sizes, diag):
        return False
    nb, nr = work.b.shape
    col = work.yt
    for k in range(nr):
        for r in range(nb):
            col[r] = work.b[r, k]
        solve_blocks(work.lu, work.piv, starts, sizes, col)
        for r in range(nb):
            work.mb[r, k] = col[r]
    for i in range(nr):
        for k in range(nr):
            acc = -work.e[i, k]
            for r in range(nb):
                acc -= work.c[i, r] * work.mb[r, k]
            work.s[i, k] = acc
        work.s[i, i] += diag
    return lu_factor(work.s, nr, work.spiv)


@njit(cache=True)
def solve_arrow(work, starts, sizes, x):
    """Solve (diag I - W) u = x in place with the factors of :func:`factor_arrow`."""
    nb, nr = work.b.shape
    solve_blocks(work.lu, work.piv, starts, sizes, x)  # v = (diag I - D)^-1 x_b
    for i in range(nr):
        acc = x[nb + i]
        for r in range(nb):
            acc += work.c[i, r] * x[r]
        x[nb + i] = acc
    lu_solve(work.s, nr, work.spiv, x, nb)
    for r in range(nb):
        acc = x[r]
        for k in range(nr):
            acc += work.mb[r, k] * x[nb + k]
        x[r] = acc


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
    jac_every,
    work,
):
    """Integrate from ``t`` through every time in ``t_out`` like ``integrator.advance`` (same
    arguments, outputs and status codes), with the Rosenbrock-W method ``tab_*``; ``starts`` /
    ``sizes``: the ball blocks; W is re-formed every ``jac_every`` accepted steps and when a step
    is rejected with a W formed before it."""
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
                jacobian_arrow(y, par, quad, scale, work, counters)
                jac_age = 0
                h_factored = -1.0
            if hs != h_factored:
                if not factor_arrow(work, 1.0 / (hs * tab_gamma), starts, sizes):
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
                solve_arrow(work, starts, sizes, u[s])
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
                fac = SAFETY * err ** (-expo) if err > 0.0 else MAX_GROWTH
                if err > 0.0 and steps > 1:
                    fac = min(fac, fac * (hs / h_old) * (err_old / err) ** expo)
                fac = min(MAX_GROWTH, max(0.2, fac))
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
                h = hs * max(0.2, SAFETY * err ** (-expo))
                counters[1] += 1
                if jac_age > 0:  # a second rejection with the same W re-forms it
                    jac_age = jac_every
                if h < h_min:
                    return STATUS_STEP_COLLAPSE, t, h, n_done
        for i in range(n):
            out_states[k, i] = y[i]
        n_done += 1
    return STATUS_OK, t, h, n_done
