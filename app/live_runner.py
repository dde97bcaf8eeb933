"""The live solver in a separate ``spawn`` process: it advances a :class:`solver.LiveSimulation`
in small chunks, paced to the playback rate, and sends each chunk to the parent.

The child process (:func:`live_main`) builds ``solver.LiveSimulation`` on the case given as TOML
text, then loops: apply the controls the parent queued (:meth:`LiveRunner.set_input`, pause, resume,
reset, record), advance ``rate * CHUNK_WALL_S`` seconds of bearing time and send the chunk Dataset,
then wait out the rest of the chunk's wall time (reading controls meanwhile), so that the simulation
runs at the playback rate (``rate``: bearing seconds per wall second). A control that arrives while
a chunk integrates cuts the chunk short (``LiveSimulation.integrate(..., interrupt=...)``, at most
:data:`solver.models.dynamic.live.INTERRUPT_SAMPLES` samples later): the samples done so far are
kept (over its share of the chunk's wall time), the control is applied at once, before any Dataset
is built (``LiveSimulation.integrate`` then ``take``), and a change's short chunk follows at once:
the cut samples and the change's go to the parent as one chunk, whose ``info["change_from_s"]``
says the simulated time from which it carries the change (the parent plays it from there). A pause,
reset or record that arrives so is applied after the cut samples are sent. The
lead is bounded: the child computes a chunk only while fewer than :data:`MAX_LEAD_CHUNKS` chunks it
sent are not yet taken by the parent (:meth:`LiveRunner.poll` counts them in a shared counter), so a
parent that falls behind never has more than that many stale chunks waiting. A control change cuts
the wait short: the chunk after it is computed at once, whatever the lead, and is short
(:data:`CHANGE_CHUNK_FRACTION` of a chunk), so that it reaches the parent about a chunk's compute
time sooner; the rest of the chunk before it is then not played. When a chunk takes longer than its
wall time the solver cannot keep up: the next chunk (the same bearing time) is given the wall time
the solver needs, so the playback runs at the rate the solver achieves, and the chunk's message says
so (:class:`_Pace`); quick chunks bring the asked rate back. The playback is slowed, never stalled.

Messages from the child (tuples): ``("preparing", text)`` (loading or compiling the kernels),
``("ready", time_s, inputs)`` (the quasi-static state; again after a reset;
``inputs``: :meth:`inputs_now`, SI), ``("chunk", ds, info)``
with ``info`` a dict of ``rate`` (bearing s per wall s the chunk was made for),
``playback_rate`` (bearing s per wall s of the chunks from now on: below ``asked_rate`` while the
solver cannot keep up), ``asked_rate``, ``behind`` (bool: this chunk took too long),
``compute_s`` (the chunk's wall time in the solver), ``chunk_wall_s`` (the wall time it was
made for), ``inputs`` (:meth:`inputs_now`) and ``sets`` (the ``set`` controls read before the
chunk was sent, applied or refused, counted from the start: the parent knows from it which chunk
is the first to carry a change it sent) and ``change_from_s`` (None, or the simulated time [s]
from which a chunk that holds samples from before a change carries it),
``("recorded", path, case_text)``, ``("refused", text)`` (a control value the model refused),
``("error", text)``, ``("stopped",)``.

Controls to the child: ``("set", name, value_SI, ramp_s)``, ``("pause",)``, ``("resume",)``,
``("reset",)``, ``("rate", bearing_s_per_wall_s)``, ``("record", out_path)``; the stop event
ends the loop.
"""

from __future__ import annotations

import multiprocessing as mp
import queue as queue_module
import time

#: Wall time of one chunk of the live loop (s): the solver advances ``rate * CHUNK_WALL_S`` of
#: bearing time per chunk, so a control change reaches the picture within about two chunks.
CHUNK_WALL_S = 0.1
#: A chunk that used more than this fraction of its wall time counts as not keeping up.
BEHIND_FRACTION = 0.9
#: The child computes no further chunk while this many chunks it sent wait, not yet taken by the
#: parent: the bearing time computed and not shown is at most this many chunks (plus the one on
#: show), whatever the parent's pace. The chunk after a control change is computed regardless.
MAX_LEAD_CHUNKS = 2
#: The chunk after a control change covers this fraction of a chunk's bearing and wall time and
#: is computed at once (the wait for the chunk before is cut short), so that the change reaches
#: the picture sooner.
CHANGE_CHUNK_FRACTION = 0.25
#: Controls that, arriving while a chunk integrates, are applied at once, before the samples done
#: so far are sent: those samples and the change's own (a :data:`CHANGE_CHUNK_FRACTION` chunk)
#: go to the parent as one chunk whose ``change_from_s`` says where the change begins.
CHANGES_AT_ONCE = ("set", "rate")


#: The live simulation the child runs ("module:name" of a class called as ``cls(case)``).
LIVE_SIMULATION = "solver:LiveSimulation"


