"""``racetrace study STUDY.toml --output DIR`` runs a study on Dask; ``racetrace study show DIR``
prints its points and metrics.

A study (docs/study-format.md) runs on a local Dask cluster of ``--workers`` single-threaded
processes (default: one per core), or on an existing cluster with ``--scheduler tcp://HOST:PORT``
(a server that does not answer as a Dask scheduler within 30 s is invalid input). Each run is
saved in DIR as it finishes; ``--resume`` continues a stopped study, skipping the runs already
finished, after checking that the base case, the run options and the solver are those of the
finished runs (``--restart`` runs every point again, ``--accept-solver-change`` keeps runs made by
another solver and records it). A progress bar (runs done, running, ETA) goes to stderr. Ctrl-C,
SIGTERM and SIGHUP stop the study: the cluster is shut down, what is done is kept (study.nc
written), the resume command is printed, and the command exits with 128 + the signal's number
(130, 143, 129); a second signal stops at once. Exit codes: 0 every run done, 1 some runs failed
(their messages are in the table), 2 invalid input, 129/130/143 stopped by a signal.
"""

from __future__ import annotations

import math
import signal
import sys
import threading
import time
from pathlib import Path

EXIT_SOME_FAILED = 1
EXIT_INTERRUPTED = 130
#: The signals that stop a study cleanly; the exit code is 128 + the signal's number.
STOP_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

#: Columns of ``study show``: (variable, race or None, header, scale, format)
SHOW_COLUMNS = (
    ("excursion", "inner", "exc_i deg", 1.0, "{:.4f}"),
    ("excursion", "outer", "exc_o deg", 1.0, "{:.4f}"),
    ("band_thickness", "inner", "band_i deg", 1.0, "{:.4f}"),
    ("band_thickness", "outer", "band_o deg", 1.0, "{:.4f}"),
    ("band_width", "inner", "width_i deg", 1.0, "{:.4f}"),
    ("band_width", "outer", "width_o deg", 1.0, "{:.4f}"),
    ("mean_contact_angle", "inner", "alpha_i deg", 1.0, "{:.2f}"),
    ("mean_contact_angle", "outer", "alpha_o deg", 1.0, "{:.2f}"),
    ("peak_pressure", "inner", "p_i GPa", 1e-9, "{:.3f}"),
    ("peak_pressure", "outer", "p_o GPa", 1e-9, "{:.3f}"),
    ("largest_load", "inner", "Q_i N", 1.0, "{:.0f}"),
    ("largest_load", "outer", "Q_o N", 1.0, "{:.0f}"),
    ("cage_slip", None, "cage slip", 1.0, "{:.4f}"),
    ("settling_time", None, "settle ms", 1e3, "{:.2f}"),
)
#: The columns of the narrow table (the default: it fits :data:`TERMINAL_WIDTH` columns).
NARROW_COLUMNS = ("band_i deg", "band_o deg", "width_i deg", "width_o deg", "p_i GPa", "p_o GPa")
#: How the narrow table writes a model.
MODEL_SHORT = {"quasistatic": "qs", "dynamic": "dyn"}
#: Width of the terminal the default table fits, in characters.
TERMINAL_WIDTH = 120
#: The legend of the metric columns.
LEGEND = (
    "exc = trajectory excursion, band = band thickness, width = band width (each race in its "
    "own ring's frame), alpha = mean contact angle, p = peak pressure, Q = largest contact load; "
    "each row's metrics are its model's: dynamic over the analysed window; quasistatic in steady "
    "running from its solution, the balls moving through a load field fixed in space (or turning "
    "with the inner ring), so a ring turning through the field draws a band (exc 0) and one "
    "holding it still a line; over one revolution for a misalignment turning with the inner ring"
)


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "study",
        help="run a parameter study on Dask (or: study show DIR)",
        description=(
            "Run the study file STUDY.toml (docs/study-format.md) on Dask and keep every run in "
            "the --output folder; or `racetrace study show DIR` to print a study folder's table. "
            "Exit codes: 0 all runs done, 1 some runs failed, 2 invalid input, 130/143/129 "
            "stopped by SIGINT/SIGTERM/SIGHUP (finished runs kept: run again with --resume)."
        ),
    )
    parser.add_argument("study", metavar="STUDY.toml | show", help="study file, or 'show'")
    parser.add_argument("folder", nargs="?", metavar="DIR", help="with 'show': the study folder")
    parser.add_argument("--output", "-o", help="study folder to write (required to run)")
    parser.add_argument(
        "--workers", type=int, help="local worker processes (default: one per core)"
    )
    parser.add_argument(
        "--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://host:8786"
    )
    parser.add_argument(
        "--resume", action="store_true", help="continue the study in --output, skipping finished"
    )
    parser.add_argument(
        "--restart",
        action="store_true",
        help="delete the runs of the study folder --output and run every point again",
    )
    parser.add_argument(
        "--accept-solver-change",
        action="store_true",
        help="with --resume: keep runs made by another solver version (recorded in the study)",
    )
    parser.add_argument("--quiet", "-q", action="store_true", help="no progress bar")
    parser.add_argument("--model", choices=("quasistatic", "dynamic"), help="show: only this model")
    parser.add_argument(
        "--wide",
        action="store_true",
        help=f"show: every metric column (wider than {TERMINAL_WIDTH} characters)",
    )
    parser.set_defaults(func=run)


