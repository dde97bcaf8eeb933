"""Dormand–Prince 5(4): explicit Runge–Kutta pair with PI step control, compiled with numba
(method "dopri5"; also the explicit step of "auto", :mod:`.imex`).

Six right-hand-side evaluations per step (the last stage is f at the new state, re-used as the
first of the next step). Output times inside a step are filled from the method's continuous
extension (Hairer, Nørsett & Wanner I, §II.6: order 4, from the seven stages already computed, no
extra evaluation). Step control, error norm and boundaries: :mod:`.control`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from .control import (
    STATUS_BALL_ESCAPED,
    STATUS_TOO_MANY_STEPS,
    clip_step,
    finish,
    growth,
    judge,
    last_stage_time,
    passed,
    reached_end,
    rejected,
    stage_time,
    start,
    workspace,
    worse,
)
from .model import after_step, evaluate, scratch
from .registry import Stepper

#: PI controller of an accepted step (Hairer's dopri5: beta = 0.04, alpha = 0.2 - 0.75 beta) and
#: the exponent of the shrink after a rejected one (1 / (embedded order + 1))
ALPHA = 0.17
BETA = 0.04
REJECT_EXPONENT = 0.2
#: right-hand sides a step keeps: its seven stages
STAGES = 7

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
def dp5_stages(y, t, hs, top, k1, k2, k3, k4, k5, k6, k7, yt, ynew, model, rhs):
    """One Dormand–Prince step of size ``hs`` from ``y`` at time ``t`` with ``k1`` = f(t, y),
    each stage read at its own time t + c_i hs, at most ``top`` (:func:`.control.stage_time`):
    the stages k2..k7
    and the new state ``ynew`` (k7 = f(ynew)); six right-hand-side evaluations (``model``,
    ``rhs``: :mod:`.model`)."""
    n = y.shape[0]
    for i in range(n):
        yt[i] = y[i] + hs * _A21 * k1[i]
    evaluate(yt, stage_time(t, _C2, hs, top), model, k2, rhs)
    for i in range(n):
        yt[i] = y[i] + hs * (_A31 * k1[i] + _A32 * k2[i])
    evaluate(yt, stage_time(t, _C3, hs, top), model, k3, rhs)
    for i in range(n):
        yt[i] = y[i] + hs * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
    evaluate(yt, stage_time(t, _C4, hs, top), model, k4, rhs)
    for i in range(n):
        yt[i] = y[i] + hs * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
    evaluate(yt, stage_time(t, _C5, hs, top), model, k5, rhs)
    for i in range(n):
        yt[i] = y[i] + hs * (
            _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
        )
    evaluate(yt, stage_time(t, 1.0, hs, top), model, k6, rhs)
    for i in range(n):
        ynew[i] = y[i] + hs * (
            _A71 * k1[i] + _A73 * k3[i] + _A74 * k4[i] + _A75 * k5[i] + _A76 * k6[i]
        )
    evaluate(ynew, stage_time(t, 1.0, hs, top), model, k7, rhs)


@njit(cache=True)
def dp5_error(hs, k1, k3, k4, k5, k6, k7, control):
    """Error norm of a Dormand–Prince step (:func:`.control.worse`; NaN kept)."""
    err = 0.0
    for i in range(k1.shape[0]):
        e = hs * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
        err = worse(err, e, i, control)
        if err != err:
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
def dp5_attempt(y, t, hs, top, work, model, control):
    """One step of size ``hs`` from ``y`` at ``t`` (``work.stages[0]`` = f(t, y); stages read at
    most at ``top``) into ``work.new``; returns
    its error norm and counts its six evaluations."""
    k = work.stages
    dp5_stages(
        y,
        t,
        hs,
        top,
        k[0],
        k[1],
        k[2],
        k[3],
        k[4],
        k[5],
        k[6],
        work.trial,
        work.new,
        model,
        work.rhs,
    )
    work.progress[0].rhs_evaluations += 6
    return dp5_error(hs, k[0], k[2], k[3], k[4], k[5], k[6], control)


@njit(cache=True)
def dp5_accept(y, t, t_new, hs, times, outputs, written, work, model):
    """Take the attempted step from ``t`` to ``t_new``: fill the output times up to ``t_new``
    (before the last) from the continuous extension, move ``y`` to the new state and run the
    model's projection. Returns (samples written, False when the state left the model's domain).
    """
    k = work.stages
    ynew = work.new
    n = y.shape[0]
    n_out = times.shape[0]
    while written < n_out - 1 and times[written] <= t_new:
        th = (times[written] - t) / hs
        dp5_dense(y, ynew, hs, th, k[0], k[2], k[3], k[4], k[5], k[6], outputs[written])
        written += 1
    for i in range(n):
        y[i] = ynew[i]
    if not after_step(y, model):
        return written, False
    # FSAL: k7 is f(ynew); the post-step projection changes y slightly, so re-use k7
    for i in range(n):
        k[0, i] = k[6, i]
    return written, True


@njit(cache=True)
def advance(y, times, outputs, control, work, model):
    """Integrate through every time in ``times`` (see :mod:`.control`); the last output is the
    state where the integration stops exactly."""
    progress = work.progress[0]
    t, h, t_end, event, err_old, done = start(y, times, control, work, model)
    if done:
        return
    steps = 0
    written = np.int64(0)  # not a literal: one compiled variant of the kernels it is passed to
    while t < t_end:
        if steps >= control.max_steps:
            finish(progress, STATUS_TOO_MANY_STEPS, t, h, written)
            return
        stop, clipped, hs = clip_step(control, event, t, h, t_end)
        top = last_stage_time(t, hs, stop, clipped)
        err = dp5_attempt(y, t, hs, top, work, model, control)
        steps += 1
        accepted, status, h_next = judge(err, hs, control, REJECT_EXPONENT)
        if not accepted:
            h = h_next
            if rejected(progress, status, t, h, written):
                return
            continue
        fac, err_old = growth(err, err_old, control, ALPHA, BETA)
        t_new = stop if clipped else t + hs
        written, inside = dp5_accept(y, t, t_new, hs, times, outputs, written, work, model)
        t = t_new
        if not inside:
            finish(progress, STATUS_BALL_ESCAPED, t, h, written)
            return
        h, event = passed(y, model, work, control, h, hs, fac, clipped, stop, t, t_end, event)
    reached_end(y, outputs, times.shape[0], progress, t, h)


class Dopri5(NamedTuple):
    """The method's part of the workspace: none."""


def dopri5_workspace(model, n, t=0.0, h=0.0):
    """Workspace of :func:`advance` for a state of ``n`` components."""
    return workspace(n, STAGES, scratch(model), Dopri5(), t, h)


def build(variant: str) -> Stepper:
    """The stepper of method "dopri5" (:mod:`.registry`)."""
    return Stepper(advance, dopri5_workspace, "Dormand-Prince 5(4), PI step control")
