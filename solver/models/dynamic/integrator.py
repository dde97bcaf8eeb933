"""Adaptive Dormand–Prince 5(4) integrator with PI step control, compiled with numba.

The stepper calls the right-hand side directly (no Python callback per step). It steps over the
requested output times and fills them from the method's continuous extension (Hairer, Nørsett &
Wanner I, §II.6: order 4, from the seven stages already computed, no extra evaluation); it stops
exactly only on the last output time of each call, where the driver's chunk ends.

Error norm: max over components of |err_i| / (tol * scale_i), where
``scale_i`` is the characteristic magnitude of component i (see ``simulate.state_scales``): the
error control is therefore absolute per physical quantity, which keeps it meaningful for positions
that are large (the pitch radius) but whose relevant variations are tiny (contact deflections).

The model supplies two kernels (``kernels.rhs`` and ``kernels.post_step``), the only model code
this module calls: the right-hand side, and a hook run after every accepted step (the dynamic model
renormalises its quaternions there and reports a ball that left the raceways). Integrator options
(tolerance, smallest step, step budget) are arguments of ``advance``, separate from the model's
parameter record. A stiff or implicit method is another ``advance``-like loop over the same two
kernels (numba compiles a function passed as an argument anew in every process, so the kernels are
bound by import rather than passed in).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .kernels import post_step, rhs_into, rhs_work

# Status codes returned by ``advance``.
STATUS_OK = 0
STATUS_NOT_FINITE = 1
STATUS_STEP_COLLAPSE = 2
STATUS_BALL_ESCAPED = 3
STATUS_TOO_MANY_STEPS = 4

# Dormand–Prince 5(4) tableau
_C2, _C3, _C4, _C5 = 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0
_A21 = 1.0 / 5.0
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63, _A64, _A65 = (
    9017.0 / 3168.0,
    -355.0 / 33.0,
    46732.0 / 5247.0,
    49.0 / 176.0,
    -5103.0 / 18656.0,
)
_A71, _A73, _A74, _A75, _A76 = (
    35.0 / 384.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
)
# continuous extension (dense output) of order 4
_D1, _D3, _D4, _D5, _D6, _D7 = (
    -12715105075.0 / 11282082432.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
)
_E1, _E3, _E4, _E5, _E6, _E7 = (
    71.0 / 57600.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
)


@njit(cache=True)
def dp5_stages(y, hs, k1, k2, k3, k4, k5, k6, k7, yt, ynew, par, quad, rec_i, rec_o, pocket, work):
    """One Dormand–Prince step of size ``hs`` from ``y`` with ``k1`` = f(y): the stages k2..k7
    and the new state ``ynew`` (k7 = f(ynew)); six right-hand-side evaluations."""
    n = y.shape[0]
    for i in range(n):
        yt[i] = y[i] + hs * _A21 * k1[i]
    rhs_into(yt, par, quad, k2, rec_i, rec_o, pocket, work, False)
    for i in range(n):
        yt[i] = y[i] + hs * (_A31 * k1[i] + _A32 * k2[i])
    rhs_into(yt, par, quad, k3, rec_i, rec_o, pocket, work, False)
    for i in range(n):
        yt[i] = y[i] + hs * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
    rhs_into(yt, par, quad, k4, rec_i, rec_o, pocket, work, False)
    for i in range(n):
        yt[i] = y[i] + hs * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
    rhs_into(yt, par, quad, k5, rec_i, rec_o, pocket, work, False)
    for i in range(n):
        yt[i] = y[i] + hs * (
            _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
        )
    rhs_into(yt, par, quad, k6, rec_i, rec_o, pocket, work, False)
    for i in range(n):
        ynew[i] = y[i] + hs * (
            _A71 * k1[i] + _A73 * k3[i] + _A74 * k4[i] + _A75 * k5[i] + _A76 * k6[i]
        )
    rhs_into(ynew, par, quad, k7, rec_i, rec_o, pocket, work, False)


@njit(cache=True)
def dp5_error(hs, k1, k3, k4, k5, k6, k7, scale, tol):
    """Error norm of a Dormand–Prince step: max |err_i| / (tol scale_i) (NaN kept)."""
    err = 0.0
    for i in range(k1.shape[0]):
        e = hs * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
        r = abs(e) / (tol * scale[i])
        if r > err or r != r:  # keep a NaN: it must reach the finiteness check
            err = r
            if r != r:
                break
    return err


@njit(cache=True)
def dp5_dense(y, ynew, hs, th, k1, k3, k4, k5, k6, k7, out):
    """``out`` <- the continuous extension of a Dormand–Prince step at ``th`` in [0, 1]."""
    th1 = 1.0 - th
    for i in range(y.shape[0]):
        r2 = ynew[i] - y[i]
        r3 = hs * k1[i] - r2
        r4 = r2 - hs * k7[i] - r3
        r5 = hs * (
            _D1 * k1[i] + _D3 * k3[i] + _D4 * k4[i] + _D5 * k5[i] + _D6 * k6[i] + _D7 * k7[i]
        )
        out[i] = y[i] + th * (r2 + th1 * (r3 + th * (r4 + th1 * r5)))


@njit(cache=True)
def advance(
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
):
    """Integrate from ``t`` through every time in ``t_out`` (increasing, all after ``t``),
    storing the state at each in ``out_states[k]`` (from the continuous extension, except the
    last, where the integration stops exactly). ``y`` is updated in place. ``counters`` (3,)
    accumulates [accepted steps, rejected steps, rhs evaluations].

    Returns (status, t, h, n_done): the status code, the time reached, the step size to continue
    with, and how many output samples were written.
    """
    n = y.shape[0]
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    k7 = np.empty(n)
    yt = np.empty(n)
    ynew = np.empty(n)
    scratch = rhs_work(int(par.ball_count))
    rhs_into(y, par, quad, k1, rec_inner, rec_outer, pocket, scratch, False)
    counters[2] += 1
    err_old = 1e-4
    steps = 0
    n_done = 0
    n_out = t_out.shape[0]
    if n_out == 0:
        return STATUS_OK, t, h, 0
    t_end = t_out[n_out - 1]
    while t < t_end:
        if steps >= max_steps:
            return STATUS_TOO_MANY_STEPS, t, h, n_done
        clipped = False
        hs = h
        if t + hs >= t_end:
            hs = t_end - t
            clipped = True
        dp5_stages(
            y, hs, k1, k2, k3, k4, k5, k6, k7, yt, ynew, par, quad, rec_inner, rec_outer, pocket,
            scratch,
        )  # fmt: skip
        counters[2] += 6
        steps += 1
        err = dp5_error(hs, k1, k3, k4, k5, k6, k7, scale, tol)
        if not (err < 1e300):  # NaN/inf in the new state reaches err through k7
            # NaN/inf somewhere: retry with a much smaller step, give up below h_min
            h = 0.1 * hs
            counters[1] += 1
            if h < h_min:
                return STATUS_NOT_FINITE, t, h, n_done
            continue
        if err <= 1.0:
            # accept; PI controller (Hairer's dopri5: beta = 0.04, alpha = 0.2 - 0.75 beta)
            fac = 0.9 * err ** (-0.17) * err_old**0.04 if err > 0.0 else 5.0
            fac = min(5.0, max(0.2, fac))
            err_old = max(err, 1e-4)
            t_new = t_end if clipped else t + hs
            # outputs inside the step from the continuous extension
            while n_done < n_out - 1 and t_out[n_done] <= t_new:
                th = (t_out[n_done] - t) / hs
                dp5_dense(y, ynew, hs, th, k1, k3, k4, k5, k6, k7, out_states[n_done])
                n_done += 1
            t = t_new
            for i in range(n):
                y[i] = ynew[i]
            if not post_step(y, par, rec_inner, rec_outer):
                return STATUS_BALL_ESCAPED, t, h, n_done
            # FSAL: k7 is f(ynew); the post-step projection changes y slightly, so re-use k7
            for i in range(n):
                k1[i] = k7[i]
            counters[0] += 1
            if not clipped or hs * fac > h:
                h = hs * fac
        else:
            fac = max(0.2, 0.9 * err ** (-0.2))
            h = hs * fac
            counters[1] += 1
            if h < h_min:
                return STATUS_STEP_COLLAPSE, t, h, n_done
    for i in range(n):
        out_states[n_out - 1, i] = y[i]
    return STATUS_OK, t, h, n_out
