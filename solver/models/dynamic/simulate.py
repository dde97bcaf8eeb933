"""Driver of the dynamic model: ``simulate(case, progress=None, cancel=None, options=None)``.

The numba integrator advances in chunks of ``options.chunk_samples`` output samples; between chunks
the driver reports progress and checks for cancellation. Outcomes:

- finished: Dataset with attrs ``complete = 1``, ``stop_reason = "finished"``;
- cancelled (``cancel()`` true or ``cancel.is_set()``): the samples computed so far,
  ``complete = 0``, ``stop_reason = "cancelled"``;
- diverged (NaN, step-size collapse, a ball leaving the raceways, step budget exhausted):
  :class:`solver.errors.SimulationDiverged` is raised with the likely cause in its message and the
  partial Dataset (``complete = 0``, ``stop_reason`` = the message) in its ``dataset`` attribute.
"""

from __future__ import annotations

import math
import os
import time as _time
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from solver.case import dynamic_problems
from solver.case.validate import equal_speeds_problem, run_length_problems
from solver.errors import CaseError, NoSolutionError, Problem, SimulationDiverged
from solver.history import CH_INNER_SPEED, CH_OUTER_SPEED, N_CHANNELS, event_times
from solver.inputs import Inputs, rad_s_to_rpm, to_inputs
from solver.physics.traction import NODE_COLUMNS

from . import layout as L
from .initial import initial_state, initial_state_from_quasistatic, quasistatic_solution
from .integrate import stepper
from .integrate.control import (
    STATUS_BALL_ESCAPED,
    STATUS_NOT_FINITE,
    STATUS_OK,
    STATUS_STEP_COLLAPSE,
    STATUS_TOO_MANY_STEPS,
    step_control,
)
from .integrate.model import bearing_model
from .observe import channel_series
from .options import CASE_OVERRIDES, SimulationOptions
from .output import build_dataset
from .params import build_params, build_quadrature, model_history

_DIVERGENCE_CAUSES = MappingProxyType(
    {
        STATUS_NOT_FINITE: (
            "the state became non-finite (NaN/inf): a contact force blew up, usually a too-light "
            "cage or an overload driving a ball through a race"
        ),
        STATUS_STEP_COLLAPSE: (
            "the integration step collapsed below {h_min:.1e} s: the contact forces are too stiff "
            "or discontinuous (cage pocket impacts or a ball running onto a shoulder); loosen the "
            "tolerance or check the cage clearances"
        ),
        STATUS_BALL_ESCAPED: (
            "a ball left the raceways (centre more than D/4 from the pitch circle or a deflection "
            "above 2 % of D): the load is too large for the bearing or nothing holds the balls"
        ),
        STATUS_TOO_MANY_STEPS: (
            "the step budget of a chunk ({max_steps} steps) was exhausted: the model is too stiff "
            "for the requested tolerance"
        ),
    }
)


def _is_cancelled(cancel) -> bool:
    if cancel is None:
        return False
    is_set = getattr(cancel, "is_set", None)
    if callable(is_set):
        return bool(is_set())
    return bool(cancel())


