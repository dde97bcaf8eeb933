"""Additive (implicit–explicit) Runge–Kutta integrator: the cage's guiding-land film implicit,
everything else explicit (method "imex"); and the default method "auto" that switches between it
and the explicit Dormand–Prince step (:mod:`.dopri5`); compiled with numba.

A cage running in its guiding land near the land (eccentricity above about 0.95 of the clearance)
is held by the film's squeeze damping, which on the light cage is an overdamped mode of the cage's
radial velocity of about -1.5e6 1/s on the 218 heavy case: it sets the explicit step there
(docs/numerics.md). The right-hand side is split exactly as

    f(Y) = f_E(Y) + f_I(Y),   f_I(Y) = P A P (Y - y_n),   f_E = f - f_I,

where P selects the cage's velocity (3 slots; one such block per cage, ``Imex.cages``) and A is
the derivative of the cage's acceleration with respect to its velocity through the guiding-land
force (:func:`kernels.cage_land`, forward differences at the step's start, no right-hand-side
evaluation; :func:`cage_velocity_jacobian` can add the pockets' forces, see ``LAND_POCKETS``). Any
A keeps the order (the split is exact); an A close to the true block removes the stability limit of
the film mode.

Method: ARK4(3)6L[2]SA of Kennedy & Carpenter (Appl. Numer. Math. 44, 2003, 139–181): an explicit
tableau coupled to an L-stable ESDIRK (gamma = 1/4), sharing b and c; order 4, embedded order 3;
six right-hand-side evaluations per accepted step (five on a rejected one). Each implicit stage
solves a 3 x 3 system per block. PI step control with exponent 1/4 (:mod:`.control`). Output times
inside a step are filled by cubic Hermite interpolation of the step's end values and slopes (local
error O(h^4), no extra evaluation).

Method "auto" (``Imex.switch`` > 0): a step is an explicit Dormand–Prince step (its own error
estimate, step control and continuous extension) while its size times the spectral bound of A
stays at or below ``SWITCH_BOUND``, an additive step otherwise, with hysteresis (``SWITCH_BACK``).
Where the cage is not near its land (the spindle cases) every step is explicit.
"""

from __future__ import annotations

from functools import partial
from typing import NamedTuple

import numpy as np
from numba import njit

from ..kernels import cage_land, cage_pocket
from ..layout import BALL_STRIDE, C_VEL, cage_base
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
from .dopri5 import ALPHA, BETA, REJECT_EXPONENT, STAGES, dp5_accept, dp5_attempt
from .model import after_step, evaluate, scratch
from .registry import Stepper

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
    pockets at ``y``, with the ring and cage frames and the ring speeds held in ``scratch`` by the
    last right-hand-side evaluation."""
    z = int(par.ball_count)
    work = scratch.contact
    pk = scratch.pocket
    ld = scratch.land
    speed = scratch.ring_speed
    cage_land(y, cb, scratch.inner_origin, scratch.inner_vel, speed[0], speed[1], par, work, ld)
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


class Imex(NamedTuple):
    """The method's part of the workspace: the additive pair, the switch and the implicit
    blocks' scratch."""

    explicit: np.ndarray  # (s, s) explicit stage matrix
    c: np.ndarray  # (s,) stage times as fractions of the step (row sums of either matrix)
    implicit: np.ndarray  # (s, s) implicit stage matrix
    b: np.ndarray  # (s,) weights
    e: np.ndarray  # (s,) weights minus the embedded weights
    order: int  # order of the embedded solution + 1
    switch: float  # "auto": the step x spectral bound above which a step is additive; 0: always
    switch_back: float  # "auto": ... below which explicit steps resume after an additive one
    cages: np.ndarray  # (blocks,) first slot of each cage's state block (its velocity: + C_VEL)
    jac: np.ndarray  # (blocks, 3, 3) d(cage acceleration)/d(cage velocity) [1/s]
    lu: np.ndarray  # (blocks, 3, 3) LU factors of I - h gamma jac
    fi: np.ndarray  # (s, blocks, 3) implicit part of the right-hand side at the stages
    rr: np.ndarray  # (3,) scratch
    dd: np.ndarray  # (3,)
    base: np.ndarray  # (3,)
    moved: np.ndarray  # (3,)