def _fail(message: str) -> int:
    from racetrace.cli import EXIT_INVALID_INPUT

    print(f"racetrace: invalid input:\n{message}", file=sys.stderr)
    return EXIT_INVALID_INPUT


class StudyProgressBar:
    """One-line progress of a study on a stream: runs done/total, running, failed, ETA."""

    def __init__(self, stream=None, width: int = 30):
        self.stream = stream if stream is not None else sys.stderr
        self.width = width

    def __call__(self, p) -> None:
        fraction = p.done / p.total if p.total else 1.0
        filled = int(round(self.width * fraction))
        bar = "#" * filled + "." * (self.width - filled)
        eta = f"ETA {p.eta_s:.0f} s" if math.isfinite(p.eta_s) else "ETA --"
        failed = f", {p.failed} failed" if p.failed else ""
        self.stream.write(
            f"\r[{bar}] {p.done}/{p.total} runs done{failed}, {p.running} running, "
            f"elapsed {p.elapsed_s:.0f} s, {eta} "
        )
        self.stream.flush()

    def close(self) -> None:
        self.stream.write("\n")
        self.stream.flush()


class StopSignals:
    """While active (a ``with`` block): SIGINT, SIGTERM and SIGHUP set ``event`` (the study stops
    after cancelling what is pending, keeping what is done) and are remembered in ``signum``; a
    second one raises KeyboardInterrupt to stop at once. The previous handlers come back on exit."""

    def __init__(self, event: threading.Event):
        self.event = event
        self.signum: int | None = None
        self._previous: dict = {}

    def _handle(self, signum, frame):  # noqa: ARG002 - the signal handler interface
        if self.event.is_set():
            raise KeyboardInterrupt
        self.signum = signum
        self.event.set()
        print(
            f"\nracetrace: {signal.Signals(signum).name} received: stopping, finished runs are "
            "kept ...",
            file=sys.stderr,
        )

    def __enter__(self):
        for signum in STOP_SIGNALS:
            self._previous[signum] = signal.signal(signum, self._handle)
        return self

    def __exit__(self, *exc):
        for signum, previous in self._previous.items():
            signal.signal(signum, previous)
        return False

    @property
    def exit_code(self) -> int:
        return 128 + (self.signum or signal.SIGINT)


