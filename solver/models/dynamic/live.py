"""A dynamic simulation that runs on in chunks while its inputs change (issue 24 §3, live mode).

:class:`LiveSimulation` holds the state of one dynamic run of a single bearing and integrates it
chunk by chunk (:meth:`LiveSimulation.advance`), with the same integrator, tolerances and step
control as :func:`.simulate.simulate`. Between chunks an operating input may be set
(:meth:`LiveSimulation.set_input`): from the current simulated time it ramps linearly to the new
value over :data:`LIVE_RAMP` seconds of simulated time. The session is an operating history that
grows: each channel is a piecewise-linear table of (time, value) knots, and the model's
:class:`solver.history.HistoryRecord` is rebuilt from the tables at every change; the knot times
are event times of the step control, so no step passes the start or the end of a ramp.

Output sampling: a fixed number of samples per second of simulated time
(:attr:`LiveSimulation.samples_per_second`): the case's ``simulation.samples_per_second`` for a
case with time histories, else the case's ``samples_per_revolution`` at its relative ring speed at
the start. It does not follow later speed changes, so chunks of equal duration have equal sizes.
Sample k lies at t = k / samples_per_second; a chunk holds whole samples.

Everything since the start (or the last :meth:`reset`) is recorded: the stored states (one row of
``state_size`` floats, 8 bytes each, per sample) and the knot tables, up to the sample count a run
may hold (:data:`solver.case.validate.MAX_DYNAMIC_BALL_SAMPLES` ball samples); beyond it the
session runs on but the record ends there. :meth:`recorded_case` writes the record as a case whose
histories are ``table`` forms; :meth:`recorded_result` is the record as one ordinary run Dataset.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from solver.case import dynamic_problems
from solver.case.history import MAX_KNOTS
from solver.case.schema import field as schema_field
from solver.case.validate import MAX_DYNAMIC_BALL_SAMPLES, check_value
from solver.errors import CaseError, Problem, SimulationDiverged
from solver.history import (
    CH_INNER_SPEED,
    CH_MISALIGNMENT,
    CH_MISALIGNMENT_AXIS,
    CH_MOMENT_AXIS,
    CH_OUTER_SPEED,
    CH_RADIAL_LOAD_ANGLE,
    CH_TILTING_MOMENT,
    CHANNEL_NAMES,
    FRAME_INNER_RING,
    FRAME_SPACE,
    N_CHANNELS,
    ChannelHistory,
    channel_value,
    event_times,
    history_record,
)
from solver.inputs import HISTORY_CHANNELS, operating_at, rad_s_to_rpm, to_inputs

from . import layout as L
from .integrate import stepper
from .integrate.control import STATUS_OK, step_control
from .integrate.model import bearing_model
from .options import SimulationOptions
from .output import build_dataset, chunk_dataset
from .params import build_params, build_quadrature
from .simulate import _DIVERGENCE_CAUSES, RunStatistics, _start, state_scales

#: Simulated time [s] over which a change of an input ramps (linearly) from its current value to
#: the one set. 0.002 s is two thirds of a shaft revolution at 20 000 rpm and about 200 periods of
#: the ball-race contacts' vibration (~10 us), so a change does not ring the balls like a step; in
#: wall time it is 0.002 s times the session's wall seconds per simulated second (about 0.2 s on
#: the spindle case on one free core, docs/live.md), so a change is complete in the picture within
#: the 0.5 s the live view allows.
LIVE_RAMP = 0.002

#: The case key of each channel (its unit: :data:`solver.inputs.HISTORY_CHANNELS`).
CHANNEL_KEYS = {channel: key for key, (channel, _) in HISTORY_CHANNELS.items()}


def _unit_scale(channel: int) -> float:
    """The SI value of one unit of the channel's case key."""
    return HISTORY_CHANNELS[CHANNEL_KEYS[channel]][1]


@dataclass
class _Table:
    """One channel's knots (SI), times non-decreasing, linear segments."""

    times: list
    values: list

    def channel(self) -> ChannelHistory:
        return ChannelHistory(tuple(self.times), tuple(self.values))


#: Output samples integrated between two calls of :meth:`LiveSimulation.advance`'s ``interrupt``:
#: a control that arrives while a chunk integrates waits at most this many samples (a fifth of
#: the app's chunk of 0.6 ms at 60 000 samples/s on the spindle case) before the chunk returns.
INTERRUPT_SAMPLES = 8


