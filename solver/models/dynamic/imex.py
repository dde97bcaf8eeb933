"""Additive (implicit–explicit) Runge–Kutta integrator: the cage's guiding-land film implicit,
everything else explicit; and the default method "auto" that switches between it and the explicit
Dormand–Prince step; compiled with numba.

A cage running in its guiding land near the land (eccentricity above about 0.95 of the clearance)
is held by the film's squeeze damping, which on the light cage is an overdamped mode of the cage's
radial velocity of about -1.5e6 1/s on the 218 heavy case: it sets the explicit step there
(docs/numerics.md). The right-hand side is split exactly as

    f(Y) = f_E(Y) + f_I(Y),   f_I(Y) = P A P (Y - y_n),   f_E = f - f_I,

where P selects the cage's velocity (3 slots) and A is the derivative of the cage's acceleration
with respect to its velocity through the guiding-land force (:func:`kernels.cage_land`, forward
differences at the step's start, no right-hand-side evaluation; :func:`cage_velocity_jacobian`
can add the pockets' forces, see ``LAND_POCKETS``). Any A keeps the order (the split is exact);
an A close to the true block removes the stability limit of the film mode.

Method: ARK4(3)6L[2]SA of Kennedy & Carpenter (Appl. Numer. Math. 44, 2003, 139–181): an explicit
tableau coupled to an L-stable ESDIRK (gamma = 1/4), sharing b and c; order 4, embedded order 3;
six right-hand-side evaluations per accepted step (five on a rejected one). Each implicit stage
solves a 3 x 3 system. Error norm, status codes and post-step hook as in ``integrator``; PI step
control with exponent 1/4. Output times inside a step are filled by cubic Hermite interpolation
of the step's end values and slopes (local error O(h^4), no extra evaluation); the step stops
exactly only at the last output time of each call.

Method "auto" (``switch`` > 0 in :func:`advance_imex`): a step is an explicit Dormand–Prince step
(``integrator.dp5_stages``) while its size times the spectral bound of A stays at or below
``SWITCH_BOUND``, an additive step otherwise, with hysteresis (``SWITCH_BACK``). Where the cage
is not near its land (the spindle cases) every step is explicit.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from .integrator import (
    STATUS_BALL_ESCAPED,
    STATUS_NOT_FINITE,
    STATUS_OK,
    STATUS_STEP_COLLAPSE,
    STATUS_TOO_MANY_STEPS,
    dp5_dense,
    dp5_error,
    dp5_stages,
)
from .kernels import cage_land, cage_pocket, post_step, rhs_into, rhs_work
from .layout import BALL_STRIDE, C_VEL, RING_SIZE

#: method "auto": largest step size times the land block's spectral bound (largest absolute row
#: sum; about 1.2x its largest eigenvalue on the 218 heavy case) taken by an explicit
#: Dormand–Prince step, whose stability interval on the negative real axis reaches 3.3; and the
#: value below which explicit steps resume after an additive step (hysteresis: without it a
#: rejected additive step hands a shrunken step to the explicit method, whose growth overshoots
#: into a rejected additive step again). Chosen by measurement (docs/numerics.md).
SWITCH_BOUND = 3.0
SWITCH_BACK = 1.5
#: whether the implicit block also holds the pockets' forces: False, the land's alone (the pockets'
#: damping is far from stiff: with them the 218 heavy case takes as many steps, and each step
#: costs 72 more pocket evaluations)
LAND_POCKETS = False
#: relative velocity step of the land Jacobian's forward differences (of the cage state's
#: characteristic velocity)
JACOBIAN_STEP = 1e-4


class ArkTableau(NamedTuple):
    """Additive Runge–Kutta pair: explicit and implicit stage matrices, shared weights, the
    weights minus the embedded weights, and the order of the embedded solution + 1."""

    explicit: np.ndarray
    implicit: np.ndarray
    b: np.ndarray
    e: np.ndarray
    order: int


def ark436l2sa() -> ArkTableau:
    """ARK4(3)6L[2]SA (Kennedy & Carpenter 2003, tables of §5)."""
    ae = np.zeros((6, 6))
    ae[1, 0] = 0.5
    ae[2, :2] = (13861.0 / 62500.0, 6889.0 / 62500.0)
    ae[3, :3] = (
        -116923316275.0 / 2393684061468.0,
        -2731218467317.0 / 15368042101831.0,
        9408046702089.0 / 11113171139209.0,
    )
    ae[4, :4] = (
        -451086348788.0 / 2902428689909.0,
        -2682348792572.0 / 7519795681897.0,
        12662868775082.0 / 11960479115383.0,
        3355817975965.0 / 11060851509271.0,
    )
    ae[5, :5] = (
        647845179188.0 / 3216320057751.0,
        73281519250.0 / 8382639484533.0,
        552539513391.0 / 3454668386233.0,
        3354512671639.0 / 8306763924573.0,
        4040.0 / 17871.0,
    )
    ai = np.zeros((6, 6))
    ai[1, :2] = (0.25, 0.25)
    ai[2, :3] = (8611.0 / 62500.0, -1743.0 / 31250.0, 0.25)
    ai[3, :4] = (5012029.0 / 34652500.0, -654441.0 / 2922500.0, 174375.0 / 388108.0, 0.25)
    ai[4, :5] = (
        15267082809.0 / 155376265600.0,
        -71443401.0 / 120774400.0,
        730878875.0 / 902184768.0,
        2285395.0 / 8070912.0,
        0.25,
    )
    b = np.array(
        (82889.0 / 524892.0, 0.0, 15625.0 / 83664.0, 69875.0 / 102672.0, -2260.0 / 8211.0, 0.25)
    )
    ai[5, :] = b  # stiffly accurate
    b_hat = np.array(
        (
            4586570599.0 / 29645900160.0,
            0.0,
            178811875.0 / 945068544.0,
            814220225.0 / 1159782912.0,
            -3700637.0 / 11593932.0,
            61727.0 / 225920.0,
        )
    )
    return ArkTableau(ae, ai, b, b - b_hat, 4)


@njit(cache=True)
def _lu3(m):
    """In-place LU factors (no pivoting: the matrix is I - h gamma A with A a damping block, whose
    diagonal dominates) of the 3 x 3 ``m``."""
    for p in range(3):
        for r in range(p + 1, 3):
            m[r, p] /= m[p, p]
            for c in range(p + 1, 3):
                m[r, c] -= m[r, p] * m[p, c]


@njit(cache=True)
def _solve3(m, rhs, out):
    """``out`` <- solution of (L U) out = rhs with the factors of :func:`_lu3`."""
    for r in range(3):
        acc = rhs[r]
        for c in range(r):
            acc -= m[r, c] * out[c]
        out[r] = acc
    for r in range(2, -1, -1):
        acc = out[r]
        for c in range(r + 1, 3):
            acc -= m[r, c] * out[c]
        out[r] = acc / m[r, r]


@njit(cache=True)
def _cage_force(y, cb, par, scratch, pockets, out):
    """``out`` (3,) <- force on the cage [N] from its guiding land and (``pockets`` True) all its
    pockets at ``y``, with the ring and cage frames held in ``scratch`` by the last
    right-hand-side evaluation."""
    z = int(par.ball_count)
    work = scratch.contact
    pk = scratch.pocket
    ld = scratch.land
    cage_land(y, cb, scratch.inner_origin, scratch.inner_vel, par, work, ld)
    out[0] = ld[0]
    out[1] = ld[1]
    out[2] = ld[2]
    if not pockets:
        return
    rot = scratch.cage_rot
    omega = scratch.cage_omega
    for j in range(z):
        if cage_pocket(y, BALL_STRIDE * j, cb, j, par, rot, omega, work, pk) > 0.0:
            out[0] += pk[6]
            out[1] += pk[7]
            out[2] += pk[8]


@njit(cache=True)
def cage_velocity_jacobian(y, cb, par, scratch, dv, pockets, base, moved, jac):
    """``jac`` (3, 3) <- d(cage acceleration)/d(cage velocity) [1/s] of the guiding-land and
    (``pockets`` True) pocket forces at ``y`` (forward differences of step ``dv`` [m/s]);
    ``base``, ``moved``: (3,) scratch.
    The ring and cage frames are those of the last right-hand-side evaluation (the cage velocity
    does not enter them). ``y`` is restored."""
    _cage_force(y, cb, par, scratch, pockets, base)
    inv = 1.0 / (par.cage_mass * dv)
    for c in range(3):
        k = cb + C_VEL + c
        keep = y[k]
        y[k] = keep + dv
        _cage_force(y, cb, par, scratch, pockets, moved)
        y[k] = keep
        for r in range(3):
            jac[r, c] = (moved[r] - base[r]) * inv


@njit(cache=True)
def advance_imex(
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
    ae,
    ai,
    b,
    e,
    order,
    switch,
    switch_back,
):
    """``integrator.advance`` with the additive pair (``ae``, ``ai``, ``b``, ``e``, ``order``) of
    :func:`ark436l2sa`: same arguments before the tableau, same returns (status, t, h, n_done).

    ``switch`` > 0: a step whose size times the spectral bound (largest absolute row sum) of the
    matrix A stays at or below ``switch`` is an explicit Dormand–Prince step
    (``integrator.dp5_stages``, its own error estimate, step control and continuous extension);
    only the steps that the film's damping would make unstable or inaccurate for the explicit
    method are additive ones; after an additive step, explicit steps resume only at or below
    ``switch_back`` (< ``switch``). ``switch`` = 0: every step is additive."""
    n = y.shape[0]
    ns = b.shape[0]
    z = int(par.ball_count)
    cb = BALL_STRIDE * z + RING_SIZE
    k0 = cb + C_VEL  # the implicit slots: cage velocity x, y, z
    implicit = bool(par.cage)
    gamma = ai[1, 1]
    k = np.empty((max(ns, 7), n))  # f at the stages (seven for a Dormand–Prince step)
    fi = np.zeros((ns, 3))  # implicit part at the stages
    yt = np.empty(n)
    ynew = np.empty(n)
    jac = np.zeros((3, 3))
    lu = np.empty((3, 3))
    rr = np.empty(3)
    dd = np.empty(3)
    base = np.empty(3)
    moved = np.empty(3)
    scratch = rhs_work(int(par.ball_count))
    rhs_into(y, par, quad, k[0], rec_inner, rec_outer, pocket, scratch, False)
    counters[2] += 1
    dv = JACOBIAN_STEP * scale[k0]
    err_old = 1e-4
    additive = False  # the method of the last step (switching: with hysteresis)
    steps = 0
    n_done = 0
    exponent = 0.7 / order
    memory = 0.4 / order
    n_out = t_out.shape[0]
    if n_out == 0:
        return STATUS_OK, t, h, 0
    t_target = t_out[n_out - 1]
    while t < t_target:
        if steps >= max_steps:
            return STATUS_TOO_MANY_STEPS, t, h, n_done
        clipped = False
        hs = h
        if t + hs >= t_target:
            hs = t_target - t
            clipped = True
        if implicit:
            cage_velocity_jacobian(y, cb, par, scratch, dv, LAND_POCKETS, base, moved, jac)
        if switch > 0.0:
            bound = 0.0
            for r in range(3):
                bound = max(bound, abs(jac[r, 0]) + abs(jac[r, 1]) + abs(jac[r, 2]))
            # with hysteresis (SWITCH_BACK)
            additive = hs * bound > (switch_back if additive else switch)
            if not additive:
                dp5_stages(
                    y, hs, k[0], k[1], k[2], k[3], k[4], k[5], k[6], yt, ynew, par, quad,
                    rec_inner, rec_outer, pocket, scratch,
                )  # fmt: skip
                counters[2] += 6
                steps += 1
                err = dp5_error(hs, k[0], k[2], k[3], k[4], k[5], k[6], scale, tol)
                if not (err < 1e300):
                    h = 0.1 * hs
                    counters[1] += 1
                    if h < h_min:
                        return STATUS_NOT_FINITE, t, h, n_done
                    continue
                if err <= 1.0:
                    fac = 0.9 * err ** (-0.17) * err_old**0.04 if err > 0.0 else 5.0
                    fac = min(5.0, max(0.2, fac))
                    err_old = max(err, 1e-4)
                    t_new = t_target if clipped else t + hs
                    while n_done < n_out - 1 and t_out[n_done] <= t_new:
                        th = (t_out[n_done] - t) / hs
                        dp5_dense(
                            y, ynew, hs, th, k[0], k[2], k[3], k[4], k[5], k[6], out_states[n_done]
                        )
                        n_done += 1
                    t = t_new
                    for i in range(n):
                        y[i] = ynew[i]
                    if not post_step(y, par, rec_inner, rec_outer):
                        return STATUS_BALL_ESCAPED, t, h, n_done
                    for i in range(n):
                        k[0, i] = k[6, i]  # FSAL
                    counters[0] += 1
                    if not clipped or hs * fac > h:
                        h = hs * fac
                else:
                    h = hs * max(0.2, 0.9 * err ** (-0.2))
                    counters[1] += 1
                    if h < h_min:
                        return STATUS_STEP_COLLAPSE, t, h, n_done
                continue
        for r in range(3):
            for c in range(3):
                lu[r, c] = (1.0 if r == c else 0.0) - hs * gamma * jac[r, c]
        _lu3(lu)
        for c in range(3):
            fi[0, c] = 0.0
        for s in range(1, ns):
            for i in range(n):
                acc = 0.0
                for j in range(s):
                    acc += ae[s, j] * k[j, i]
                yt[i] = y[i] + hs * acc
            if implicit:
                for c in range(3):
                    acc = yt[k0 + c] - y[k0 + c]
                    for j in range(s):
                        acc += hs * (ai[s, j] - ae[s, j]) * fi[j, c]
                    rr[c] = acc
                _solve3(lu, rr, dd)
                for c in range(3):
                    yt[k0 + c] = y[k0 + c] + dd[c]
                for r in range(3):
                    fi[s, r] = jac[r, 0] * dd[0] + jac[r, 1] * dd[1] + jac[r, 2] * dd[2]
            rhs_into(yt, par, quad, k[s], rec_inner, rec_outer, pocket, scratch, False)
        counters[2] += ns - 1
        steps += 1
        err = 0.0
        for i in range(n):
            acc = 0.0
            est = 0.0
            for j in range(ns):
                acc += b[j] * k[j, i]
                est += e[j] * k[j, i]
            ynew[i] = y[i] + hs * acc
            r = abs(hs * est) / (tol * scale[i])
            if r > err or r != r:  # keep a NaN: it must reach the finiteness check
                err = r
        if not (err < 1e300):
            h = 0.1 * hs
            counters[1] += 1
            if h < h_min:
                return STATUS_NOT_FINITE, t, h, n_done
            continue
        if err <= 1.0:
            fac = 0.9 * err ** (-exponent) * err_old**memory if err > 0.0 else 5.0
            fac = min(5.0, max(0.2, fac))
            err_old = max(err, 1e-4)
            t_new = t_target if clipped else t + hs
            for i in range(n):
                yt[i] = y[i]  # keep y_n for the outputs inside the step
                y[i] = ynew[i]
            if not post_step(y, par, rec_inner, rec_outer):
                return STATUS_BALL_ESCAPED, t, h, n_done
            for i in range(n):
                ynew[i] = k[0, i]  # keep f(y_n)
            rhs_into(y, par, quad, k[0], rec_inner, rec_outer, pocket, scratch, False)
            counters[2] += 1
            # outputs inside the step: cubic Hermite interpolation of y_n, y, f(y_n), f(y)
            while n_done < n_out - 1 and t_out[n_done] <= t_new:
                th = (t_out[n_done] - t) / hs
                h00 = (1.0 + 2.0 * th) * (1.0 - th) ** 2
                h10 = th * (1.0 - th) ** 2 * hs
                h01 = th * th * (3.0 - 2.0 * th)
                h11 = th * th * (th - 1.0) * hs
                for i in range(n):
                    out_states[n_done, i] = h00 * yt[i] + h10 * ynew[i] + h01 * y[i] + h11 * k[0, i]
                n_done += 1
            t = t_new
            counters[0] += 1
            if not clipped or hs * fac > h:
                h = hs * fac
        else:
            h = hs * max(0.2, 0.9 * err ** (-1.0 / order))
            counters[1] += 1
            if h < h_min:
                return STATUS_STEP_COLLAPSE, t, h, n_done
    for i in range(n):
        out_states[n_out - 1, i] = y[i]
    return STATUS_OK, t, h, n_out
