"""``racetrace simulate CASE --output run.nc``: run the dynamic model and save the result (NetCDF).

A progress bar with the simulated time and an ETA goes to stderr. Ctrl-C stops the run at the next
chunk boundary: the partial result (attrs ``complete = 0``) is written atomically and the command
exits with 130. A diverged run also writes what it had and exits with 4, printing the likely cause.
Case warnings and result warnings (the result leaves the model's validity, the run stopped early or
is too short to settle) are printed on stderr as ``warning: ...`` lines; they do not change the exit
code. The trajectory metrics (excursion, band thickness, settling) go to stdout, as JSON with
``--json``.
"""

from __future__ import annotations

import json
import signal
import sys
import threading
import time
from pathlib import Path

EXIT_DIVERGED = 4
EXIT_INTERRUPTED = 130


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "simulate",
        help="run the dynamic model (contact trajectories) and save a NetCDF result",
        description=(
            "Integrate the dynamic bearing model of CASE (a case file or a catalogue name) for "
            "[simulation] shaft_revolutions and save every results-schema variable to NetCDF. "
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
        "--no-traction", action="store_true", help="frictionless ball-race contacts"
    )
    parser.add_argument("--no-cage", action="store_true", help="leave the cage out of the model")
    parser.add_argument("--quiet", "-q", action="store_true", help="no progress bar")
    parser.add_argument(
        "--json",
        action="store_true",
        help="print the trajectory metrics and the settling window as JSON",
    )
    parser.set_defaults(func=run)


def _load_case(name: str):
    from solver.catalogue import resolve_case

    return resolve_case(name)


class ProgressBar:
    """Text progress bar on a stream: fraction, simulated time, wall time and ETA."""

    def __init__(self, stream=None, width: int = 30):
        self.stream = stream if stream is not None else sys.stderr
        self.width = width
        self.start = time.perf_counter()
        self._first = None  # (wall time, fraction) of the first report: the rate is timed from it

    def eta(self, now: float, fraction: float) -> float:
        """Seconds left from the rate since the first report (NaN until at least 1 s and 0.5 % of
        progress after it: start-up and compiling say nothing about the rate)."""
        if self._first is None:
            self._first = (now, fraction)
            return float("nan")
        t0, f0 = self._first
        if now - t0 < 1.0 or fraction - f0 < 0.005:
            return float("nan")
        return (now - t0) / (fraction - f0) * (1.0 - fraction)

    def __call__(self, fraction: float, simulated_time: float, message: str = "") -> None:
        now = time.perf_counter()
        elapsed = now - self.start
        eta = self.eta(now, fraction)
        eta_text = f"ETA {eta:.0f} s" if eta == eta else "ETA --"
        filled = int(round(self.width * fraction))
        bar = "#" * filled + "." * (self.width - filled)
        self.stream.write(
            f"\r[{bar}] {100 * fraction:5.1f}%  t = {simulated_time * 1e3:.3f} ms  "
            f"elapsed {elapsed:.0f} s  {eta_text} "
        )
        self.stream.flush()

    def close(self) -> None:
        self.stream.write("\n")
        self.stream.flush()


def _print_case_warnings(case) -> None:
    """Case.warnings() as ``warning: ...`` lines on stderr (inputs without warnings: nothing)."""
    warnings = getattr(case, "warnings", None)
    for warning in warnings() if callable(warnings) else ():
        print(f"warning: {warning.message}", file=sys.stderr)


def run(args) -> int:
    from solver.errors import SimulationDiverged
    from solver.models.dynamic import SimulationOptions, simulate
    from solver.results.io import save_dataset

    from .quasistatic import print_result_warnings

    case = _load_case(args.case)
    _print_case_warnings(case)
    output = Path(args.output) if args.output else Path(Path(args.case).stem + ".nc")
    changes = {}
    if args.revolutions is not None:
        changes["shaft_revolutions"] = args.revolutions
    if args.samples_per_revolution is not None:
        changes["samples_per_revolution"] = args.samples_per_revolution
    if args.tolerance is not None:
        changes["tolerance"] = args.tolerance
    if args.no_traction:
        changes["traction"] = False
    if args.no_cage:
        changes["cage"] = False
    # the case's [simulation] values, overridden by the command line
    options = SimulationOptions(**changes)
    stop = threading.Event()

    def on_sigint(signum, frame):  # noqa: ARG001 - signal handler signature
        if stop.is_set():  # second Ctrl-C: give up at once
            raise KeyboardInterrupt
        stop.set()
        print("\nracetrace: interrupt received, stopping at the next chunk ...", file=sys.stderr)

    previous = signal.signal(signal.SIGINT, on_sigint)
    bar = None if args.quiet else ProgressBar()
    if bar is not None:
        from solver.compiled import dynamic_model_compiled

        if not dynamic_model_compiled():
            print("racetrace: compiling the dynamic model (first run only) ...", file=sys.stderr)
    try:
        try:
            ds = simulate(case, progress=bar, cancel=stop, options=options)
            code = 0
        except SimulationDiverged as error:
            ds = getattr(error, "dataset", None)
            if bar is not None:
                bar.close()
                bar = None
            print(f"racetrace: {error}", file=sys.stderr)
            if ds is None:
                return EXIT_DIVERGED
            code = EXIT_DIVERGED
    finally:
        signal.signal(signal.SIGINT, previous)
        if bar is not None:
            bar.close()
    save_dataset(ds, output)
    print_result_warnings(ds)
    print_metrics(ds, args.json, output)
    if ds.attrs.get("complete", 0) != 1 and code == 0:
        print(
            f"racetrace: interrupted; partial result ({ds.sizes['time']} samples up to "
            f"t = {float(ds.time[-1]):.6g} s) written to {output}",
            file=sys.stderr,
        )
        return EXIT_INTERRUPTED
    if code == EXIT_DIVERGED:
        print(f"racetrace: partial result written to {output}", file=sys.stderr)
        return code
    print(
        f"racetrace: wrote {output} ({ds.sizes['time']} samples, {ds.attrs['wall_time_s']:.1f} s)",
        file=sys.stderr,
    )
    return 0


def print_metrics(ds, as_json: bool, output: Path) -> None:
    """The trajectory metrics and the settling window on stdout (text or JSON)."""
    from racetrace.metrics import metrics_json, metrics_text

    if as_json:
        print(json.dumps({"output": str(output), "trajectory": metrics_json(ds)}, indent=2))
    else:
        print(metrics_text(ds))