def state_scales(history, par, y0: np.ndarray) -> np.ndarray:
    """Characteristic magnitudes of the state components for the error norm (the contacts at
    ``y0`` under the operating history ``history`` at t = 0).

    delta_ref = largest contact deflection at the start (>= 0.1 um); V = delta_ref * omega_n with
    the ball's contact natural frequency omega_n = sqrt(2 k_lin / m), k_lin = 1.5 Q / delta.
    Positions scale with delta_ref, velocities with V, angles with delta_ref over the lever arm.
    """
    z = int(par.ball_count)
    n = y0.shape[0]
    rec_i = np.zeros((z, L.N_CONTACT_RECORD))
    rec_o = np.zeros((z, L.N_CONTACT_RECORD))
    from .kernels import rhs

    no_nodes = np.zeros((1, NODE_COLUMNS))  # traction weight 0
    rhs(y0, 0.0, history, par, no_nodes, np.zeros(n), rec_i, rec_o, np.zeros(z))
    defl = np.concatenate((rec_i[:, L.K_DEFLECTION], rec_o[:, L.K_DEFLECTION]))
    load = np.concatenate((rec_i[:, L.K_ELASTIC], rec_o[:, L.K_ELASTIC]))
    k = int(np.argmax(defl))
    delta_ref = max(float(defl[k]), 1e-7)
    k_lin = 1.5 * load[k] / defl[k] if defl[k] > 0 else 1e7
    omega_n = math.sqrt(2.0 * k_lin / par.ball_mass)
    v = delta_ref * omega_n
    rball = 0.5 * par.ball_diameter
    rpitch = 0.5 * par.pitch_diameter
    s = np.empty(n)
    for j in range(z):
        b = L.ball_base(j)
        s[b + L.B_POS : b + L.B_POS + 3] = delta_ref
        s[b + L.B_VEL : b + L.B_VEL + 3] = v
        s[b + L.B_QUAT : b + L.B_QUAT + 4] = delta_ref / rball
        s[b + L.B_OMEGA : b + L.B_OMEGA + 3] = v / rball
    rb = L.ring_base(z)
    s[rb + L.R_POS : rb + L.R_POS + 3] = delta_ref
    s[rb + L.R_VEL : rb + L.R_VEL + 3] = v
    s[rb + L.R_TILT : rb + L.R_TILT + 2] = delta_ref / rpitch
    s[rb + L.R_TILT_RATE : rb + L.R_TILT_RATE + 2] = v / rpitch
    s[rb + L.R_PHI_INNER] = 1.0
    s[rb + L.R_PHI_OUTER] = 1.0
    cb = L.cage_base(z)
    s[cb + L.C_POS : cb + L.C_POS + 3] = 10.0 * delta_ref
    s[cb + L.C_VEL : cb + L.C_VEL + 3] = 10.0 * v
    s[cb + L.C_ANGLE] = 10.0 * delta_ref / rpitch
    s[cb + L.C_SPEED] = 10.0 * v / rpitch
    s[cb + L.C_TILT : cb + L.C_TILT + 2] = 10.0 * delta_ref / rpitch
    s[cb + L.C_TILT_RATE : cb + L.C_TILT_RATE + 2] = 10.0 * v / rpitch
    return s


class RunStatistics:
    """Counters of one run (steps, rejected steps, right-hand-side evaluations: the stepper's
    progress record, integrate.control.PROGRESS), wall time and first step [s]."""

    def __init__(self, progress: np.ndarray):
        self.progress = progress
        self.wall_time = 0.0
        self.initial_step = 0.0

    @property
    def steps(self) -> int:
        return int(self.progress[0]["accepted"])

    @property
    def rejected(self) -> int:
        return int(self.progress[0]["rejected"])

    @property
    def rhs_evaluations(self) -> int:
        return int(self.progress[0]["rhs_evaluations"])


def _start(inputs, options, history, par, quad):
    """(initial state, description of the start for the Dataset attrs, the quasi-static solution
    started from or None)."""
    if options.start == "quasistatic":
        try:
            qs = quasistatic_solution(inputs)
        except NoSolutionError as error:
            return (
                initial_state(history, par, quad),
                f"quasi-static solver found no solution ({error}); started from the model's own "
                "force balance (no gyroscopic moment)",
                None,
            )
        return (
            initial_state_from_quasistatic(par, qs),
            "quasi-static Jones-Harris solution (solver.models.quasistatic): ball positions, "
            "orbital and spin speeds, attitude, ring offset and tilt, cage speed",
            qs,
        )
    return (
        initial_state(history, par, quad),
        "the model's own quasi-static force balance (no gyroscopic moment)",
        None,
    )


def _inputs(case) -> Inputs:
    """SI inputs of a Case (a path or a catalogue name is resolved by solver.facade), after the
    dynamic model's own rules (:func:`solver.case.dynamic_problems`, raised as CaseError); Inputs
    as given."""
    if isinstance(case, Inputs):
        return case
    if isinstance(case, str | os.PathLike):
        raise TypeError(
            f"the model takes a Case or Inputs, not {case!r}: solver.simulate resolves a "
            "case-file path or a catalogue name"
        )
    problems = dynamic_problems(case)
    if problems:
        raise CaseError(problems)
    return to_inputs(case)


