"""Benchmark of the quasi-static model (warm: numba compiled and cached before timing).

Prints the median of repeats of
1. one solve of the 218 bearing (16 balls) under 17.8 kN axial + 8.9 kN radial at 10 000 rpm, from
   scratch (static start, continuation if needed, race-control fixed point), as SI arrays and as a
   Dataset;
2. a 31-point speed sweep 0-30 000 rpm with continuation (each speed starts from the previous one),
   for the same 218 case and for the 7008C-class spindle case, as SI arrays and as a stacked
   Dataset.

Targets (on a 2-core machine): <= 20 ms per solve, <= 0.5 s per sweep.
Run: python benchmarks/quasistatic.py [--repeats N]
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

import numpy as np

from solver.catalogue import resolve_case
from solver.inputs import rpm_to_rad_s, to_inputs
from solver.models.quasistatic import (
    quasistatic_speed_sweep,
    solve_operating_point,
    solve_quasistatic,
)


def median_time(func, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def state_sweep(geometry, base, speeds_rpm):
    previous = None
    for rpm in speeds_rpm:
        op = dataclasses.replace(base, inner_ring_speed=rpm_to_rad_s(rpm))
        previous = solve_operating_point(geometry, op, previous)
    return previous


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()
    speeds = np.linspace(0.0, 30000.0, 31)

    case_218 = resolve_case("218-heavy-combined")
    geometry = case_218.geometry()
    op = to_inputs(case_218).operating
    # warm-up (compilation / cache load)
    solve_operating_point(geometry, op)
    solve_quasistatic(case_218)
    state_sweep(geometry, op, speeds)

    t_state = median_time(lambda: solve_operating_point(geometry, op), args.repeats)
    t_ds = median_time(lambda: solve_quasistatic(case_218), args.repeats)
    print(f"218, 17.8 kN + 8.9 kN at 10 000 rpm, one solve (arrays):  {t_state * 1e3:8.2f} ms")
    print(f"218, 17.8 kN + 8.9 kN at 10 000 rpm, one solve (Dataset): {t_ds * 1e3:8.2f} ms")

    sweep_repeats = max(3, args.repeats // 3)
    for name in ("218-heavy-combined", "spindle-combined-load"):
        case = resolve_case(name)
        g = case.geometry()
        base = to_inputs(case).operating
        state_sweep(g, base, speeds)
        t_sweep = median_time(lambda g=g, base=base: state_sweep(g, base, speeds), sweep_repeats)
        t_sweep_ds = median_time(
            lambda case=case: quasistatic_speed_sweep(case, speeds), sweep_repeats
        )
        print(f"{name}: 31-point sweep 0-30 000 rpm (arrays):  {t_sweep:8.3f} s")
        print(f"{name}: 31-point sweep 0-30 000 rpm (Dataset): {t_sweep_ds:8.3f} s")


if __name__ == "__main__":
    main()