class AdvanceTiming(NamedTuple):
    """What the last :meth:`LiveSimulation.advance` cost: the simulated time it added [s], the
    wall and CPU (``time.process_time``) seconds of its integration, the wall and CPU seconds of
    building its Dataset, and whether ``interrupt`` ended it before its planned samples (with
    the count it planned)."""

    simulated_s: float
    integration_wall_s: float
    integration_cpu_s: float
    dataset_wall_s: float
    dataset_cpu_s: float = 0.0
    interrupted: bool = False
    planned_samples: int = 0


class LiveSimulation:
    """A dynamic run of one bearing that advances chunk by chunk and follows inputs set while it
    runs (module docstring). ``case``: a validated :class:`solver.case.Case` of one bearing (a
    steady case, or one with time histories: it starts from their values at t = 0 and then holds
    them); ``options``: :class:`SimulationOptions` as :func:`.simulate.simulate` takes (its run
    length is not read: a session runs as long as it is advanced). CaseError when the dynamic
    model cannot run the case (a bearing set, equal ring speeds)."""

    def __init__(self, case, options: SimulationOptions | None = None):
        if getattr(case, "bearing_set", None) is not None:
            raise CaseError(
                Problem(
                    "set",
                    "live mode runs one bearing; this case describes a bearing set ([set]): run "
                    "the set's dynamic model (racetrace simulate, Run in the app, "
                    "solver.simulate(case))",
                )
            )
        if not hasattr(case, "histories"):
            problems = dynamic_problems(case) if hasattr(case, "operating") else []
            raise CaseError(
                problems
                or "LiveSimulation takes a Case of one bearing (solver.LiveSimulation also takes a "
                "case-file path or a catalogue name)"
            )
        inputs = to_inputs(case)
        steady = not case.histories
        if steady:  # the rings must turn; the case's run length is not read
            problems = [p for p in dynamic_problems(case) if p.key.startswith("operating.")]
            if problems:
                raise CaseError(problems)
        self._case = case
        self._given = (options or SimulationOptions()).validated()
        self._options = self._given.resolved(inputs.simulation)
        self._base_inputs = inputs
        frame_turns = inputs.history is not None and (
            inputs.history.radial_load_frame == FRAME_INNER_RING
        )
        self._radial_load_frame = FRAME_INNER_RING if frame_turns else FRAME_SPACE
        self._tilt_free = inputs.operating.tilting_moment is not None
        op = inputs.operating
        if steady:
            per_rev = self._options.samples_per_revolution
            relative = abs(op.inner_ring_speed - op.outer_ring_speed) / (2.0 * math.pi)
            self._rate = float(per_rev) * relative
        else:
            self._rate = float(inputs.simulation.samples_per_second)
        self._par = build_params(inputs, self._options)
        self._quad = build_quadrature(self._options, self._par)
        self._method = stepper(self._options.method)
        self._max_record = max(2, MAX_DYNAMIC_BALL_SAMPLES // int(self._par.ball_count))
        start = {c: float(v) for c, v in _operating_channels(inputs, 0.0).items()}
        self._closed = False
        self._restart(start)

    # ---- the session's state ---------------------------------------------------------------------
    def _restart(self, values: dict) -> None:
        """Start at t = 0 from the quasi-static state under the channel values ``values`` (SI)."""
        self._start_values = dict(values)
        self._tables = {c: _Table([0.0], [v]) for c, v in values.items()}
        self._rebuild_history()
        inputs = self._inputs_now()
        y, note, quasistatic = _start(inputs, self._options, self._history, self._par, self._quad)
        self._start_note = note
        self._quasistatic = quasistatic
        self._y = np.ascontiguousarray(y, dtype=np.float64)
        self._scale = state_scales(self._history, self._par, self._y)
        omega_n = self._scale[L.B_VEL] / self._scale[L.B_POS]
        self._h_start = 0.05 / omega_n
        self._model = bearing_model(self._history, self._par, self._quad)
        self._work = self._method.workspace(self._model, self._y.shape[0], 0.0, self._h_start)
        self._stats = RunStatistics(self._work.progress)
        self._stats.initial_step = self._h_start
        self._control = self._step_control(0.0)
        self._sample = 0  # index of the last sample integrated
        self._record = [self._y.copy()[None, :]]  # stored states, chunk by chunk
        self._recorded = 1  # samples in the record
        self._diverged = None  # the divergence message, once diverged
        self._integration_wall = 0.0
        self._pending = []  # (times, states) integrated and not yet taken (integrate, take)
        self._pending_timing = []  # ... and the AdvanceTiming of each of those integrations
        #: :class:`AdvanceTiming` of the last :meth:`advance` or :meth:`take` (None before)
        self.last_advance: AdvanceTiming | None = None

    def _rebuild_history(self) -> None:
        channels = {c: table.channel() for c, table in self._tables.items()}
        self._history = history_record(
            channels, dict(self._start_values), self._radial_load_frame, self._tilt_free
        )

    def _step_control(self, t: float):
        return step_control(
            self._options.tolerance,
            self._scale,
            1e-6 * self._h_start,
            self._options.max_steps_per_chunk,
            event_times(self._history, t, math.inf),
        )

    def _inputs_now(self):
        """The session's Inputs: the case's, with its operating point at t = 0 and the session's
        history."""
        base = replace(self._base_inputs, history=self._history)
        return replace(base, operating=operating_at(base, 0.0))

    # ---- public API ------------------------------------------------------------------------------
    @property
    def time(self) -> float:
        """Simulated time reached [s]."""
        return self._sample / self._rate

    @property
    def samples_per_second(self) -> float:
        """Output samples per second of simulated time."""
        return self._rate

    @property
    def input_names(self) -> tuple[str, ...]:
        """The inputs :meth:`set_input` takes (solver.history.CHANNEL_NAMES): the tilt is imposed
        (misalignment, misalignment_axis) or solved under a moment (tilting_moment, moment_axis),
        as the case gives it."""
        unused = _unused_channels(self._tilt_free)
        return tuple(name for c, name in enumerate(CHANNEL_NAMES) if c not in unused)

    def inputs_now(self) -> dict:
        """{input name: value at the current simulated time} (SI: rad/s, N, rad, N m); the radial
        load's angle of a load turning with the shaft is its angle in the inner ring's frame."""
        t = self.time
        return {
            name: float(channel_value(self._history, CHANNEL_NAMES.index(name), t))
            for name in self.input_names
        }

    def set_input(self, name: str, value: float, ramp_s: float = LIVE_RAMP) -> None:
        """From the current simulated time, ramp input ``name`` (one of :attr:`input_names`)
        linearly to ``value`` (SI) over ``ramp_s`` simulated seconds (0: a step). A ramp still
        under way on the same input is replaced by the new one from its current value. CaseError
        naming the input when the name or the value is not allowed (the case's rules for the
        key)."""
        channel = self._channel(name)
        value = _finite(name, value, "value")
        ramp_s = _finite(name, ramp_s, "ramp_s")
        if ramp_s < 0.0:
            raise CaseError(
                Problem(
                    CHANNEL_KEYS[channel],
                    f"live input {name}: ramp_s = {ramp_s!r} s must be >= 0 (0 is a step)",
                )
            )
        targets = {c: table.values[-1] for c, table in self._tables.items()}
        targets[channel] = value
        self._check_values(channel, targets)
        t = self.time
        table = self._tables[channel]
        if len(table.times) + 2 > MAX_KNOTS:
            raise CaseError(
                Problem(
                    CHANNEL_KEYS[channel],
                    f"live input {name}: changed so often that its recorded history would pass "
                    f"the {MAX_KNOTS:,} points a case's table may hold; save the session "
                    "(recorded_case) and reset() to start a new record",
                )
            )
        now = float(channel_value(self._history, channel, t))
        while table.times and table.times[-1] > t:
            table.times.pop()
            table.values.pop()
        if table.times[-1] < t:
            table.times.append(t)
            table.values.append(now)
        at_t = sum(1 for x in table.times if x == t)
        if ramp_s == 0.0 and at_t >= 2:
            table.values[-1] = value  # a second step at one time replaces the first
        else:
            table.times.append(t + ramp_s)
            table.values.append(value)
        self._rebuild_history()
        self._model = bearing_model(self._history, self._par, self._quad)
        self._control = self._step_control(t)

    def advance(self, duration_s: float, interrupt=None):
        """Integrate from the current time over ``duration_s`` simulated seconds (rounded to
        whole samples, at least one) and return the new samples as a Dataset of the schema of a
        dynamic run (results-schema.md; every input of :attr:`input_names` as a data variable
        over ``time``). ``interrupt``: None, or a callable without arguments asked after every
        :data:`INTERRUPT_SAMPLES` samples; when it returns true the call ends there and returns
        the samples done so far (``last_advance.interrupted``), so that an input set next
        (:meth:`set_input`) acts from that time, not from the end of the planned duration.
        SimulationDiverged (with the samples of this call in ``dataset``) when the integration
        fails; the session must then be :meth:`reset`. The same as :meth:`integrate` then
        :meth:`take`."""
        self.integrate(duration_s, interrupt)
        return self.take()

    def integrate(self, duration_s: float, interrupt=None) -> AdvanceTiming:
        """The integration of :meth:`advance` without its Dataset: the new samples wait, with
        those of earlier calls, for :meth:`take`, so that an input set between two calls (after
        an ``interrupt``) acts at once, before any Dataset is built. What this call did (its
        dataset times 0). SimulationDiverged (``dataset``: the samples not yet taken) when the
        integration fails."""
        self._check_open()
        if self._diverged is not None:
            raise SimulationDiverged(f"{self._diverged}; reset() the live simulation to go on")
        duration_s = _finite("advance", duration_s, "duration_s")
        if duration_s <= 0.0:
            raise ValueError(f"advance: duration_s = {duration_s!r} must be > 0")
        count = max(1, int(round(duration_s * self._rate)))
        first = self._sample + 1
        times = np.arange(first, first + count, dtype=np.float64) / self._rate
        states = np.empty((count, self._y.shape[0]))
        done = 0
        interrupted = False
        progress = self._work.progress
        step = self._options.chunk_samples
        if interrupt is not None:
            step = min(step, INTERRUPT_SAMPLES)
        begin = _time.perf_counter()
        begin_cpu = _time.process_time()
        while done < count:
            if done and interrupt is not None and interrupt():
                interrupted = True
                break
            stop = min(done + step, count)
            self._method.advance(
                self._y, times[done:stop], states[done:stop], self._control, self._work, self._model
            )
            done += int(progress["written"][0])
            status = int(progress["status"][0])
            if status != STATUS_OK:
                t = float(progress["t"][0])
                cause = _DIVERGENCE_CAUSES[status].format(
                    h_min=self._control.h_min, max_steps=self._options.max_steps_per_chunk
                )
                self._diverged = f"live simulation diverged at t = {t:.6g} s: {cause}"
                break
        integration = _time.perf_counter() - begin
        integration_cpu = _time.process_time() - begin_cpu
        self._integration_wall += integration
        times, states = times[:done], states[:done]
        self._sample += done
        self._keep(states)
        part = AdvanceTiming(
            done / self._rate, integration, integration_cpu, 0.0, 0.0, interrupted, count
        )
        if done:
            self._pending.append((times, states))
        self._pending_timing.append(part)
        if self._diverged is not None:
            error = SimulationDiverged(self._diverged)
            error.dataset = self.take()
            raise error
        return part

    def take(self):
        """The samples :meth:`integrate` added since the last take as one Dataset (as
        :meth:`advance` returns it; None when there are none); ``last_advance``: the
        integrations it holds summed (interrupted when one was, the samples they planned) and
        the cost of its Dataset (left as it was when nothing was integrated since the last
        take)."""
        self._check_open()
        pending, parts = self._pending, self._pending_timing
        if not parts:  # no integration since the last take
            return None
        self._pending, self._pending_timing = [], []
        begin = _time.perf_counter()
        begin_cpu = _time.process_time()
        ds = None
        if pending:
            times = np.concatenate([t for t, _ in pending])
            states = np.concatenate([y for _, y in pending], axis=0)
            ds = self._chunk_dataset(times, states)
        self.last_advance = AdvanceTiming(
            sum(p.simulated_s for p in parts),
            sum(p.integration_wall_s for p in parts),
            sum(p.integration_cpu_s for p in parts),
            _time.perf_counter() - begin,
            _time.process_time() - begin_cpu,
            any(p.interrupted for p in parts),
            sum(p.planned_samples for p in parts),
        )
        return ds

    def reset(self) -> None:
        """Back to t = 0 at the quasi-static state of the inputs' current targets (the values
        they were last set to, ramps taken as finished), the history and the record cleared."""
        self._check_open()
        self._restart({c: table.values[-1] for c, table in self._tables.items()})

    def close(self) -> None:
        """Free the record; advancing, resetting or recording afterwards is a RuntimeError."""
        self._record = []
        self._pending, self._pending_timing = [], []
        self._recorded = 0
        self._closed = True

    # ---- internals -------------------------------------------------------------------------------
    def _check_open(self) -> None:
        if self._closed:
            raise RuntimeError("the live simulation was closed: start a new LiveSimulation")

    def _channel(self, name) -> int:
        if name not in self.input_names:
            raise CaseError(
                Problem(
                    "operating",
                    f"live input {name!r}: not an input of this session; give one of "
                    + ", ".join(self.input_names),
                )
            )
        channel = CHANNEL_NAMES.index(name)
        if channel == CH_RADIAL_LOAD_ANGLE and self._radial_load_frame == FRAME_INNER_RING:
            raise CaseError(
                Problem(
                    CHANNEL_KEYS[channel],
                    f"live input {name}: the case turns the radial load with the shaft "
                    '(radial_load_angle_deg = { rotating = "with_shaft" }), so its angle is not '
                    "set live; open a case with a load fixed in space to turn it by hand",
                )
            )
        return channel

    def _check_values(self, channel: int, targets: dict) -> None:
        """CaseError unless the case's rules accept the target values (SI) of every channel,
        with the message of the key of ``channel`` first."""
        key = CHANNEL_KEYS[channel]
        name = CHANNEL_NAMES[channel]
        value = targets[channel] / _unit_scale(channel)
        problems = []
        check_value(schema_field(key), key, value, problems)
        if not problems:
            try:
                self.steady_case(targets)
            except CaseError as error:
                problems = error.problems
        if not problems and channel in (CH_INNER_SPEED, CH_OUTER_SPEED):
            inner, outer = targets[CH_INNER_SPEED], targets[CH_OUTER_SPEED]
            if inner == outer:
                problems = [
                    Problem(
                        key,
                        f"{key} = {value:g}: the inner and the outer ring would both turn at "
                        f"{rad_s_to_rpm(inner):g} rpm, so the rings would not turn relative to "
                        "each other and nothing would run; set a different speed",
                        ("operating.inner_ring_speed_rpm", "operating.outer_ring_speed_rpm"),
                    )
                ]
        if problems:
            raise CaseError(
                [
                    Problem(p.key, f"live input {name} = {targets[channel]:g} (SI): {p.message}")
                    for p in problems
                ]
            )

    def steady_case(self, values: dict | None = None):
        """The case at the channel values ``values`` (SI; None: the values at t = 0 of the
        record) as a steady case of the session's bearing, validated (CaseError)."""
        values = self._start_values if values is None else values
        changes = {
            "simulation.duration_s": None,
            "simulation.samples_per_second": None,
        }
        changes.update(self._number_changes(values))
        return self._case.with_values(changes)

    def _number_changes(self, values: dict, rotating: bool = False) -> dict:
        """{case key: number in the key's unit} of the channel values ``values`` (SI) that the
        session sets; ``rotating``: the radial load's angle of a load turning with the shaft as
        the case's rotating form from that angle (else as a number)."""
        unused = _unused_channels(self._tilt_free)
        changes = {}
        for c, v in values.items():
            if c in unused:
                continue
            turning = self._radial_load_frame == FRAME_INNER_RING
            if c == CH_RADIAL_LOAD_ANGLE and turning and rotating:
                spec = self._case.histories[CHANNEL_KEYS[c]].spec
                changes[CHANNEL_KEYS[c]] = {
                    "rotating": spec["rotating"],
                    "start_deg": math.degrees(v),
                }
                continue
            changes[CHANNEL_KEYS[c]] = _case_number(v / _unit_scale(c))
        return changes

    # ---- the record ------------------------------------------------------------------------------
    @property
    def recorded_time(self) -> float:
        """Simulated time [s] the record covers (from 0; less than :attr:`time` once the record
        is full)."""
        return (self._recorded - 1) / self._rate

    @property
    def record_bytes(self) -> int:
        """Memory [bytes] held by the record's states."""
        return int(sum(block.nbytes for block in self._record))

    def recorded_case_object(self):
        """The session's record as a validated :class:`solver.case.Case` (:meth:`recorded_case`)."""
        self._check_open()
        end = self.recorded_time
        if not end > 0.0:
            raise CaseError(
                Problem(
                    "simulation.duration_s",
                    "the live simulation has not been advanced since its start or reset: nothing "
                    "is recorded yet; advance it first",
                )
            )
        changes = {
            "simulation.shaft_revolutions": None,
            "simulation.samples_per_revolution": None,
            "simulation.duration_s": end,
            "simulation.samples_per_second": self._rate,
        }
        changes.update(self._number_changes(self._start_values, rotating=True))
        unused = _unused_channels(self._tilt_free)
        tables = 0
        for c, table in self._tables.items():
            if c in unused or len(table.times) < 2:
                continue
            scale = _unit_scale(c)
            points = []
            for t, v in zip(table.times, table.values, strict=True):
                points.append([t, _case_number(v / scale)])
                if t > end:  # the first knot after the record's end: the ramp under way
                    break
            changes[CHANNEL_KEYS[c]] = {"table": points, "interpolation": "linear"}
            tables += 1
        if not tables:  # a duration needs a history: the inner ring's speed as a one-point table
            c = CH_INNER_SPEED
            value = _case_number(self._start_values[c] / _unit_scale(c))
            changes[CHANNEL_KEYS[c]] = {"table": [[0.0, value]], "interpolation": "linear"}
        return self._case.with_values(changes)

    def recorded_case(self) -> str:
        """The case TOML text of the session's record: the case with every input the user
        changed as a ``table`` history of exactly its knots (case units), starting from the
        values at t = 0, ``simulation.duration_s`` = the recorded time and
        ``simulation.samples_per_second`` = the session's. ``racetrace simulate`` of it repeats the
        session. CaseError when nothing is recorded yet."""
        return self.recorded_case_object().to_toml(inline_files=True)

    def recorded_result(self):
        """The session's record as one ordinary dynamic run Dataset (results-schema.md) of
        :meth:`recorded_case`: ``complete`` = 1 unless the session diverged, the case text of
        the recorded case; saveable with the results API."""
        case = self.recorded_case_object()
        inputs = to_inputs(case)
        count = self._recorded
        states = np.concatenate(self._record, axis=0)[:count]
        times = np.arange(count, dtype=np.float64) / self._rate
        complete = self._diverged is None or self._recorded < self._sample + 1
        stop_reason = "finished" if complete else self._diverged
        self._stats.wall_time = self._integration_wall
        ds = build_dataset(
            inputs,
            self._options,
            inputs.history,
            self._par,
            self._quad,
            times,
            states,
            self._period(times),
            complete,
            stop_reason,
            self._stats,
            self._quasistatic,
        )
        ds.attrs["initial_state"] = self._start_note
        return ds

    def _keep(self, states: np.ndarray) -> None:
        """Add the samples ``states`` to the record, up to its size limit."""
        room = self._max_record - self._recorded
        if room > 0 and states.shape[0]:
            kept = states[:room].copy()
            self._record.append(kept)
            self._recorded += kept.shape[0]

    def _chunk_dataset(self, times: np.ndarray, states: np.ndarray):
        self._stats.wall_time = self._integration_wall
        unused = _unused_channels(self._tilt_free)
        ds = chunk_dataset(
            self._inputs_now(),
            self._options,
            self._history,
            self._par,
            self._quad,
            times,
            states,
            self._period(times),
            self._stats,
            [c for c in range(N_CHANNELS) if c not in unused],
            self._quasistatic,
        )
        ds.attrs["initial_state"] = self._start_note
        ds.attrs["live_ramp_s"] = LIVE_RAMP
        return ds

    def _period(self, times: np.ndarray) -> float:
        values = np.empty((N_CHANNELS, times.size))
        from .observe import channel_series

        channel_series(self._history, np.ascontiguousarray(times), values)
        mean = float(np.mean(np.abs(values[CH_INNER_SPEED] - values[CH_OUTER_SPEED])))
        return 2.0 * math.pi / mean if mean > 0.0 else math.inf


def _unused_channels(tilt_free: bool) -> tuple[int, ...]:
    if tilt_free:
        return (CH_MISALIGNMENT, CH_MISALIGNMENT_AXIS)
    return (CH_TILTING_MOMENT, CH_MOMENT_AXIS)


def _operating_channels(inputs, t: float) -> dict:
    """{channel: SI value} of every channel of ``inputs`` at time ``t`` (its history's, a radial
    load turning with the shaft in the ring's frame)."""
    if inputs.history is None:
        from solver.history import operating_values

        return operating_values(inputs.operating)
    return {c: float(channel_value(inputs.history, c, t)) for c in range(N_CHANNELS)}


def _finite(name: str, value, what: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number):
        raise CaseError(
            Problem("operating", f"live input {name}: {what} = {value!r} must be a finite number")
        )
    return number


def _case_number(value: float) -> float:
    """A value in case units as the case file holds it: a float, -0 as 0."""
    return float(value) + 0.0