def _length_names(options: SimulationOptions) -> tuple[str, str]:
    """How the run length's two values are named in messages: the option when it was given,
    else the case key."""
    return tuple(
        f"simulation option {name}"
        if getattr(options, name) is not None
        else CASE_OVERRIDES[name][1]
        for name in ("shaft_revolutions", "samples_per_revolution")
    )


class TimeGrid(NamedTuple):
    """The output times of a run and the shaft period its metrics and messages use."""

    times: np.ndarray  # (S + 1,) output times from 0 [s]
    period: float  # shaft period [s]: at the steady speed, or at the history's mean speed
    per_revolution: float  # samples per shaft revolution (steady) or NaN (a history)

    def reached(self, sample: int) -> str:
        """How far sample ``sample`` is into the run, in words."""
        if math.isfinite(self.per_revolution):
            total = (self.times.size - 1) / self.per_revolution
            return f"{sample / self.per_revolution:.2f} of {total:g} revolutions"
        return f"{self.times[sample]:.4g} of {self.times[-1]:g} s"


def _time_grid(inputs, options, given, history) -> TimeGrid:
    """Output times: a steady case samples ``samples_per_revolution`` times per shaft revolution
    for ``shaft_revolutions``; a case with a history (``inputs.history``) samples
    ``simulation.samples_per_second`` times per second over ``simulation.duration`` [s]."""
    op = inputs.operating
    if inputs.history is None:
        problems = run_length_problems(
            options.shaft_revolutions,
            options.samples_per_revolution,
            int(inputs.geometry.ball_count),
            _length_names(given),
        )
        if problems:
            raise CaseError(problems)
        speed = abs(op.inner_ring_speed - op.outer_ring_speed)
        if not speed > 0.0:  # steady Inputs (a Case was refused by dynamic_problems)
            raise CaseError([equal_speeds_problem(rad_s_to_rpm(op.inner_ring_speed))])
        period = 2.0 * math.pi / speed
        per_rev = options.samples_per_revolution
        n_samples = int(round(options.shaft_revolutions * per_rev))
        return TimeGrid(np.arange(n_samples + 1) * (period / per_rev), period, float(per_rev))
    duration = inputs.simulation.duration
    rate = inputs.simulation.samples_per_second
    problems = [
        Problem(key, f"{key} = {value!r}: a case with time histories needs a positive number")
        for key, value in (
            ("simulation.duration", duration),
            ("simulation.samples_per_second", rate),
        )
        if value is None or not (math.isfinite(value) and value > 0.0)
    ]
    if problems:
        raise CaseError(problems)
    n_samples = max(1, int(round(duration * rate)))
    times = np.linspace(0.0, float(duration), n_samples + 1)
    values = np.empty((N_CHANNELS, times.size))
    channel_series(history, times, values)
    mean = float(np.mean(np.abs(values[CH_INNER_SPEED] - values[CH_OUTER_SPEED])))
    if not mean > 0.0:
        raise CaseError(
            Problem(
                "operating.inner_ring_speed_rpm",
                "the ring speeds' histories never turn the rings relative to each other, so "
                "nothing runs; give the speeds that the run should follow",
            )
        )
    return TimeGrid(times, 2.0 * math.pi / mean, math.nan)


class ChunkRun(NamedTuple):
    """How a run's chunk loop ended (:func:`run_chunks`)."""

    done: int  # stored samples, the start included
    stop_reason: str  # "finished", "cancelled" or the divergence message
    diverged_message: str | None  # the divergence message, None when it did not diverge
    wall_time: float  # wall time of the loop [s]


