"""Benchmark of the live simulation (solver.LiveSimulation, docs/live.md) on the shipped spindle
case (``spindle-combined-load``: 7008C-class hybrid, 18 balls, 20 000 rpm, 500 N axial + 300 N
radial, sampled 60 000 times per simulated second).

    python benchmarks/live.py [--chunk-revolutions 0.5] [--chunks 6] [--repeats 3]

After a warm-up chunk (which loads or compiles the numba kernels):

- throughput: ``--chunks`` chunks of ``--chunk-revolutions`` shaft revolutions each; simulated
  shaft revolutions per wall second and per CPU second (``time.process_time``) of the whole
  ``advance`` (integration and Dataset);
- the wall time of each chunk split into the integration and the building of its Dataset
  (``LiveSimulation.last_advance``), and the Dataset's share;
- latency of a control change (solver side): the radial load is set from 300 N to 1200 N
  (``set_input`` with the default ramp, LIVE_RAMP) and chunks are advanced until one holds the
  end of the ramp. Two wall times from the ``set_input`` call: to the end of the first chunk that
  holds a sample after the change started, and to the end of the chunk that holds the end of the
  ramp (the change complete); the same in CPU seconds, what they take on one free core.

Each figure is the median of ``--repeats`` repeats (each on a fresh session); the spread
(min-max) is printed beside it. Wall times depend on the machine's load: compare them as ratios
within one run, or use the CPU figures.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

CASE = "spindle-combined-load"


def _median(values):
    return statistics.median(values), min(values), max(values)


def _show(label, values, unit, digits=3):
    med, low, high = _median(values)
    print(f"  {label:<52} {med:.{digits}f} {unit}  ({low:.{digits}f}-{high:.{digits}f})")


def throughput(chunk_s: float, chunks: int, period: float):
    """(revolutions per wall s, per CPU s, integration wall s per chunk, Dataset wall s per
    chunk, Dataset share of the chunk's wall time) of one fresh session."""
    from solver import LiveSimulation

    live = LiveSimulation(CASE)
    live.advance(chunk_s)  # the first chunk of a session is not timed
    wall = cpu = simulated = 0.0
    integration, dataset = [], []
    for _ in range(chunks):
        w0, c0 = time.perf_counter(), time.process_time()
        live.advance(chunk_s)
        wall += time.perf_counter() - w0
        cpu += time.process_time() - c0
        timing = live.last_advance
        simulated += timing.simulated_s
        integration.append(timing.integration_wall_s)
        dataset.append(timing.dataset_wall_s)
    live.close()
    revolutions = simulated / period
    share = sum(dataset) / (sum(dataset) + sum(integration))
    return (
        revolutions / wall,
        revolutions / cpu,
        statistics.median(integration),
        statistics.median(dataset),
        share,
    )


def latency(chunk_s: float):
    """(wall s from set_input to the end of the first chunk showing the change, to the end of
    the chunk holding the end of the ramp, and the CPU s of both) of one fresh session."""
    from solver import LIVE_RAMP, LiveSimulation

    live = LiveSimulation(CASE)
    live.advance(chunk_s)
    start = live.time
    t0, c0 = time.perf_counter(), time.process_time()
    live.set_input("radial_load", 1200.0)
    first = first_cpu = None
    while True:
        ds = live.advance(chunk_s)
        load = ds["radial_load"].values
        if first is None and load.max() > 300.0:
            first, first_cpu = time.perf_counter() - t0, time.process_time() - c0
        if ds["time"].values[-1] >= start + LIVE_RAMP - 1e-12:
            assert load[-1] == 1200.0
            done, done_cpu = time.perf_counter() - t0, time.process_time() - c0
            break
    live.close()
    return first, done, first_cpu, done_cpu


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--chunk-revolutions", type=float, default=0.5)
    parser.add_argument("--chunks", type=int, default=6)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    from solver import LIVE_RAMP, LiveSimulation

    period = 60.0 / 20000.0
    chunk_s = args.chunk_revolutions * period
    print(f"live simulation of {CASE}: chunks of {args.chunk_revolutions:g} shaft revolutions")
    print(f"({chunk_s * 1e3:.3g} ms simulated), ramp LIVE_RAMP = {LIVE_RAMP:g} s;")
    print(f"1-minute load before: {os.getloadavg()[0]:.1f}")
    warm = LiveSimulation(CASE)
    w0 = time.perf_counter()
    warm.advance(chunk_s)
    print(f"warm-up (load or compile the kernels, first chunk): {time.perf_counter() - w0:.1f} s")
    warm.close()
    rows = [throughput(chunk_s, args.chunks, period) for _ in range(args.repeats)]
    lat = [latency(chunk_s) for _ in range(args.repeats)]
    print(f"medians of {args.repeats} repeats (min-max):")
    _show("simulated shaft revolutions per wall second", [r[0] for r in rows], "rev/s")
    _show("simulated shaft revolutions per CPU second", [r[1] for r in rows], "rev/s")
    _show("integration, wall per chunk", [r[2] for r in rows], "s")
    _show("Dataset building, wall per chunk", [r[3] for r in rows], "s")
    _show("Dataset share of a chunk's wall time", [r[4] for r in rows], "")
    _show("latency set_input -> first chunk showing the change", [x[0] for x in lat], "s")
    _show("latency set_input -> chunk holding the ramp's end", [x[1] for x in lat], "s")
    _show("  the same in CPU seconds: first chunk showing it", [x[2] for x in lat], "s")
    _show("  the same in CPU seconds: chunk holding the ramp's end", [x[3] for x in lat], "s")
    print(f"1-minute load after: {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
