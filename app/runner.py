"""Run a solver in a separate ``spawn`` process, with a progress queue and a cancel event.

The child process imports the job (``"module:function"``, called as ``job(case_text, progress,
cancel) -> xarray.Dataset``), saves the Dataset to a NetCDF file given by the parent (or, when that
folder cannot take it, to the temporary folder: the ``done`` message names the file written) and
reports through a queue. ``spawn`` keeps the server's VTK/EGL state out of the child, and a crash
of the child (even a segfault) only ends that run: :meth:`SolverRunner.poll` reports it as an
error.

Messages from the child, as tuples:
``("progress", fraction, simulated_time_s, text)`` (a text starting with :data:`PREPARING`: what
the run does before its first step), ``("done", path, complete)``, ``("error", text)``.
"""

from __future__ import annotations

import importlib
import multiprocessing as mp
import queue as queue_module
import sys
import time
from dataclasses import dataclass

DYNAMIC_JOB = "app.runner:dynamic_job"
QUASISTATIC_JOB = "app.runner:quasistatic_job"
#: Text of the progress messages (fraction 0) that say what a run does before its first step:
#: loading the compiled kernels, or compiling them (``app.compile_watch``).
PREPARING = "preparing: "


# ---- jobs (run in the child) ---------------------------------------------------------------------
def dynamic_job(case_text: str, progress, cancel):
    """The dynamic model on a case given as TOML text. Before the first step it reports
    (:data:`PREPARING`) whether numba loads the compiled kernels or compiles them."""
    import solver

    from .compile_watch import LOADING, compiling_words, watching_compiles

    case = solver.parse_case(case_text)
    nan = float("nan")
    progress(0.0, nan, PREPARING + LOADING)
    with watching_compiles(lambda count: progress(0.0, nan, PREPARING + compiling_words(count))):
        return solver.simulate(case, progress=progress, cancel=cancel)


def quasistatic_job(case_text: str, progress, cancel):
    """The quasi-static answer (``solver.quasistatic_answer``: over one revolution for a tilt
    turning with the inner ring) on a case given as TOML text (no progress, not cancellable)."""
    import solver

    return solver.quasistatic_answer(solver.parse_case(case_text))


def _child_main(target: str, case_text: str, out_path: str, messages, cancel_event) -> None:
    """Entry point of the child process: never raises, always ends with a done/error message."""
    import signal

    from app.process import die_with_parent

    die_with_parent(signal.SIGKILL)  # a solver never runs on without the server
    # Ctrl-C in the server's terminal reaches this process too: the server stops the run itself
    # (cancel event), so that the part computed so far is saved
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    from solver import (
        CaseError,
        NoSolutionError,
        ResultWriteError,
        SimulationDiverged,
        clean_message,
    )

    try:
        module_name, func_name = target.split(":")
        job = getattr(importlib.import_module(module_name), func_name)

        def progress(fraction, simulated_time=float("nan"), text="", *_):
            messages.put(("progress", float(fraction), float(simulated_time), str(text)))

        ds = job(case_text, progress, cancel_event)
        written = _save(ds, out_path)
        messages.put(("done", written, int(ds.attrs.get("complete", 1))))
    except (CaseError, NoSolutionError, SimulationDiverged, ResultWriteError) as error:
        messages.put(("error", clean_message(error)))
    except Exception as error:  # an unexpected failure: say what it was, in one line
        import traceback

        traceback.print_exc(file=sys.stderr)  # the server log keeps the details
        messages.put(("error", f"internal error in the solver ({type(error).__name__}: {error})"))


def _save(ds, out_path: str) -> str:
    """Save the job's result at ``out_path``, or, when the runs folder cannot take it (read-only,
    full), in the temporary folder; returns the path written. ResultWriteError when neither works
    (both reasons in the message)."""
    import tempfile
    from pathlib import Path

    from solver import ResultWriteError, save_dataset

    try:
        return str(save_dataset(ds, out_path))
    except ResultWriteError as error:
        fallback = Path(tempfile.gettempdir()) / Path(out_path).name.lstrip(".")
        try:
            return str(save_dataset(ds, fallback))
        except ResultWriteError as second:
            raise ResultWriteError(out_path, f"{error.reason}; and {second}") from None


