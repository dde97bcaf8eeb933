"""Count how racetrace copes with faults (run by hand, not in CI).

    python benchmarks/robustness.py

Faults: ``racetrace simulate`` stopped by SIGINT, SIGTERM and SIGHUP; an output folder that is
missing, read-only, or fills up during the run; a file-size limit (ulimit -f); the run store on a
read-only and on a full folder; job results a stopped server left behind; a killed solver process.
A fault loses a result when a computed result ends up nowhere. Tiny file systems need root (tmpfs
mounts); without it those faults are skipped and said so.

Bad input files (mutated case files and result files) are explored by
``python -m tests.explore_fuzz``, with the generators the fuzz tests use.

Prints the figures: faults tried, results lost.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # racetrace itself, when it is not installed
#: The case the faults run (a shipped catalogue case).
CASE = "spindle-combined-load"


def _case_text() -> str:
    from solver.catalogue import resolve_case

    return resolve_case(CASE).to_toml()


# ---- faults --------------------------------------------------------------------------------------
def _mount(args) -> bool:
    return subprocess.run(["mount", *args], capture_output=True).returncode == 0


@contextlib.contextmanager
def _tmpfs(path: Path, options: str):
    path.mkdir(parents=True, exist_ok=True)
    if not _mount(["-t", "tmpfs", "-o", options, "tmpfs", str(path)]):
        yield None
        return
    try:
        yield path
    finally:
        subprocess.run(["umount", "-l", str(path)], capture_output=True)


def _simulate(folder: Path, output: str, *args, preexec_fn=None):
    return subprocess.Popen(
        [
            sys.executable,
            "-m",
            "racetrace",
            "simulate",
            CASE,
            "-o",
            output,
            *args,
        ],
        cwd=folder,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        preexec_fn=preexec_fn,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )


def _wait_for_progress(process, timeout=300.0) -> str:
    seen = b""
    deadline = time.monotonic() + timeout
    while b"%" not in seen and time.monotonic() < deadline and process.poll() is None:
        seen += os.read(process.stderr.fileno(), 256)
    return seen.decode(errors="replace")


def _readable_result(path: Path) -> bool:
    from solver.results.io import load_dataset

    try:
        return load_dataset(path).sizes["time"] > 1
    except Exception:  # noqa: BLE001
        return False


def fault_signal(work: Path, signum: int) -> tuple[str, bool | None]:
    """(what happened, result lost?) for a signal during a run."""
    process = _simulate(work, "run.nc", "--revolutions", "200")
    _wait_for_progress(process)
    process.send_signal(signum)
    _, err = process.communicate(timeout=300)
    kept = _readable_result(work / "run.nc")
    leftovers = [p.name for p in work.iterdir() if p.name != "run.nc"]
    note = f"exit {process.returncode}, partial result kept: {kept}, leftovers: {leftovers or 0}"
    return note, not kept


def fault_before_run(work: Path, output: str, preexec_fn=None) -> tuple[str, bool | None]:
    """A fault found before the run: exit 2 and no run (nothing computed, nothing lost)."""
    process = _simulate(work, output, "--revolutions", "0.1", "-q", preexec_fn=preexec_fn)
    _, err = process.communicate(timeout=300)
    text = err.decode(errors="replace")
    first = next((line for line in text.splitlines() if not line.startswith("racetrace:")), "")
    clean = process.returncode == 2 and "Traceback" not in text
    return f"exit {process.returncode}: {first[:90]}", not clean


def fault_disk_fills(work: Path) -> tuple[str, bool | None]:
    """The output's file system fills up during the run: the result goes to the temp folder."""
    with _tmpfs(work / "small", "size=8m") as folder:
        if folder is None:
            return "skipped (cannot mount a tmpfs)", None
        process = _simulate(folder, "run.nc", "--revolutions", "3")
        _wait_for_progress(process)
        with contextlib.suppress(OSError):  # fill the disk
            with open(folder / "filler", "wb") as handle:
                while True:
                    handle.write(b"\0" * 1_000_000)
        _, err = process.communicate(timeout=300)
        text = err.decode(errors="replace")
        saved = [w.rstrip(".,") for w in text.split() if w.startswith(tempfile.gettempdir())]
        kept = bool(saved) and _readable_result(Path(saved[-1].removesuffix(" instead")))
        for path in saved:
            Path(path).unlink(missing_ok=True)
        return f"exit {process.returncode}, saved to the temp folder: {kept}", not kept