def run_chunks(method, model, y, grid, states, control, work, options, progress, cancel):
    """Advance ``model`` from state ``y`` over the output times of ``grid`` (:class:`TimeGrid`)
    in chunks of ``options.chunk_samples`` samples, storing them in ``states`` (the start in
    ``states[0]``), with the stepper ``method`` and its workspace ``work``. Between chunks it
    reports progress (``progress(fraction, simulated_time, message)``, None: no reports) and
    checks ``cancel`` (:func:`_is_cancelled`); it stops at the first chunk the stepper ends with
    a status other than OK, with the likely cause in the message."""
    times, period = grid.times, grid.period
    n_samples = times.size - 1
    reached = work.progress  # the stepper's progress record (1,)
    done = 1
    stop_reason = "finished"
    diverged_message = None
    start = _time.perf_counter()
    while done <= n_samples:
        if _is_cancelled(cancel):
            stop_reason = "cancelled"
            break
        stop = min(done + options.chunk_samples, n_samples + 1)
        method.advance(y, times[done:stop], states[done:stop], control, work, model)
        done += int(reached["written"][0])
        status = int(reached["status"][0])
        if status != STATUS_OK:
            t = float(reached["t"][0])
            cause = _DIVERGENCE_CAUSES[status].format(
                h_min=control.h_min, max_steps=options.max_steps_per_chunk
            )
            diverged_message = (
                f"simulation diverged at t = {t:.6g} s ({t / period:.3f} shaft revolutions): "
                f"{cause}"
            )
            stop_reason = diverged_message
            break
        if progress is not None:
            elapsed = _time.perf_counter() - start
            progress(
                (done - 1) / n_samples,
                float(times[done - 1]),
                f"{grid.reached(done - 1)}, {elapsed:.1f} s",
            )
    return ChunkRun(done, stop_reason, diverged_message, _time.perf_counter() - start)


def simulate(case, progress=None, cancel=None, options: SimulationOptions | None = None):
    """Run the dynamic model of ``case`` and return an ``xarray.Dataset`` (results-schema.md).

    ``case``: a :class:`solver.case.Case` (``solver.simulate`` also takes a case-file path or a
    catalogue name; CaseError when the dynamic model cannot run it,
    :func:`solver.case.dynamic_problems`), or :class:`solver.inputs.Inputs`.
    ``progress(fraction, simulated_time, message)`` is called between chunks; ``cancel`` is a
    callable or an Event. ``options``: :class:`SimulationOptions`; None = the case's
    ``[simulation]`` values and the default numerical knobs.
    """
    inputs = _inputs(case)
    given = (options or SimulationOptions()).validated()
    options = given.resolved(inputs.simulation)
    par = build_params(inputs, options)
    history = model_history(inputs)
    grid = _time_grid(inputs, options, given, history)
    times, period = grid.times, grid.period
    n_samples = times.size - 1
    quad = build_quadrature(options, par)
    y, start_note, quasistatic = _start(inputs, options, history, par, quad)
    states = np.empty((n_samples + 1, y.shape[0]))
    states[0] = y
    scale = state_scales(history, par, y)
    # first step: a fraction of the shortest contact period
    omega_n = scale[L.B_VEL] / scale[L.B_POS]
    h = 0.05 / omega_n
    method = stepper(options.method)
    model = bearing_model(history, par, quad)
    work = method.workspace(model, y.shape[0], 0.0, h)
    control = step_control(
        options.tolerance,
        scale,
        1e-6 * h,
        options.max_steps_per_chunk,
        event_times(history, 0.0, float(times[-1])),
    )
    stats = RunStatistics(work.progress)
    stats.initial_step = h
    run = run_chunks(method, model, y, grid, states, control, work, options, progress, cancel)
    done, stop_reason, diverged_message = run.done, run.stop_reason, run.diverged_message
    stats.wall_time = run.wall_time
    complete = stop_reason == "finished"
    ds = build_dataset(
        inputs,
        options,
        history,
        par,
        quad,
        times[:done],
        states[:done],
        period,
        complete,
        stop_reason,
        stats,
        quasistatic,
    )
    ds.attrs["initial_state"] = start_note
    if diverged_message is not None:
        err = SimulationDiverged(diverged_message)
        err.dataset = ds
        raise err
    return ds