# ---- parent side ---------------------------------------------------------------------------------
@dataclass
class RunEvent:
    """What :meth:`SolverRunner.poll` reports. ``kind`` is progress | done | error."""

    kind: str
    fraction: float = 0.0
    simulated_time: float = float("nan")
    text: str = ""
    path: str = ""
    complete: int = 1
    eta_s: float = float("nan")  # estimated seconds left (progress events)


class SolverRunner:
    """At most one background run at a time."""

    def __init__(self):
        self._ctx = mp.get_context("spawn")
        self._process = None
        self._messages = None
        self._cancel = None
        self._time_left = None  # solver.TimeLeft of the run going: its rate is timed from there
        self._finished = True

    @property
    def busy(self) -> bool:
        return not self._finished

    def start(self, case_text: str, out_path: str, target: str = DYNAMIC_JOB) -> None:
        """Start ``target`` on ``case_text`` in a spawn process; result saved to ``out_path``."""
        if self.busy:
            raise RuntimeError("a run is already in progress; cancel it first")
        self._messages = self._ctx.Queue()
        self._cancel = self._ctx.Event()
        self._process = self._ctx.Process(
            target=_child_main,
            args=(target, case_text, str(out_path), self._messages, self._cancel),
            daemon=True,
            name="racetrace-solver",
        )
        from solver import TimeLeft

        self._time_left = TimeLeft()
        self._finished = False
        self._process.start()

    def cancel(self) -> None:
        """Ask the run to stop at its next check; it then reports ``done`` with ``complete = 0``."""
        if self._cancel is not None:
            self._cancel.set()

    def stop_now(self) -> None:
        """End the run's process at once, without waiting for a check of the cancel event (a
        process that is still compiling the kernels checks none); nothing of it is saved."""
        if self._process is not None and self._process.is_alive():
            self._process.kill()
        self._finish()

    def poll(self) -> list[RunEvent]:
        """Events since the last call (non-blocking); the last one is done/error when finished."""
        events = []
        if self._messages is None or self._finished:
            return events
        while True:
            try:
                msg = self._messages.get_nowait()
            except queue_module.Empty:
                break
            events.append(self._event(msg))
            if msg[0] in ("done", "error"):
                self._finish()
                return events
        if self._process is not None and not self._process.is_alive():
            # the child ended: collect a last message, or report its death
            try:
                msg = self._messages.get(timeout=0.5)
                events.append(self._event(msg))
            except queue_module.Empty:
                code = self._process.exitcode
                events.append(
                    RunEvent(
                        "error", text=f"the solver process stopped unexpectedly (exit code {code})"
                    )
                )
            self._finish()
        return events

    def _event(self, msg) -> RunEvent:
        if msg[0] == "progress":
            _, fraction, sim_t, text = msg
            eta = self._time_left(time.monotonic(), fraction)
            return RunEvent(
                "progress", fraction=fraction, simulated_time=sim_t, text=text, eta_s=eta
            )
        if msg[0] == "done":
            return RunEvent("done", fraction=1.0, path=msg[1], complete=int(msg[2]))
        return RunEvent("error", text=str(msg[1]))

    def _finish(self) -> None:
        self._finished = True
        if self._process is not None:
            self._process.join(timeout=5)
            if self._process.is_alive():
                self._process.kill()
            self._process = None

    def shutdown(self) -> None:
        """Stop any running child (used when the server exits)."""
        if self._process is not None and self._process.is_alive():
            self.cancel()
            self._process.join(timeout=2)
            if self._process.is_alive():
                self._process.kill()
        self._finish()