def imex_workspace(model, n, t=0.0, h=0.0, switch=0.0, switch_back=0.0):
    """Workspace of :func:`advance` for a state of ``n`` components; ``switch``,
    ``switch_back``: those of :class:`Imex` (0: every step additive)."""
    ark = ark436l2sa()
    s = ark.b.shape[0]
    par = model.par
    cages = np.array([cage_base(int(par.ball_count))] if par.cage else [], dtype=np.int64)
    blocks = cages.shape[0]
    method = Imex(
        ark.explicit,
        ark.explicit.sum(axis=1),
        ark.implicit,
        ark.b,
        ark.e,
        ark.order,
        float(switch),
        float(switch_back),
        cages,
        np.zeros((blocks, 3, 3)),
        np.empty((blocks, 3, 3)),
        np.zeros((s, blocks, 3)),
        np.empty(3),
        np.empty(3),
        np.empty(3),
        np.empty(3),
    )
    return workspace(n, max(s, STAGES), scratch(model), method, t, h)


@njit(cache=True)
def land_jacobians(y, model, work, control):
    """``work.method.jac[b]`` <- the land block of each cage at ``y``."""
    m = work.method
    for b in range(m.cages.shape[0]):
        cb = m.cages[b]
        dv = JACOBIAN_STEP * control.scale[cb + C_VEL]
        cage_velocity_jacobian(
            y, cb, model.par, work.rhs, dv, LAND_POCKETS, m.base, m.moved, m.jac[b]
        )


@njit(cache=True)
def spectral_bound(m):
    """Largest absolute row sum of the land blocks [1/s]."""
    bound = 0.0
    for b in range(m.cages.shape[0]):
        jac = m.jac[b]
        for r in range(3):
            bound = max(bound, abs(jac[r, 0]) + abs(jac[r, 1]) + abs(jac[r, 2]))
    return bound


@njit(cache=True)
def ark_attempt(y, t, hs, top, work, model, control):
    """One additive step of size ``hs`` from ``y`` at ``t`` (``work.stages[0]`` = f(t, y); each
    stage read at its time t + c_s hs, at most ``top``: :func:`.control.stage_time`; the land
    blocks in
    ``work.method.jac``) into ``work.new``; returns its error norm and counts its evaluations."""
    m = work.method
    ae = m.explicit
    ai = m.implicit
    b = m.b
    e = m.e
    k = work.stages
    yt = work.trial
    ynew = work.new
    fi = m.fi
    lu = m.lu
    rr = m.rr
    dd = m.dd
    n = y.shape[0]
    ns = b.shape[0]
    blocks = m.cages.shape[0]
    gamma = ai[1, 1]
    for q in range(blocks):
        jac = m.jac[q]
        for r in range(3):
            for c in range(3):
                lu[q, r, c] = (1.0 if r == c else 0.0) - hs * gamma * jac[r, c]
        _lu3(lu[q])
        for c in range(3):
            fi[0, q, c] = 0.0
    for s in range(1, ns):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += ae[s, j] * k[j, i]
            yt[i] = y[i] + hs * acc
        for q in range(blocks):
            k0 = m.cages[q] + C_VEL  # the implicit slots: cage velocity x, y, z
            jac = m.jac[q]
            for c in range(3):
                acc = yt[k0 + c] - y[k0 + c]
                for j in range(s):
                    acc += hs * (ai[s, j] - ae[s, j]) * fi[j, q, c]
                rr[c] = acc
            _solve3(lu[q], rr, dd)
            for c in range(3):
                yt[k0 + c] = y[k0 + c] + dd[c]
            for r in range(3):
                fi[s, q, r] = jac[r, 0] * dd[0] + jac[r, 1] * dd[1] + jac[r, 2] * dd[2]
        evaluate(yt, stage_time(t, m.c[s], hs, top), model, k[s], work.rhs)
    work.progress[0].rhs_evaluations += ns - 1
    err = 0.0
    for i in range(n):
        acc = 0.0
        est = 0.0
        for j in range(ns):
            acc += b[j] * k[j, i]
            est += e[j] * k[j, i]
        ynew[i] = y[i] + hs * acc
        err = worse(err, hs * est, i, control)
    return err


