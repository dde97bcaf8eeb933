"""What every integration method of the dynamic model shares: the step-control record, the
workspace record, the progress record with the status codes, the error norm and the rules that
accept or reject a step and choose the next step size; compiled with numba.

A stepper (one module per method, listed in :mod:`.registry`) has one entry point

    advance(y, times, outputs, control, work, model)

that integrates from ``work.progress[0]["t"]`` through every time in ``times`` (increasing, all
after that time), stores the state at each in ``outputs[k]`` and updates ``y`` in place and the
progress record (time reached, step size to continue with, samples written, status, counters).
The state and its time derivative are in the model's units (SI, :mod:`..layout`); times in s.

Error norm: max over components of |err_i| / (tolerance * scale_i), where ``scale_i`` is the
characteristic magnitude of component i (``simulate.state_scales``): the error control is absolute
per physical quantity. Step-size control: PI controller on accepted steps (exponents given by the
method), a shrink on rejected ones, a stronger shrink when the trial state is not finite; the run
stops with a status when the step falls below ``h_min`` or the step budget of a call is spent.

Step boundaries: a step never passes the last output time of a call (where the integration stops
exactly) nor any time in ``control.event_times`` (where inputs that vary in time may jump: the
stepper lands on the event and evaluates the right-hand side afresh there). Each stage reads the
model at its own time; the stages of a step cut at an event read it just before the event
(:func:`last_stage_time`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from .model import evaluate

# Status codes of the progress record.
STATUS_OK = 0
STATUS_NOT_FINITE = 1
STATUS_STEP_COLLAPSE = 2
STATUS_BALL_ESCAPED = 3
STATUS_TOO_MANY_STEPS = 4

#: Progress of an integration, one record (a structured array of length 1 in the workspace):
#: time reached [s], step size to continue with [s], accepted and rejected steps and right-hand-side
#: evaluations (summed over calls), output samples written by the last call and its status.
PROGRESS = np.dtype(
    [
        ("t", np.float64),
        ("h", np.float64),
        ("accepted", np.int64),
        ("rejected", np.int64),
        ("rhs_evaluations", np.int64),
        ("written", np.int64),
        ("status", np.int64),
    ]
)


class StepControl(NamedTuple):
    """How a stepper controls its step (SI units; every method reads the same record)."""

    tolerance: float  # local error tolerance, relative to ``scale``
    scale: np.ndarray  # (n,) characteristic magnitude of each state component (its units)
    h_min: float  # smallest step [s]: below it the run stops (STATUS_STEP_COLLAPSE/NOT_FINITE)
    max_steps: int  # step attempts allowed in one call of ``advance``
    event_times: np.ndarray  # (m,) increasing times [s] that every step ends on, never passes
    safety: float = 0.9  # factor on the step size the error estimate asks for
    grow_max: float = 5.0  # largest growth of the step after an accepted step
    shrink_min: float = 0.2  # smallest factor on the step after an accepted or rejected step
    nan_shrink: float = 0.1  # factor on the step after a step with a non-finite state
    error_floor: float = 1e-4  # smallest previous error the PI controller remembers


class Workspace(NamedTuple):
    """Arrays a stepper works in, made once per run (:func:`workspace`)."""

    stages: np.ndarray  # (stage_count, n) right-hand sides at the stages [state units / s]
    trial: np.ndarray  # (n,) a stage's state
    new: np.ndarray  # (n,) the state at the end of the step
    rhs: tuple  # the model's scratch of one right-hand-side evaluation (.model.scratch)
    progress: np.ndarray  # (1,) PROGRESS record
    method: tuple  # the method's own constants and scratch (a record of its stepper module)


def workspace(n, stage_count, rhs, method, t=0.0, h=0.0) -> Workspace:
    """A :class:`Workspace` for a state of ``n`` components, starting at time ``t`` with step
    ``h`` [s]."""
    progress = np.zeros(1, dtype=PROGRESS)
    progress[0]["t"] = t
    progress[0]["h"] = h
    return Workspace(np.empty((stage_count, n)), np.empty(n), np.empty(n), rhs, progress, method)


def step_control(tolerance, scale, h_min, max_steps, event_times=()) -> StepControl:
    """A :class:`StepControl` with the default safety factors; ``event_times`` [s] increasing."""
    events = np.ascontiguousarray(event_times, dtype=np.float64).reshape(-1)
    if events.size > 1 and not np.all(np.diff(events) > 0.0):
        raise ValueError("step_control: event_times must be strictly increasing")
    return StepControl(float(tolerance), scale, float(h_min), int(max_steps), events)


@njit(cache=True)
def finish(progress, status, t, h, written):
    """Store the outcome of a call in the progress record; returns nothing."""
    progress.t = t
    progress.h = h
    progress.written = written
    progress.status = status


@njit(cache=True)
def first_event(control, t):
    """Index of the first event time after ``t``."""
    return np.searchsorted(control.event_times, t, side="right")


@njit(cache=True)
def boundary(control, event, t_end):
    """The time the next step must not pass: the event ``event`` when it comes before ``t_end``,
    else ``t_end``."""
    if event < control.event_times.shape[0] and control.event_times[event] < t_end:
        return control.event_times[event]
    return t_end


@njit(cache=True)
def past_events(control, event, t):
    """Index of the first event time after ``t``, searching on from ``event``."""
    while event < control.event_times.shape[0] and control.event_times[event] <= t:
        event += 1
    return event


@njit(cache=True)
def worse(err, value, i, control):
    """max(err, |value| / (tolerance scale_i)), keeping a NaN (it must reach the finiteness
    check)."""
    r = abs(value) / (control.tolerance * control.scale[i])
    if r > err or r != r:
        return r
    return err


@njit(cache=True)
def judge(err, hs, control, reject_exponent):
    """Verdict on a step of size ``hs`` with error norm ``err``: (accepted, status, h). Accepted:
    (True, STATUS_OK, hs). Rejected: the step to retry with; status STATUS_OK to retry, else the
    status to stop with (the step fell below ``h_min``)."""
    if not (err < 1e300):  # NaN/inf in the trial state reaches err through its last stage
        h = control.nan_shrink * hs
        return False, STATUS_NOT_FINITE if h < control.h_min else STATUS_OK, h
    if err <= 1.0:
        return True, STATUS_OK, hs
    h = hs * max(control.shrink_min, control.safety * err ** (-reject_exponent))
    return False, STATUS_STEP_COLLAPSE if h < control.h_min else STATUS_OK, h


@njit(cache=True)
def growth(err, err_old, control, alpha, beta):
    """(factor on the step after an accepted step, error to remember): PI controller
    safety * err^-alpha * err_old^beta, within [shrink_min, grow_max]."""
    fac = control.safety * err ** (-alpha) * err_old**beta if err > 0.0 else control.grow_max
    fac = min(control.grow_max, max(control.shrink_min, fac))
    return fac, max(err, control.error_floor)


@njit(cache=True)
def next_step(h, hs, fac, clipped):
    """Step size after an accepted step ``hs`` with growth ``fac``: a step clipped to a boundary
    keeps the larger step it was cut from."""
    if not clipped or hs * fac > h:
        return hs * fac
    return h


# ---- the bookkeeping of a call of ``advance``, the same in every method -------------------------
@njit(cache=True)
def start(y, times, control, work, model):
    """Begin a call of ``advance``: f(y) into ``work.stages[0]`` (counted). Returns (t, h, the last
    output time, the index of the next event, the error the PI controller remembers, done);
    ``done`` when ``times`` is empty: the outcome (nothing written) is then stored."""
    progress = work.progress[0]
    t = progress.t
    h = progress.h
    evaluate(y, t, model, work.stages[0], work.rhs)
    progress.rhs_evaluations += 1
    n_out = times.shape[0]
    if n_out == 0:
        finish(progress, STATUS_OK, t, h, 0)
        return t, h, t, first_event(control, t), control.error_floor, True
    return t, h, times[n_out - 1], first_event(control, t), control.error_floor, False


@njit(cache=True)
def clip_step(control, event, t, h, t_end):
    """(where the step from ``t`` must end at the latest, whether step ``h`` is cut there, the step
    to attempt) [s]."""
    stop = boundary(control, event, t_end)
    clipped = t + h >= stop
    return stop, clipped, stop - t if clipped else h


@njit(cache=True)
def last_stage_time(t, hs, stop, clipped):
    """The latest time a stage of the step ``hs`` from ``t`` reads the model at: just before
    ``stop`` when the step is cut there (an input may jump at an event: the step sees the values
    before it, the next step those from it on), else t + hs."""
    if clipped:
        return np.nextafter(stop, -np.inf)
    return t + hs


@njit(cache=True)
def stage_time(t, c, hs, top):
    """Time [s] of the stage at fraction ``c`` of the step ``hs`` from ``t``, at most ``top``."""
    return min(t + c * hs, top)


@njit(cache=True)
def rejected(progress, status, t, h, written):
    """Count a rejected step; True when the run stops on it (``status`` is not STATUS_OK: the
    outcome is then stored with the step ``h`` it asked for)."""
    progress.rejected += 1
    if status != STATUS_OK:
        finish(progress, status, t, h, written)
        return True
    return False


@njit(cache=True)
def passed(y, model, work, control, h, hs, fac, clipped, stop, t, t_end, event):
    """Count an accepted step ``hs`` that ended at ``t`` inside the model's domain. Returns (the
    next step size, the index of the next event); on an event before ``t_end`` the inputs may
    change, so f(y) is evaluated afresh into ``work.stages[0]`` (counted)."""
    progress = work.progress[0]
    progress.accepted += 1
    h = next_step(h, hs, fac, clipped)
    if clipped and stop < t_end:
        event = past_events(control, event, t)
        evaluate(y, t, model, work.stages[0], work.rhs)
        progress.rhs_evaluations += 1
    return h, event


@njit(cache=True)
def reached_end(y, outputs, n_out, progress, t, h):
    """The last output is the state where the integration stops exactly; store the outcome."""
    for i in range(y.shape[0]):
        outputs[n_out - 1, i] = y[i]
    finish(progress, STATUS_OK, t, h, n_out)
