"""``racetrace simulate CASE --output run.nc``: run the dynamic model and save the result (NetCDF).

A progress bar with the simulated time and an ETA goes to stderr. Before the run, the output path
is checked (its folder exists and is writable, it is not a folder) and the run's size is compared
with the free memory, disk and file-size limit: each problem is an invalid input (exit 2). Ctrl-C,
SIGTERM or SIGHUP stop the run at the next chunk boundary: the partial result (attrs
``complete = 0``) is written atomically and the command exits with 128 + the signal number (130 for
Ctrl-C). A diverged run also writes what it had and exits with 4, printing the likely cause. When
the result cannot be written where asked (disk full, file-size limit), it is written to a file in
the temporary folder instead, named on stderr, and the command exits with 5. A signal while the run
starts (loading, compiling, finding the quasi-static start) stops it at once, with nothing written
(exit 128 + the signal number); while the result is being written, signals wait until it is written
(a second Ctrl-C cannot lose it), and the command then exits with 128 + the first one.
Case warnings and result warnings (the result leaves the model's validity, the run stopped early or
is too short to settle) are printed on stderr as ``warning: ...`` lines; they do not change the exit
code. The trajectory metrics (excursion, band thickness, settling) and the rating lives (L10,
L10r) go to stdout, as JSON with ``--json``.

A bearing-set case (a ``[set]`` table) runs the set's dynamic model (``solver.simulate``): the
result has a ``bearing`` dimension, the warnings are named by bearing, and stdout gives each
bearing's loads, trajectory metrics, cage slip, power loss, friction torque and rating lives, then
the set's energy balance (:func:`.bearing_set.dynamic_set_text`). What the set's model cannot run
(a spring preload, time histories) is refused before the run, naming the key (exit 2).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import sys
import threading
import time
from pathlib import Path

from solver import TimeLeft, clean_message

from ._output import output_problem, save_result, size_problems
from ._output import say as _say

EXIT_DIVERGED = 4
#: The result could not be written to the output path: it went to a file in the temporary folder
#: (named on stderr), or nowhere.
EXIT_NOT_WRITTEN = 5
EXIT_INTERRUPTED = 130


class _IntegrationMethods:
    """The dynamic model's integration methods (``solver.INTEGRATION_METHODS``), looked up only
    when argparse checks or lists the ``--method`` choices, so that building the parser imports
    no model."""

    def __iter__(self):
        import solver

        return iter(solver.INTEGRATION_METHODS)

    def __contains__(self, name) -> bool:
        return name in tuple(self)


METHODS = _IntegrationMethods()


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "simulate",
        help="run the dynamic model (contact trajectories) and save a NetCDF result",
        description=(
            "Integrate the dynamic bearing model of CASE (a case file or a catalogue name) for "
            "[simulation] shaft_revolutions and save every results-schema variable to NetCDF "
            "(a bearing set's case: the set's model, with a 'bearing' dimension). "
            "Case and result warnings go to stderr as 'warning: ...' lines. Exit codes: 0 done, "
            "2 invalid input, 3 no quasi-static start, 4 diverged (partial result saved), "
            "130 interrupted (partial result saved)."
        ),
    )
    parser.add_argument("case", help="case file (.toml) or catalogue case name")
    parser.add_argument("--output", "-o", help="NetCDF file to write (default: <case name>.nc)")
    parser.add_argument("--revolutions", type=float, help="override [simulation] shaft_revolutions")
    parser.add_argument(
        "--samples-per-revolution", type=int, help="override [simulation] samples_per_revolution"
    )
    parser.add_argument("--tolerance", type=float, help="override [simulation] tolerance")
    parser.add_argument(
        "--method",
        choices=METHODS,
        metavar="METHOD",  # argparse would list the choices when the parser is built
        help="integration method: %(choices)s (default auto; docs/numerics.md)",
    )
    parser.add_argument(
        "--no-traction", action="store_true", help="frictionless ball-race contacts"
    )
    parser.add_argument("--no-cage", action="store_true", help="leave the cage out of the model")
    parser.add_argument("--quiet", "-q", action="store_true", help="no progress bar")
    parser.add_argument(
        "--json",
        action="store_true",
        help="print the trajectory metrics, the settling window and the rating lives as JSON",
    )
    parser.set_defaults(func=run)


def _load_case(name: str):
    from solver import resolve_case

    return resolve_case(name)


class ProgressBar:
    """Text progress bar on a stream: fraction, simulated time, wall time and ETA."""

    def __init__(self, stream=None, width: int = 30):
        self.stream = stream if stream is not None else sys.stderr
        self.width = width
        self.start = time.perf_counter()
        self.eta = TimeLeft()  # seconds left, from the rate since the first report

    def __call__(self, fraction: float, simulated_time: float, message: str = "") -> None:
        now = time.perf_counter()
        elapsed = now - self.start
        eta = self.eta(now, fraction)
        eta_text = f"ETA {eta:.0f} s" if eta == eta else "ETA --"
        filled = int(round(self.width * fraction))
        bar = "#" * filled + "." * (self.width - filled)
        self._write(
            f"\r[{bar}] {100 * fraction:5.1f}%  t = {simulated_time * 1e3:.3f} ms  "
            f"elapsed {elapsed:.0f} s  {eta_text} "
        )

    def close(self) -> None:
        self._write("\n")

    def _write(self, text: str) -> None:
        """Write and flush; a closed terminal (after a hang-up) silences the bar, never the run."""
        if self.stream is None:
            return
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):
            self.stream = None


def _print_case_warnings(case) -> None:
    """Case.warnings() as ``warning: ...`` lines on stderr (inputs without warnings: nothing)."""
    warnings = getattr(case, "warnings", None)
    for warning in warnings() if callable(warnings) else ():
        print(f"warning: {warning.message}", file=sys.stderr)


def _options(args, case):
    """SimulationOptions from the command line, checked with the case keys' bounds and the run
    length rules (CaseError naming the option otherwise), and the run's size estimate."""
    from solver import (
        CaseError,
        SimulationOptions,
        dynamic_ball_count,
        dynamic_run_size,
        run_length_problems,
    )

    changes = {}
    if args.revolutions is not None:
        changes["shaft_revolutions"] = args.revolutions
    if args.samples_per_revolution is not None:
        changes["samples_per_revolution"] = args.samples_per_revolution
    if args.tolerance is not None:
        changes["tolerance"] = args.tolerance
    if args.method is not None:
        changes["method"] = args.method
    if args.no_traction:
        changes["traction"] = False
    if args.no_cage:
        changes["cage"] = False
    # the case's [simulation] values, overridden by the command line
    options = SimulationOptions(**changes).validated()
    sim = case.simulation
    balls = dynamic_ball_count(case) if hasattr(case, "bearing") else case.geometry.ball_count
    if getattr(case, "histories", None):  # a case with a time history runs for a duration
        return options, _history_run_size(args, sim, balls)
    revolutions = sim.shaft_revolutions if args.revolutions is None else args.revolutions
    per_rev = (
        sim.samples_per_revolution
        if args.samples_per_revolution is None
        else args.samples_per_revolution
    )
    names = (
        "simulation.shaft_revolutions" if args.revolutions is None else "--revolutions",
        "simulation.samples_per_revolution"
        if args.samples_per_revolution is None
        else "--samples-per-revolution",
    )
    problems = run_length_problems(revolutions, per_rev, balls, names)
    if problems:
        raise CaseError(problems)
    return options, dynamic_run_size(revolutions, per_rev, balls)