def run(args) -> int:
    if args.study == "show":
        if not args.folder:
            return _fail(
                "study show DIR: name the study folder (the --output of a study run) or a "
                "study file (*.study.nc)"
            )
        return show(args.folder, args.model, args.wide)
    if args.folder:
        return _fail(f"unexpected argument {args.folder!r}: give the folder with --output")
    if not args.output:
        return _fail("--output DIR is required: the folder where the study keeps its runs")
    if args.workers is not None and args.workers < 1:
        return _fail(f"--workers {args.workers}: give 1 or more worker processes")
    if args.workers is not None and args.scheduler:
        return _fail("--workers and --scheduler together: the cluster at --scheduler has its own")
    if args.restart and args.resume:
        return _fail(
            "--resume and --restart together: --resume keeps the finished runs, "
            "--restart deletes them; give one"
        )
    if args.accept_solver_change and not args.resume:
        return _fail("--accept-solver-change goes with --resume (it keeps the finished runs)")
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        return _fail("the study runner needs dask.distributed: pip install 'dask[distributed]'")
    from solver import Study, connect_scheduler, scheduler_address

    if args.scheduler:
        scheduler_address(args.scheduler)  # CaseError naming the form before any other work
    stop = threading.Event()
    with StopSignals(stop) as signals:
        try:
            study = Study.from_file(args.study)
            if stop.is_set():  # a signal while the study was read: nothing started yet
                print("racetrace: stopped before the study started", file=sys.stderr)
                return signals.exit_code
            return _run_study(args, study, signals, connect_scheduler)
        except KeyboardInterrupt:  # a second signal: stopped at once
            print("racetrace: stopped at once; finished runs are kept", file=sys.stderr)
            print(_resume_hint(args), file=sys.stderr)
            return signals.exit_code if signals.signum else EXIT_INTERRUPTED


def _resume_hint(args) -> str:
    return (
        f"racetrace: interrupted: run `racetrace study {args.study} --output {args.output} "
        "--resume` to finish"
    )


def _run_study(args, study, signals: StopSignals, connect_scheduler) -> int:
    stop = signals.event
    client = None
    if args.scheduler:
        client = connect_scheduler(args.scheduler)
    points = study.points()
    runs = sum(len(p.models) for p in points)
    print(
        f"racetrace: study {study.title!r}: {len(points)} point(s), {runs} run(s) -> {args.output}",
        file=sys.stderr,
    )
    bar = None if args.quiet else StudyProgressBar()
    started = time.perf_counter()
    try:
        ds = study.run(
            args.output,
            client=client,
            workers=args.workers,
            resume=args.resume,
            progress=bar,
            cancel=stop,
            log=lambda line: print(f"racetrace: {line}", file=sys.stderr),
            restart=args.restart,
            accept_solver_change=args.accept_solver_change,
        )
    finally:
        if bar is not None:
            bar.close()
        if client is not None:
            client.close()
    status = ds["status"].values
    done = int((status == "done").sum())
    failed = int((status == "failed").sum())
    pending = int((status == "pending").sum())
    print(
        f"racetrace: {done} run(s) done, {failed} failed, {pending} not run, in "
        f"{time.perf_counter() - started:.0f} s; study Dataset {Path(args.output) / 'study.nc'}",
        file=sys.stderr,
    )
    print(show_table(ds))
    if stop.is_set() or pending:
        print(_resume_hint(args), file=sys.stderr)
        return signals.exit_code
    return EXIT_SOME_FAILED if failed else 0


#: Columns of ``study show`` for a study of bearing sets (its Dataset has a ``bearing``
#: coordinate): each bearing's axial load (one column per bearing), then these.
SET_SHOW_COLUMNS = (
    ("axial_stiffness", None, "k_ax N/um", 1e-6, "{:.1f}"),
    ("radial_stiffness", None, "k_rad N/um", 1e-6, "{:.1f}"),
    ("tilt_stiffness", None, "k_tilt Nm/mrad", 1e-3, "{:.2f}"),
)
SET_LEGEND = (
    "Fa = axial load each bearing of the set carries in its own direction (preload included), "
    "k_ax, k_rad, k_tilt = the set's axial, radial and tilting stiffness at the load point "
    "(quasi-static set model)"
)


def _set_columns(ds) -> list:
    """The ``study show`` columns of a bearing-set study."""
    per_bearing = [
        ("bearing_axial_load", str(b), f"Fa {b} N", 1.0, "{:.1f}") for b in ds["bearing"].values
    ]
    return [*per_bearing, *SET_SHOW_COLUMNS]