@njit(cache=True)
def ark_accept(y, t, t_new, hs, times, outputs, written, work, model):
    """Take the attempted additive step from ``t`` to ``t_new``: move ``y`` to the new state, run
    the model's projection, evaluate f there (``work.stages[0]``) and fill the output times up to
    ``t_new`` (before the last) by cubic Hermite interpolation. Returns (samples written, False
    when the state left the model's domain)."""
    k = work.stages
    yt = work.trial
    ynew = work.new
    n = y.shape[0]
    n_out = times.shape[0]
    for i in range(n):
        yt[i] = y[i]  # keep y_n for the outputs inside the step
        y[i] = ynew[i]
    if not after_step(y, model):
        return written, False
    for i in range(n):
        ynew[i] = k[0, i]  # keep f(y_n)
    evaluate(y, t_new, model, k[0], work.rhs)
    work.progress[0].rhs_evaluations += 1
    # outputs inside the step: cubic Hermite interpolation of y_n, y, f(y_n), f(y)
    while written < n_out - 1 and times[written] <= t_new:
        th = (times[written] - t) / hs
        h00 = (1.0 + 2.0 * th) * (1.0 - th) ** 2
        h10 = th * (1.0 - th) ** 2 * hs
        h01 = th * th * (3.0 - 2.0 * th)
        h11 = th * th * (th - 1.0) * hs
        for i in range(n):
            outputs[written, i] = h00 * yt[i] + h10 * ynew[i] + h01 * y[i] + h11 * k[0, i]
        written += 1
    return written, True


@njit(cache=True)
def advance(y, times, outputs, control, work, model):
    """Integrate through every time in ``times`` (see :mod:`.control`) with additive steps, or
    (``work.method.switch`` > 0, method "auto") with explicit Dormand–Prince steps wherever the
    land blocks allow them."""
    m = work.method
    progress = work.progress[0]
    t, h, t_end, event, err_old, done = start(y, times, control, work, model)
    if done:
        return
    additive = False  # the method of the last step (switching: with hysteresis)
    steps = 0
    written = np.int64(0)  # not a literal: one compiled variant of the kernels it is passed to
    exponent = 0.7 / m.order
    memory = 0.4 / m.order
    while t < t_end:
        if steps >= control.max_steps:
            finish(progress, STATUS_TOO_MANY_STEPS, t, h, written)
            return
        stop, clipped, hs = clip_step(control, event, t, h, t_end)
        top = last_stage_time(t, hs, stop, clipped)
        land_jacobians(y, model, work, control)
        if m.switch > 0.0:
            additive = hs * spectral_bound(m) > (m.switch_back if additive else m.switch)
        else:
            additive = True
        if additive:
            err = ark_attempt(y, t, hs, top, work, model, control)
            accepted, status, h_next = judge(err, hs, control, 1.0 / m.order)
        else:
            err = dp5_attempt(y, t, hs, top, work, model, control)
            accepted, status, h_next = judge(err, hs, control, REJECT_EXPONENT)
        steps += 1
        if not accepted:
            h = h_next
            if rejected(progress, status, t, h, written):
                return
            continue
        t_new = stop if clipped else t + hs
        if additive:
            fac, err_old = growth(err, err_old, control, exponent, memory)
            written, inside = ark_accept(y, t, t_new, hs, times, outputs, written, work, model)
        else:
            fac, err_old = growth(err, err_old, control, ALPHA, BETA)
            written, inside = dp5_accept(y, t, t_new, hs, times, outputs, written, work, model)
        t = t_new
        if not inside:
            finish(progress, STATUS_BALL_ESCAPED, t, h, written)
            return
        h, event = passed(y, model, work, control, h, hs, fac, clipped, stop, t, t_end, event)
    reached_end(y, outputs, times.shape[0], progress, t, h)


_NOTES = {
    "auto": (
        "Dormand-Prince 5(4), with additive Runge-Kutta ARK4(3)6L[2]SA steps (the cage's "
        "guiding-land film implicit) where the film limits the explicit step; PI step control"
    ),
    "imex": (
        "additive Runge-Kutta ARK4(3)6L[2]SA, the cage's guiding-land film implicit, PI step "
        "control"
    ),
}


def build(variant: str) -> Stepper:
    """The stepper of method "imex" (every step additive) or "auto" (switching)."""
    switch = (SWITCH_BOUND, SWITCH_BACK) if variant == "auto" else (0.0, 0.0)
    return Stepper(
        advance, partial(imex_workspace, switch=switch[0], switch_back=switch[1]), _NOTES[variant]
    )
