"""Benchmark of the quasi-static model (warm: numba compiled and cached before timing).

Prints, as the median (and the fastest) of repeats, wall-clock and process CPU time:
1. one operating point as a Dataset (``solve_quasistatic``: the solve, the Dataset builder, the
   rating lives, film and Hertz extras) and as SI arrays (``solve_quasistatic_state``), for the
   218 heavy case and the 7008C-class spindle case, with each ball-speed rule
   (``simulation.quasistatic_ball_speeds``: "traction", the default, and "race_control");
2. apart, a tilt turning with the ring (spindle-misalignment-ring), which needs one solve per ring
   angle: ``solve_over_revolution`` at the app preview's 12 angles, per Dataset and per angle;
3. a 31-point speed sweep 0-30 000 rpm with continuation (each speed starts from the previous one),
   for both cases, as SI arrays and as a stacked Dataset (the cases' default ball speeds).

The machine's load average is printed first: with other jobs on the cores the wall times grow, and
the CPU times less so.

Targets (on a 2-core machine): <= 10 ms per Dataset of one operating point with the default ball
speeds, <= 0.5 s per sweep.
Run: python benchmarks/quasistatic.py [--repeats N] [--no-sweeps]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import time

import numpy as np

from solver.catalogue import resolve_case
from solver.inputs import rpm_to_rad_s, to_inputs
from solver.models.quasistatic import (
    quasistatic_speed_sweep,
    solve_operating_point,
    solve_over_revolution,
    solve_quasistatic,
    solve_quasistatic_state,
)

CASES = ("218-heavy-combined", "spindle-combined-load")
RULES = ("traction", "race_control")
TURNING_CASE = "spindle-misalignment-ring"
PREVIEW_ANGLES = 12  # app.components.case_form.PREVIEW_RING_ANGLES (not imported: solver side)


@dataclasses.dataclass
class Timing:
    """Median and fastest of repeats [s], wall clock and process CPU."""

    wall: float
    wall_min: float
    cpu: float
    cpu_min: float

    def row(self, scale: float = 1e3, digits: int = 2) -> str:
        values = (self.wall, self.wall_min, self.cpu, self.cpu_min)
        return " ".join(f"{value * scale:8.{digits}f}" for value in values)


def timing(func, repeats: int) -> Timing:
    walls, cpus = [], []
    for _ in range(repeats):
        wall, cpu = time.perf_counter(), time.process_time()
        func()
        cpus.append(time.process_time() - cpu)
        walls.append(time.perf_counter() - wall)
    return Timing(statistics.median(walls), min(walls), statistics.median(cpus), min(cpus))


def with_rule(inputs, rule: str):
    """The inputs with ``simulation.quasistatic_ball_speeds`` = ``rule``."""
    simulation = dataclasses.replace(inputs.simulation, quasistatic_ball_speeds=rule)
    return dataclasses.replace(inputs, simulation=simulation)


def state_sweep(geometry, base, speeds_rpm, lubricant):
    previous = None
    for rpm in speeds_rpm:
        op = dataclasses.replace(base, inner_ring_speed=rpm_to_rad_s(rpm))
        previous = solve_operating_point(geometry, op, previous, lubricant)
    return previous


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=31)
    parser.add_argument("--no-sweeps", action="store_true", help="skip the speed sweeps")
    args = parser.parse_args()
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"load average (1, 5, 15 min): {load} on {os.cpu_count()} cores")
    print(f"median and fastest of {args.repeats} repeats, ms")
    header = f"{'wall':>8} {'(min)':>8} {'CPU':>8} {'(min)':>8}"

    print(f"\n1. one operating point{'':38s}{header}")
    for name in CASES:
        inputs = to_inputs(resolve_case(name))
        for rule in RULES:
            case = with_rule(inputs, rule)
            solve_quasistatic(case)  # warm-up: compilation or cache load
            ds_time = timing(lambda case=case: solve_quasistatic(case), args.repeats)
            state_time = timing(lambda case=case: solve_quasistatic_state(case), args.repeats)
            label = f"{name}, {rule}"
            print(f"   {label:<42s} Dataset {ds_time.row()}")
            print(f"   {'':<42s} arrays  {state_time.row()}")

    case = resolve_case(TURNING_CASE)
    solve_over_revolution(case, angles=PREVIEW_ANGLES)
    turning = timing(lambda: solve_over_revolution(case, angles=PREVIEW_ANGLES), args.repeats)
    print(f"\n2. tilt turning with the ring ({TURNING_CASE}, {PREVIEW_ANGLES} ring angles)")
    print(f"   {'one Dataset over the revolution':<50s} {turning.row()}")
    print(f"   {'per ring angle':<50s} {turning.row(1e3 / PREVIEW_ANGLES)}")

    if args.no_sweeps:
        return
    speeds = np.linspace(0.0, 30000.0, 31)
    sweep_repeats = max(3, args.repeats // 10)
    print(f"\n3. 31-point speed sweep 0-30 000 rpm, median of {sweep_repeats}, s")
    for name in CASES:
        case = resolve_case(name)
        inputs = to_inputs(case)
        lubricant = (
            inputs.lubricant if inputs.simulation.quasistatic_ball_speeds == "traction" else None
        )
        g, base = inputs.geometry, inputs.operating
        state_sweep(g, base, speeds, lubricant)
        arrays = timing(
            lambda g=g, b=base, lub=lubricant: state_sweep(g, b, speeds, lub), sweep_repeats
        )
        stacked = timing(lambda case=case: quasistatic_speed_sweep(case, speeds), sweep_repeats)
        print(f"   {name + ' (arrays)':<50s} {arrays.row(1.0, 3)}")
        print(f"   {name + ' (Dataset)':<50s} {stacked.row(1.0, 3)}")


if __name__ == "__main__":
    main()