def _history_run_size(args, sim, balls: int):
    """The run size of a case with a time history (``simulation.duration_s`` at
    ``samples_per_second``); CaseError for the run-length options of a steady case or a run
    the length rules refuse."""
    from solver import CaseError, Problem, dynamic_run_size, history_run_length_problems

    for option, value, key in (
        ("--revolutions", args.revolutions, "simulation.duration_s"),
        ("--samples-per-revolution", args.samples_per_revolution, "simulation.samples_per_second"),
    ):
        if value is not None:
            raise CaseError(
                Problem(
                    option,
                    f"{option} {value:g}: this case has a time history and runs for a duration "
                    f"in seconds; set {key} in the case instead",
                )
            )
    problems = history_run_length_problems(sim.duration_s, sim.samples_per_second, balls)
    if problems:
        raise CaseError(problems)
    # samples = duration x samples per second, as revolutions x samples per revolution
    return dynamic_run_size(sim.duration_s, sim.samples_per_second, balls)


def _check_room(size, output: Path) -> None:
    """Refuse a run whose result would not fit in the memory, the disk or the file-size limit
    (CaseError); warn when it takes more than half of the memory or disk."""
    from solver import CaseError, Problem

    errors, warnings = size_problems(size.memory_bytes, size.file_bytes, output.parent)
    for warning in warnings:
        _say(f"warning: {warning}")
    if errors:
        raise CaseError([Problem("output", e) for e in errors])