def fault_store(work: Path, options: str) -> tuple[str, bool | None]:
    from app.run_store import RunStore
    from solver import parse_case, solve_quasistatic

    text = _case_text()
    ds = solve_quasistatic(parse_case(text))
    with _tmpfs(work / "runs", options) as folder:
        if folder is None:
            return "skipped (cannot mount a tmpfs)", None
        store = RunStore(folder)
        if "size" in options:  # fill it first
            with contextlib.suppress(OSError), open(folder / "filler", "wb") as handle:
                while True:
                    handle.write(b"\0" * 100_000)
        info = store.save(ds, text, "fault test")
        back, _ = store.load(info.run_id)
        kept = back is not None and info.run_id in [r.run_id for r in store.list()]
        return f"saved on disk: {info.saved}, kept in memory and listed: {kept}", not kept


def fault_leftover_job(work: Path) -> tuple[str, bool | None]:
    from app.run_store import RunStore
    from solver import parse_case, solve_quasistatic
    from solver.results.io import save_dataset

    store = RunStore(work / "runs")
    store.root.mkdir()
    save_dataset(solve_quasistatic(parse_case(_case_text())), store.root / ".job-0123abcd.nc")
    old = time.time() - 3600
    os.utime(store.root / ".job-0123abcd.nc", (old, old))
    report = store.recover()
    kept = len(report.recovered) == 1
    return f"recovered as a run: {kept}", not kept


def fault_killed_solver(work: Path) -> tuple[str, bool | None]:
    from app.runner import SolverRunner
    from solver.catalogue import resolve_case

    runner = SolverRunner()
    case = resolve_case(CASE).with_values({"simulation.shaft_revolutions": 200.0})
    runner.start(case.to_toml(), work / "job.nc")
    deadline = time.monotonic() + 300
    events = []
    while time.monotonic() < deadline and not any(e.kind == "progress" for e in events):
        events += runner.poll()
        time.sleep(0.2)
    os.kill(runner._process.pid, signal.SIGKILL)
    while runner.busy and time.monotonic() < deadline:
        events += runner.poll()
        time.sleep(0.2)
    last = events[-1] if events else None
    reported = last is not None and last.kind == "error"
    # the killed process held the only copy of its partial state: nothing finished was lost
    return f"reported as: {last.text if last else 'nothing'}", not reported


def run_faults() -> list[tuple[str, str, bool | None]]:
    results = []

    def limit_file_size():
        hard = resource.getrlimit(resource.RLIMIT_FSIZE)[1]
        resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, hard))

    cases = [
        ("simulate: SIGINT", lambda w: fault_signal(w, signal.SIGINT)),
        ("simulate: SIGTERM", lambda w: fault_signal(w, signal.SIGTERM)),
        ("simulate: SIGHUP", lambda w: fault_signal(w, signal.SIGHUP)),
        ("simulate: missing folder", lambda w: fault_before_run(w, "missing/run.nc")),
        ("simulate: folder as output", lambda w: fault_before_run(w, ".")),
        ("simulate: file-size limit", lambda w: fault_before_run(w, "r.nc", limit_file_size)),
        ("simulate: disk fills during the run", fault_disk_fills),
        ("run store: read-only folder", lambda w: fault_store(w, "ro,size=1m")),
        ("run store: full folder", lambda w: fault_store(w, "size=256k")),
        ("run store: job left by a stopped server", fault_leftover_job),
        ("app runner: solver process killed", fault_killed_solver),
    ]
    if os.geteuid() == 0:  # root writes anywhere: the read-only case needs a read-only mount
        cases.insert(5, ("simulate: read-only folder", _read_only_simulate))
    for name, fault in cases:
        with tempfile.TemporaryDirectory() as work:
            try:
                note, lost = fault(Path(work))
            except Exception as error:  # noqa: BLE001
                note, lost = f"the fault test failed: {type(error).__name__}: {error}", True
        results.append((name, note, lost))
    return results


def _read_only_simulate(work: Path):
    with _tmpfs(work / "ro", "ro,size=64k") as folder:
        if folder is None:
            return "skipped (cannot mount a tmpfs)", None
        return fault_before_run(work, str(folder / "run.nc"))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.parse_args()
    faults = run_faults()
    tried = [f for f in faults if f[2] is not None]
    lost = [f for f in tried if f[2]]
    print(f"faults tried:       {len(tried)} ({len(faults) - len(tried)} skipped)")
    print(f"results lost:       {len(lost)}")
    for name, note, was_lost in faults:
        mark = "skipped" if was_lost is None else ("LOST" if was_lost else "ok")
        print(f"  {mark:7s} {name}: {note}")
    return 1 if lost else 0


if __name__ == "__main__":
    sys.exit(main())
