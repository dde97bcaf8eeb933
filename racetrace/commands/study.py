"""``racetrace study STUDY.toml --output DIR`` runs a study on Dask; ``racetrace study show DIR``
prints its points and metrics.

A study (docs/study-format.md) runs on a local Dask cluster of ``--workers`` single-threaded
processes (default: one per core), or on an existing cluster with ``--scheduler ADDRESS``. Each
run is saved in DIR as it finishes; ``--resume`` continues a stopped study, skipping the runs
already finished. A progress bar (runs done, running, ETA) goes to stderr. Ctrl-C stops the study:
what is done is kept, and the command exits with 130. Exit codes: 0 every run done, 1 some runs
failed (their messages are in the table), 2 invalid input, 130 interrupted.
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

#: Columns of ``study show``: (variable, race or None, header, scale, format)
SHOW_COLUMNS = (
    ("excursion", "inner", "exc_i deg", 1.0, "{:.4f}"),
    ("excursion", "outer", "exc_o deg", 1.0, "{:.4f}"),
    ("band_thickness", "inner", "band_i deg", 1.0, "{:.4f}"),
    ("band_thickness", "outer", "band_o deg", 1.0, "{:.4f}"),
    ("mean_contact_angle", "inner", "alpha_i deg", 1.0, "{:.2f}"),
    ("mean_contact_angle", "outer", "alpha_o deg", 1.0, "{:.2f}"),
    ("peak_pressure", "inner", "p_i GPa", 1e-9, "{:.3f}"),
    ("peak_pressure", "outer", "p_o GPa", 1e-9, "{:.3f}"),
    ("largest_load", "inner", "Q_i N", 1.0, "{:.0f}"),
    ("largest_load", "outer", "Q_o N", 1.0, "{:.0f}"),
    ("cage_slip", None, "cage slip", 1.0, "{:.4f}"),
    ("settling_time", None, "settle ms", 1e3, "{:.2f}"),
)


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "study",
        help="run a parameter study on Dask (or: study show DIR)",
        description=(
            "Run the study file STUDY.toml (docs/study-format.md) on Dask and keep every run in "
            "the --output folder; or `racetrace study show DIR` to print a study folder's table. "
            "Exit codes: 0 all runs done, 1 some runs failed, 2 invalid input, 130 interrupted "
            "(finished runs kept: run again with --resume)."
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
    parser.add_argument("--quiet", "-q", action="store_true", help="no progress bar")
    parser.add_argument("--model", choices=("quasistatic", "dynamic"), help="show: only this model")
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


def run(args) -> int:
    if args.study == "show":
        if not args.folder:
            return _fail("study show DIR: name the study folder (the --output of a study run)")
        return show(args.folder, args.model)
    if args.folder:
        return _fail(f"unexpected argument {args.folder!r}: give the folder with --output")
    if not args.output:
        return _fail("--output DIR is required: the folder where the study keeps its runs")
    if args.workers is not None and args.workers < 1:
        return _fail(f"--workers {args.workers}: give 1 or more worker processes")
    if args.workers is not None and args.scheduler:
        return _fail("--workers and --scheduler together: the cluster at --scheduler has its own")
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        return _fail("the study runner needs dask.distributed: pip install 'dask[distributed]'")
    from solver import Study

    study = Study.from_file(args.study)
    stop = threading.Event()

    def on_sigint(signum, frame):  # noqa: ARG001
        if stop.is_set():
            raise KeyboardInterrupt
        stop.set()
        print(
            "\nracetrace: interrupt received: stopping, finished runs are kept ...",
            file=sys.stderr,
        )

    client = None
    if args.scheduler:
        from dask.distributed import Client

        try:
            client = Client(args.scheduler, timeout=30)
        except OSError as error:
            return _fail(f"--scheduler {args.scheduler}: cannot connect ({error})")
    points = study.points()
    runs = sum(len(p.models) for p in points)
    print(
        f"racetrace: study {study.title!r}: {len(points)} point(s), {runs} run(s) -> {args.output}",
        file=sys.stderr,
    )
    bar = None if args.quiet else StudyProgressBar()
    previous = signal.signal(signal.SIGINT, on_sigint)
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
        )
    finally:
        signal.signal(signal.SIGINT, previous)
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
        print(
            f"racetrace: interrupted: run `racetrace study {args.study} --output {args.output} "
            "--resume` to finish",
            file=sys.stderr,
        )
        return EXIT_INTERRUPTED
    return EXIT_SOME_FAILED if failed else 0


def show_table(ds, model: str | None = None) -> str:
    """The points and their metrics as a text table (one row per point and model)."""
    import json

    import numpy as np

    keys = json.loads(ds.attrs.get("varied_keys", "[]"))
    headers = ["point", "model", *(k.rsplit(".", 1)[-1] for k in keys), "status"]
    headers += [c[2] for c in SHOW_COLUMNS]
    rows = []
    messages = []
    for i, point in enumerate(ds["point"].values):
        for j, name in enumerate(ds["model"].values):
            if model and name != model:
                continue
            status = str(ds["status"].values[i, j])
            if status == "not run":
                continue
            row = [str(point), str(name)]
            for key in keys:
                value = ds[key].values[i]
                if isinstance(value, float | int | np.floating):
                    row.append(f"{value:g}" if math.isfinite(value) else "-")
                else:
                    row.append(str(value))
            row.append(status)
            for var, race, _h, scale, fmt in SHOW_COLUMNS:
                da = ds[var].isel(point=i, model=j)
                value = float(da.sel(race=race)) if race else float(da)
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
        lines += ["", "failed runs:", *messages]
    lines.append(
        "exc = trajectory excursion, band = band thickness (each race in its own ring's frame), "
        "alpha = mean contact angle, p = peak pressure, Q = largest contact load"
    )
    return "\n".join(lines)


def show(folder, model=None) -> int:
    from solver import open_study, study_dataset

    ds = study_dataset(open_study(folder))
    print(f"study {ds.attrs['title']!r} (base case {ds.attrs['base_case']}), folder {folder}")
    print(show_table(ds, model))
    return 0