def live_main(
    case_text: str, rate: float, controls, messages, stop, target: str, taken=None
) -> None:
    """Child process entry point (see the module docstring); ``target``: the simulation class
    (:data:`LIVE_SIMULATION`); ``taken``: the shared count of chunks the parent has taken (a
    ``multiprocessing.Value``; None: no bound on the lead)."""
    try:
        _live_loop(case_text, rate, controls, messages, stop, target, taken)
    except Exception as error:  # the parent shows it in words
        from solver import clean_message

        messages.put(("error", clean_message(error)))
    messages.put(("stopped",))


def _live_loop(case_text: str, rate: float, controls, messages, stop, target: str, taken) -> None:
    import importlib

    import solver

    from .compile_watch import LOADING, compiling_words, watching_compiles

    messages.put(("preparing", LOADING))
    case = solver.parse_case(case_text)
    with watching_compiles(lambda count: messages.put(("preparing", compiling_words(count)))):
        module, name = target.split(":")
        sim = getattr(importlib.import_module(module), name)(case)
    messages.put(("ready", float(sim.time), dict(sim.inputs_now())))
    pace = _Pace(rate)
    paused = False
    sent = 0  # chunks sent since the start
    sets = 0  # "set" controls read since the start (applied or refused)
    changed = False  # a change was applied since the last chunk began
    try:
        while not stop.is_set():
            waiting = not changed and taken is not None and sent - taken.value >= MAX_LEAD_CHUNKS
            for control in _drain(controls, block_s=0.02 if paused or waiting else 0.0):
                paused, applied = _apply(sim, control, paused, pace, messages)
                sets += control[0] == "set"
                changed = changed or applied
            if paused or stop.is_set() or (waiting and not changed):
                continue
            start = time.monotonic()
            short = changed
            duration, wall = pace.next_chunk(short=changed)
            changed = False
            arrived = []  # controls that came while the chunk integrated: they cut it short

            def control_waiting(arrived=arrived) -> bool:
                arrived.extend(_drain(controls, block_s=0.0))
                return bool(arrived)

            part = sim.integrate(duration, interrupt=control_waiting)
            if part.interrupted:  # played over its share of the wall
                wall *= part.simulated_s / duration
            shown_from = None
            if arrived and all(control[0] in CHANGES_AT_ONCE for control in arrived):
                # applied before the cut samples are sent: they go with the change's own samples
                # in one chunk, so that no Dataset is built between the control and the change
                for control in arrived:
                    paused, applied = _apply(sim, control, paused, pace, messages)
                    sets += control[0] == "set"
                    short = short or applied
                    if applied and shown_from is None:
                        shown_from = float(sim.time)
                del arrived[:]
                if shown_from is not None:
                    extra, extra_wall = pace.next_chunk(short=True)
                    more = sim.integrate(extra, interrupt=control_waiting)
                    wall += extra_wall * more.simulated_s / extra
            chunk = sim.take()
            took = time.monotonic() - start
            info = pace.after_chunk(took, wall, measure=not short)
            info["inputs"] = dict(sim.inputs_now())
            info["sets"] = sets
            info["change_from_s"] = shown_from
            messages.put(("chunk", chunk, info))
            sent += 1
            for control in arrived:
                paused, applied = _apply(sim, control, paused, pace, messages)
                sets += control[0] == "set"
                changed = changed or applied
            wait_until = start + wall
            while not stop.is_set() and not paused and not changed:
                left = wait_until - time.monotonic()
                if left <= 0:
                    break
                for control in _drain(controls, block_s=min(left, 0.02)):
                    paused, applied = _apply(sim, control, paused, pace, messages)
                    sets += control[0] == "set"
                    changed = changed or applied
    finally:
        sim.close()


class _Pace:
    """The playback the child keeps: every chunk covers ``asked * CHUNK_WALL_S`` of bearing time
    and takes :data:`CHUNK_WALL_S` of wall time, or, while the solver cannot keep up, the wall
    time the solver needs for it; the playback rate is then what the solver achieves (shorter
    chunks would only weigh a chunk's fixed cost more). The chunk after a control change is
    :data:`CHANGE_CHUNK_FRACTION` of a chunk (bearing and wall time), so that it is computed and
    shown sooner; being short, it pays the fixed cost of a chunk more and is no measure of the
    pace."""

    def __init__(self, asked: float):
        self.asked = float(asked)
        self.chunk_wall = CHUNK_WALL_S
        self.first = True  # the next chunk is the first after a (re)start

    @property
    def duration(self) -> float:
        """Bearing time of the next chunk (s)."""
        return self.asked * CHUNK_WALL_S

    @property
    def rate(self) -> float:
        """Bearing seconds per wall second of the next chunk."""
        return self.duration / self.chunk_wall

    def ask(self, rate: float) -> None:
        self.asked = float(rate)

    def next_chunk(self, short: bool = False) -> tuple[float, float]:
        """(bearing time, wall time) of the next chunk (s); ``short``: the chunk after a control
        change."""
        scale = CHANGE_CHUNK_FRACTION if short else 1.0
        return scale * self.duration, scale * self.chunk_wall

    def after_chunk(self, took_s: float, wall_s: float | None = None, measure: bool = True) -> dict:
        """Adapt to a chunk that took ``took_s`` of wall time and was made for ``wall_s`` (None:
        a whole chunk); its report. ``measure`` false: a chunk that holds a change's short
        chunk (its fixed cost weighs more), no measure of the pace."""
        used, wall = self.rate, self.chunk_wall if wall_s is None else wall_s
        if self.first or wall < self.chunk_wall or not measure:  # one-time costs, a short chunk
            self.first = False
            return self._report(used, wall, took_s, False)
        behind = took_s > BEHIND_FRACTION * CHUNK_WALL_S
        self.chunk_wall = max(CHUNK_WALL_S, took_s / BEHIND_FRACTION) if behind else CHUNK_WALL_S
        return self._report(used, wall, took_s, behind)

    def _report(self, used: float, wall: float, took_s: float, behind: bool) -> dict:
        return {
            "rate": used,
            "playback_rate": self.rate,  # adapted to this chunk: the pace from now on
            "asked_rate": self.asked,
            "behind": bool(behind),
            "compute_s": took_s,
            "chunk_wall_s": wall,
        }