class _StoppedBeforeTheRun(BaseException):
    """A stop signal arrived while the run was starting (loading, checking, compiling, finding
    the quasi-static start): nothing computed is worth keeping. A BaseException, so that no
    ``except Exception`` on the way swallows it."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


class StopSignals:
    """The handler of :data:`STOP_SIGNALS` for one run, by phase (``phase``):

    - ``"starting"`` (until the first chunk is integrated): stop at once, raising
      :class:`_StoppedBeforeTheRun`; nothing has been written;
    - ``"running"``: the first signal sets ``stop`` (the run ends at the next chunk and keeps its
      partial result); later ones are deferred;
    - ``"saving"``: every signal is deferred until the result is written, so that a second Ctrl-C
      cannot lose it.

    ``received`` lists the signals in order; the command exits with 128 + the first."""

    def __init__(self):
        self.phase = "starting"
        self.stop = threading.Event()
        self.received: list[int] = []

    def __call__(self, signum, frame) -> None:  # noqa: ARG002 - signal handler signature
        self.received.append(signum)
        name = signal.Signals(signum).name
        if self.phase == "starting":
            raise _StoppedBeforeTheRun(signum)
        if self.phase == "running" and len(self.received) == 1:
            self.stop.set()
            _say(
                f"\nracetrace: {name} received, stopping at the next chunk (the partial result "
                "is kept) ..."
            )
            return
        _say(
            f"\nracetrace: {name} received: saving the result first, then stopping (kill -9 "
            "abandons it)"
        )

    def progress(self, bar):
        """The progress callback for the model: marks the run as running, then draws ``bar``
        (None: no bar)."""

        def report(fraction: float, simulated_time: float, message: str = "") -> None:
            if self.phase == "starting":
                self.phase = "running"
            if bar is not None:
                bar(fraction, simulated_time, message)

        return report


def run(args) -> int:
    """Run the command with :class:`StopSignals` handling SIGINT, SIGTERM and SIGHUP from its
    first line to its last (exit 128 + the signal when one stopped it)."""
    signals = StopSignals()
    previous = _install(signals)
    try:
        return _run(args, signals)
    except _StoppedBeforeTheRun as stopped:
        _say(
            f"\nracetrace: {signal.Signals(stopped.signum).name} received before the run "
            "started: stopped, nothing computed or written"
        )
        return 128 + stopped.signum
    finally:
        _restore(previous)


def _run(args, signals: StopSignals) -> int:
    from solver import CaseError, Problem, SimulationDiverged, dynamic_problems, simulate

    from .quasistatic import print_result_warnings

    case = _load_case(args.case)
    _print_case_warnings(case)
    if getattr(case, "bearing_set", None) is not None:  # what a set's run cannot do, first
        problems = dynamic_problems(case)
        if problems:
            raise CaseError(problems)
    output = Path(args.output) if args.output else Path(Path(args.case).stem + ".nc")
    # everything that can be checked before a run that may take hours
    problem = output_problem(output, "--output" if args.output else "output")
    if problem:
        raise CaseError(Problem("output", problem))
    options, size = _options(args, case)
    _check_room(size, output)

    received = signals.received
    bar = None if args.quiet else ProgressBar()
    if bar is not None:
        from solver import dynamic_model_compiled

        if not dynamic_model_compiled():
            print("racetrace: compiling the dynamic model (first run only) ...", file=sys.stderr)
    try:
        ds = simulate(case, progress=signals.progress(bar), cancel=signals.stop, options=options)
        code = 0
    except SimulationDiverged as error:
        ds = getattr(error, "dataset", None)
        if bar is not None:
            bar.close()
            bar = None
        _say(f"racetrace: {clean_message(error)}")
        if ds is None:
            return EXIT_DIVERGED
        code = EXIT_DIVERGED
    finally:
        signals.phase = "saving"  # from here every signal waits for the result to be written
        if bar is not None:
            bar.close()
    written = save_result(ds, output, _say)
    with contextlib.suppress(OSError, ValueError):  # a closed terminal: the file is what matters
        if "bearing" in ds.dims:
            print_set_warnings(ds)
        else:
            print_result_warnings(ds)
    print_metrics(ds, args.json, written)
    if written is None:
        return EXIT_NOT_WRITTEN
    moved = written != output
    if ds.attrs.get("complete", 0) != 1 and code == 0:
        name = signal.Signals(received[0]).name if received else "interrupt"
        _say(
            f"racetrace: stopped by {name}; partial result ({ds.sizes['time']} samples up to "
            f"t = {float(ds.time[-1]):.6g} s) written to {written}"
        )
        return EXIT_NOT_WRITTEN if moved else 128 + (received[0] if received else signal.SIGINT)
    if code == EXIT_DIVERGED:
        _say(f"racetrace: partial result written to {written}")
        return EXIT_NOT_WRITTEN if moved else code
    _say(
        f"racetrace: wrote {written} ({ds.sizes['time']} samples, {ds.attrs['wall_time_s']:.1f} s)"
    )
    if moved:
        return EXIT_NOT_WRITTEN
    if received:  # the run had finished: its complete result was written, then the stop obeyed
        _say(f"racetrace: stopped by {signal.Signals(received[0]).name} after the write")
        return 128 + received[0]
    return 0


#: Signals that stop a run and keep its partial result (SIGHUP: the terminal was closed).
STOP_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)


def _install(handler) -> dict:
    """Set ``handler`` for :data:`STOP_SIGNALS`; returns the previous handlers (none when not on
    the main thread, where signals cannot be handled)."""
    previous = {}
    if threading.current_thread() is not threading.main_thread():
        return previous
    for signum in STOP_SIGNALS:
        previous[signum] = signal.signal(signum, handler)
    return previous


def _restore(previous: dict) -> None:
    for signum, handler in previous.items():
        signal.signal(signum, handler)


def print_set_warnings(ds) -> None:
    """A bearing set's result warnings (``solver.set_result_warnings``) as ``warning: ...``
    lines on stderr."""
    from solver import set_result_warnings

    for message in set_result_warnings(ds):
        print(f"warning: {message}", file=sys.stderr)


def print_metrics(ds, as_json: bool, output: Path | None) -> None:
    """The trajectory metrics, the settling window and the rating lives on stdout (text or JSON;
    ``output`` is the file written, None when the result could not be written)."""
    from racetrace.metrics import (
        life_json,
        life_text,
        metrics_json,
        metrics_text,
        torque_json,
        torque_text,
    )

    from .bearing_set import dynamic_set_summary, dynamic_set_text

    try:
        if "bearing" in ds.dims:  # a bearing set: per bearing, and the set's energy balance
            if as_json:
                out = {"output": None if output is None else str(output)}
                out |= dynamic_set_summary(ds)
                print(json.dumps(out, indent=2, allow_nan=False))
            else:
                print(dynamic_set_text(ds))
        elif as_json:
            out = {
                "output": None if output is None else str(output),
                "trajectory": metrics_json(ds),
                "life": life_json(ds),
                "friction_torque": torque_json(ds),
            }
            print(json.dumps(out, indent=2, allow_nan=False))
        else:
            print(metrics_text(ds))
            print(life_text(ds))
            print(torque_text(ds))
        sys.stdout.flush()
    except BrokenPipeError:  # output piped into e.g. `head`: not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except OSError:  # the terminal was closed (SIGHUP): the result file is what matters
        pass
