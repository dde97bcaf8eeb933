"""Cold start: the numba kernels compiled on an empty cache, per kernel and per argument types.

    python benchmarks/cold_start.py [--revolutions N] [--json FILE]

Runs, in a fresh process whose numba cache folder is empty, the two things a first start does:

1. the warm-up of the app's fork server (``app/serve/preload.py``: the quasi-static solve of the
   default case ``spindle-combined-load`` and the track painter);
2. the first dynamic run of the default case (``--revolutions`` shaft revolutions, default 2: the
   kernels compiled do not depend on the length of the run).

For each phase prints the CPU seconds of the compiling process (``time.process_time``), the wall
seconds, the 1-minute load, the number of kernels and of compiled variants (numba compiles one
variant per distinct signature of argument types), and the kernels with more than one variant or
the most compile time (numba's ``numba:compile`` events: the time of a kernel includes the kernels
it compiles from inside, the exclusive time does not).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _measure(revolutions: float) -> dict:
    """Both phases in this process (its numba cache folder is empty); figures per phase."""
    sys.path.insert(0, str(ROOT))
    from numba.core import event

    class Recorder(event.Listener):
        def __init__(self):
            self.stack = []  # [name, start, child seconds]
            self.records = []  # (name, signature, seconds, exclusive seconds)

        def on_start(self, ev):
            self.stack.append([_name(ev.data["dispatcher"]), time.process_time(), 0.0])

        def on_end(self, ev):
            name, start, children = self.stack.pop()
            seconds = time.process_time() - start
            if self.stack:
                self.stack[-1][2] += seconds
            signature = ", ".join(str(a) for a in ev.data["args"])
            self.records.append((name, signature, seconds, seconds - children))

    def _name(dispatcher):
        function = dispatcher.py_func
        return f"{function.__module__}.{function.__qualname__}"

    recorder = Recorder()
    event.register("numba:compile", recorder)
    phases = {}

    def phase(label, work):
        first = len(recorder.records)
        cpu, wall = time.process_time(), time.perf_counter()
        work()
        phases[label] = {
            "cpu_s": time.process_time() - cpu,
            "wall_s": time.perf_counter() - wall,
            "load_1min": os.getloadavg()[0],
            "records": recorder.records[first:],
        }

    def warm_up():
        import numpy as np

        import solver
        from viz.tracks import _paint

        entries = {entry.name: entry for entry in solver.catalogue()}
        solver.solve_quasistatic(entries["spindle-combined-load"].load())
        i, f = np.zeros(1, np.int64), np.zeros(1)
        _paint(np.zeros((1, 1)), np.zeros((1, 1)), i, i, i, i, f, f + 1.0, f, f, 0.0, 1.0, 1)

    def first_dynamic():
        import solver
        from solver.models.dynamic import SimulationOptions

        entries = {entry.name: entry for entry in solver.catalogue()}
        options = SimulationOptions(shaft_revolutions=revolutions)
        solver.simulate(entries["spindle-combined-load"].load(), options=options)

    phase("import", lambda: __import__("solver"))
    phase("warm-up", warm_up)
    phase("first dynamic run", first_dynamic)
    return phases


def _report(phases: dict) -> None:
    for label, figures in phases.items():
        records = figures["records"]
        kernels = {}
        for name, signature, seconds, exclusive in records:
            entry = kernels.setdefault(name, {"variants": [], "seconds": 0.0, "exclusive": 0.0})
            entry["variants"].append(signature)
            entry["seconds"] += seconds
            entry["exclusive"] += exclusive
        print(
            f"\n== {label}: {figures['cpu_s']:.1f} s CPU, {figures['wall_s']:.1f} s wall, "
            f"load {figures['load_1min']:.1f}; {len(kernels)} kernels, {len(records)} variants, "
            f"{sum(r[3] for r in records):.1f} s CPU compiling"
        )
        if not kernels:
            continue
        print("  most exclusive compile time:")
        for name, entry in sorted(kernels.items(), key=lambda kv: -kv[1]["exclusive"])[:12]:
            print(f"    {entry['exclusive']:6.2f} s  x{len(entry['variants'])}  {name}")
        repeated = {n: e for n, e in kernels.items() if len(e["variants"]) > 1}
        print(f"  kernels with more than one variant: {len(repeated)}")
        for name, entry in sorted(repeated.items(), key=lambda kv: -len(kv[1]["variants"])):
            print(f"    x{len(entry['variants'])} {name} ({entry['exclusive']:.2f} s)")
            for signature in entry["variants"]:
                print(f"        ({signature})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=float, default=2.0)
    parser.add_argument("--json", type=Path, help="also write the figures to this file")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        print(json.dumps(_measure(args.revolutions)))
        return
    with tempfile.TemporaryDirectory(prefix="racetrace-cold-") as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=str(ROOT))
        command = [sys.executable, __file__, "--child", "--revolutions", str(args.revolutions)]
        done = subprocess.run(command, env=env, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        sys.exit(f"the measuring process failed:\n{done.stderr[-4000:]}")
    phases = json.loads(done.stdout.strip().splitlines()[-1])
    _report(phases)
    if args.json:
        args.json.write_text(json.dumps(phases, indent=1))


if __name__ == "__main__":
    main()