def _drain(controls, block_s: float) -> list:
    """Every control queued now (waiting up to ``block_s`` for the first)."""
    found = []
    try:
        found.append(controls.get(timeout=block_s) if block_s > 0 else controls.get_nowait())
    except queue_module.Empty:
        return found
    while True:
        try:
            found.append(controls.get_nowait())
        except queue_module.Empty:
            return found


def _apply(sim, control, paused: bool, pace: _Pace, messages) -> tuple[bool, bool]:
    """Apply one control to ``sim``; (the paused flag after it, whether it changed an input)."""
    kind = control[0]
    if kind == "set":
        _, name, value, ramp_s = control
        try:
            sim.set_input(name, float(value), ramp_s=float(ramp_s))
        except ValueError as error:  # a value the model refuses (CaseError): said, runs on
            from solver import clean_message

            messages.put(("refused", clean_message(error)))
            return paused, False
        return paused, True
    elif kind == "pause":
        return True, False
    elif kind == "resume":
        return False, False
    elif kind == "rate":
        pace.ask(float(control[1]))
    elif kind == "reset":
        sim.reset()
        pace.first = True
        messages.put(("ready", float(sim.time), dict(sim.inputs_now())))
    elif kind == "record":
        from .runner import _save

        path = _save(sim.recorded_result(), control[1])
        messages.put(("recorded", path, sim.recorded_case()))
    return paused, False


# ---- parent side ---------------------------------------------------------------------------------
class LiveRunner:
    """One live solver process: controls in, chunks out."""

    def __init__(self):
        self._ctx = mp.get_context("spawn")
        self._process = None
        self._controls = None
        self._messages = None
        self._stop = None
        self._taken = None  # chunks taken from the child (shared with it)

    @property
    def alive(self) -> bool:
        return self._process is not None and self._process.is_alive()

    def start(self, case_text: str, rate: float, target: str = LIVE_SIMULATION) -> None:
        """Start the live solver on ``case_text`` at ``rate`` bearing seconds per wall second."""
        if self._process is not None:
            raise RuntimeError("the live solver is already running; stop it first")
        self._controls = self._ctx.Queue()
        self._messages = self._ctx.Queue()
        self._stop = self._ctx.Event()
        self._taken = self._ctx.Value("q", 0, lock=False)  # written by the parent only
        self._process = self._ctx.Process(
            target=live_main,
            args=(
                *(case_text, float(rate), self._controls, self._messages, self._stop, target),
                self._taken,
            ),
            daemon=True,
            name="racetrace-live",
        )
        self._process.start()

    def send(self, *control) -> None:
        """Queue a control for the child (see the module docstring)."""
        if self._controls is not None:
            self._controls.put(tuple(control))

    def poll(self) -> list[tuple]:
        """Messages since the last call (non-blocking). A child that died without saying so is
        reported as ``("error", ...)`` then ``("stopped",)``."""
        found = []
        if self._messages is None:
            return found
        while True:
            try:
                found.append(self._messages.get_nowait())
            except queue_module.Empty:
                break
            if found[-1][0] == "chunk":
                self._taken.value += 1
        if found and found[-1][0] == "stopped":
            return found
        if self._process is not None and not self._process.is_alive():
            try:
                found.append(self._messages.get(timeout=0.5))
            except queue_module.Empty:
                code = self._process.exitcode
                found += [
                    ("error", f"the live solver process stopped unexpectedly (exit code {code})"),
                    ("stopped",),
                ]
        return found

    def stop(self, timeout_s: float = 3.0) -> None:
        """End the child: ask it, then kill it if it does not end within ``timeout_s``."""
        if self._process is None:
            return
        self._stop.set()
        self._process.join(timeout=timeout_s)
        if self._process.is_alive():
            self._process.kill()
            self._process.join(timeout=2)
        self._process = None
        for q in (self._controls, self._messages):
            q.cancel_join_thread()
            q.close()
        self._controls = self._messages = self._stop = self._taken = None