def show_table(ds, model: str | None = None, wide: bool = False) -> str:
    """The points and their metrics as a text table (one row per point and model). ``wide``:
    every column of :data:`SHOW_COLUMNS` and each varied key in its own column; else the varied
    values a point's sweep changes in one column and the :data:`NARROW_COLUMNS`, to fit
    :data:`TERMINAL_WIDTH` characters."""
    import json
    import textwrap

    import numpy as np

    from solver import sweep_varied_keys

    keys = json.loads(ds.attrs.get("varied_keys", "[]"))
    sets = "bearing" in ds.coords  # a study of bearing sets: their loads and stiffness
    if sets:
        columns = _set_columns(ds)
    else:
        columns = [c for c in SHOW_COLUMNS if wide or c[2] in NARROW_COLUMNS]
    varied_headers = [k.rsplit(".", 1)[-1] for k in keys] if wide else ["varied"]
    headers = ["point", "model", *varied_headers, "status", *(c[2] for c in columns)]
    sweep_keys = sweep_varied_keys(ds)
    rows = []
    messages = []

    def shown(value) -> str:
        if isinstance(value, float | int | np.floating):
            return f"{value:g}" if math.isfinite(value) else "-"
        return str(value)

    for i, point in enumerate(ds["point"].values):
        for j, name in enumerate(ds["model"].values):
            if model and name != model:
                continue
            status = str(ds["status"].values[i, j])
            if status == "not run":
                continue
            row = [str(point), str(name) if wide else MODEL_SHORT.get(str(name), str(name))]
            if wide:
                row += [shown(ds[key].values[i]) for key in keys]
            else:
                changed = sweep_keys.get(str(ds["sweep"].values[i]), keys)
                row.append(
                    ", ".join(f"{k.rsplit('.', 1)[-1]}={shown(ds[k].values[i])}" for k in changed)
                )
            row.append(status)
            for var, label, _h, scale, fmt in columns:  # label: a race, or a bearing
                da = ds[var].isel(point=i, model=j)
                dim = "bearing" if "bearing" in da.dims else "race"
                value = float(da.sel({dim: label})) if label else float(da)
                row.append(fmt.format(value * scale) if math.isfinite(value) else "-")
            rows.append(row)
            if status == "failed":
                messages.append(f"{point} {name}: {ds['message'].values[i, j]}")
    widths = [
        max(len(h), *(len(r[k]) for r in rows)) if rows else len(h) for k, h in enumerate(headers)
    ]
    lines = ["  ".join(h.rjust(w) for h, w in zip(headers, widths, strict=True))]
    lines += ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in rows]
    if messages:
        lines += ["", "failed runs:"]
        lines += [textwrap.fill(m, TERMINAL_WIDTH, subsequent_indent="  ") for m in messages]
    legend = SET_LEGEND if sets else LEGEND
    legend = legend if wide else "qs = quasistatic, dyn = dynamic, " + legend
    lines.append(textwrap.fill(legend, TERMINAL_WIDTH))
    if not wide and not sets:
        lines.append(
            "every metric (excursion, contact angle, load, cage slip, settling time) and each "
            "varied key in its own column:"
        )
        lines.append("  racetrace study show DIR --wide")
    return "\n".join(lines)


def show(folder, model=None, wide: bool = False) -> int:
    """Print a study's table: a study folder, or a study Dataset file (``*.study.nc``, as shipped
    in assets/studies/results/) read as ``racetrace report`` reads it."""
    from solver import CaseError, Problem, load_result, open_study, study_dataset

    path = Path(folder)
    if path.is_file():
        ds = load_result(path, str(folder))
        if ds.attrs.get("racetrace_kind") != "study":
            raise CaseError(
                Problem(
                    "study show",
                    f"{folder}: a run result, not a study (racetrace report or export reads it)",
                )
            )
        where = f"file {folder}"
    else:
        ds = study_dataset(open_study(folder))
        where = f"folder {folder}"
    import textwrap

    heading = f"study {ds.attrs['title']!r} (base case {ds.attrs['base_case']}), {where}"
    print(textwrap.fill(heading, TERMINAL_WIDTH, subsequent_indent="  "))
    print(show_table(ds, model, wide))
    return 0
