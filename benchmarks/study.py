"""Benchmark of studies on Dask: dynamic points per minute with 1 and 2 workers, and the Dask
overhead per quasi-static point.

    python benchmarks/study.py [--revolutions 5] [--points 8] [--qs-points 64]

- dynamic: a study of ``--points`` points (radial load 100 N ... 1500 N on the spindle with 500 N
  axial, 20 000 rpm) of ``--revolutions`` shaft revolutions each (120 samples per revolution), run
  on a LocalCluster of 1 and of 2 single-threaded workers. The clusters are started and warmed up
  (numba kernels loaded) before the clock starts; the time covers submitting, running, shipping the
  results back and writing every point. Prints points per minute and the ratio (target: 2 workers
  >= 1.7 x 1 worker).
- quasi-static: ``--qs-points`` points on one worker, in the study's batches. The overhead per
  point is (study wall time - sum of the points' own times) / points, a point's own time being
  its solve, metrics and the writing of its NetCDF file and record on the worker; compared with
  the mean own time of a point (target: <= 20 %).

Run it when the machine is otherwise quiet: other processes on the cores change the figures.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from solver.study import Study, StudyFolder  # noqa: E402
from solver.study.runner import start_local_cluster  # noqa: E402
from solver.study.worker import WarmUp  # noqa: E402


def dynamic_study(points: int, revolutions: float) -> Study:
    loads = ", ".join(f"{100.0 + 1400.0 * i / max(points - 1, 1):.1f}" for i in range(points))
    return Study.from_text(
        'title = "benchmark dynamic"\nbase = "spindle-axial-preload"\nmodel = "dynamic"\n'
        f"[run]\nshaft_revolutions = {revolutions}\nsamples_per_revolution = 120\n"
        f'[vary]\n"operating.radial_load_N" = [{loads}]\n'
    )


def quasistatic_study(points: int) -> Study:
    loads = ", ".join(f"{1500.0 * i / max(points - 1, 1):.1f}" for i in range(points))
    return Study.from_text(
        'title = "benchmark quasi-static"\nbase = "spindle-axial-preload"\n'
        f'[vary]\n"operating.radial_load_N" = [{loads}]\n'
    )


def timed_run(study: Study, client, folder: Path) -> tuple[float, object]:
    """(wall time, study Dataset); the workers write the runs (they share this machine)."""
    start = time.perf_counter()
    ds = study.run(folder, client=client, shared_folder=True)
    return time.perf_counter() - start, ds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=float, default=5.0)
    parser.add_argument("--points", type=int, default=8)
    parser.add_argument("--qs-points", type=int, default=64)
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="racetrace-study-bench-"))
    try:
        rates = {}
        study = dynamic_study(args.points, args.revolutions)
        for workers in (1, 2):
            cluster, client = start_local_cluster(workers)
            try:
                client.register_plugin(WarmUp())
                wall, ds = timed_run(study, client, work / f"dyn{workers}")
                done = int((ds["status"] == "done").sum())
                runs = ds["wall_time"].sel(model="dynamic").values
                rates[workers] = 60.0 * done / wall
                print(
                    f"dynamic, {workers} worker(s): {done} points x {args.revolutions:g} rev in "
                    f"{wall:.1f} s = {rates[workers]:.2f} points/min (point run time median "
                    f"{statistics.median(runs):.1f} s)"
                )
            finally:
                client.close()
                cluster.close()
        ratio = rates[2] / rates[1]
        verdict = "meets" if ratio >= 1.7 else "misses"
        print(f"speed-up 2 workers / 1 worker: {ratio:.2f} ({verdict} the 1.7 target)")

        cluster, client = start_local_cluster(1)
        try:
            client.register_plugin(WarmUp())
            qs = quasistatic_study(args.qs_points)
            timed_run(quasistatic_study(4), client, work / "qs-warm")  # imports on the worker
            wall, ds = timed_run(qs, client, work / "qs")
            records = list(StudyFolder(work / "qs").finished().values())
            solve = np.array([r["wall_time_s"] for r in records])
            save = np.array([r.get("write_time_s", 0.0) for r in records])
            point = solve + save  # a point's own time: solving it and writing its files
            overhead = (wall - float(point.sum())) / len(records)
            share = overhead / float(point.mean())
            verdict = "meets" if share <= 0.2 else "misses"
            print(
                f"quasi-static, 1 worker: {len(records)} points in {wall:.2f} s; a point's own "
                f"time: mean {1e3 * point.mean():.1f} ms (solve and metrics "
                f"{1e3 * solve.mean():.1f} ms, median {1e3 * np.median(solve):.1f} ms; writing "
                f"its NetCDF and record {1e3 * save.mean():.1f} ms); Dask overhead "
                f"{1e3 * overhead:.1f} ms per point = {100 * share:.0f} % of a point's time "
                f"({verdict} the 20 % target)"
            )
        finally:
            client.close()
            cluster.close()
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
