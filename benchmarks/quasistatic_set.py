"""Benchmark of the quasi-static bearing-set model against one bearing (warm: numba compiled and
cached before timing).

For each ball-speed rule (``simulation.quasistatic_ball_speeds``: "traction", the default, and
"race_control") prints the median (and fastest) process CPU time of repeats of the following,
taken in turn within each repeat (so that a change of the machine's load falls on all of them):

1. the shipped DB pair ``spindle-pair-db-light-preload`` solved as SI arrays from its SI inputs
   (``solve_set_state`` of ``set_inputs``: the preload offset, the set solve at rest and at
   speed, the stiffness) and as a Dataset from its Case (``solver.solve``);
2. one bearing: the single-bearing model solving the more loaded bearing of that pair alone at its
   operating point in the pair (its axial and radial load and its tilt), as SI arrays from its SI
   inputs (``solve_operating_point``) and as a Dataset from its Case (``solve_quasistatic``);

and the ratio pair / one bearing. Target: pair <= 2.5 x one bearing with the same rule (issue 25).
Run: python benchmarks/quasistatic_set.py [--repeats N]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import statistics
import time

from solver import Case, solve
from solver.catalogue import resolve_case
from solver.models.quasistatic import solve_operating_point, solve_quasistatic
from solver.models.quasistatic.bearing_set import set_inputs, solve_set_state

PAIR = "spindle-pair-db-light-preload"
RULES = ("traction", "race_control")


def cpu_times(funcs: dict, repeats: int) -> dict:
    """{name: (median, fastest) process CPU time [s]} of ``repeats`` calls of each of ``funcs``
    ({name: callable}), called in turn within each repeat."""
    times = {name: [] for name in funcs}
    for _ in range(repeats):
        for name, func in funcs.items():
            start = time.process_time()
            func()
            times[name].append(time.process_time() - start)
    return {name: (statistics.median(t), min(t)) for name, t in times.items()}


def single_case(pair, operating) -> Case:
    """The pair's case as one bearing at ``operating`` (SI, a bearing's own operating point)."""
    data = pair.to_dict()
    del data["set"]
    data["operating"].update(
        axial_load_N=operating.axial_load,
        radial_load_N=operating.radial_load,
        radial_load_angle_deg=math.degrees(operating.radial_load_angle),
        misalignment_deg=math.degrees(operating.misalignment),
        misalignment_axis_deg=math.degrees(operating.misalignment_axis),
    )
    return Case.from_dict(data)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}; CPU times in ms, median (fastest)")
    for rule in RULES:
        pair = resolve_case(PAIR).with_values({"simulation.quasistatic_ball_speeds": rule})
        given = set_inputs(pair)
        state = solve_set_state(given)  # warm-up, and the loaded bearing's operating point
        member = state.members[0]
        inputs = dataclasses.replace(member.inputs, operating=state.operatings[0])
        lubricant = inputs.lubricant if rule == "traction" else None
        single = single_case(pair, state.operatings[0])
        solve(pair)
        solve_quasistatic(single)
        rows = cpu_times(
            {
                "pair, SI arrays": lambda g=given: solve_set_state(g),
                "one bearing, SI arrays": lambda i=inputs, lub=lubricant: solve_operating_point(
                    i.geometry, i.operating, traction_lubricant=lub
                ),
                "pair, Dataset": lambda p=pair: solve(p),
                "one bearing, Dataset": lambda c=single: solve_quasistatic(c),
            },
            args.repeats,
        )
        print(f"\nball speeds: {rule}")
        for name, (median, fastest) in rows.items():
            print(f"  {name:24s} {median * 1e3:8.2f} ({fastest * 1e3:.2f})")
        for kind in ("SI arrays", "Dataset"):
            ratio = rows[f"pair, {kind}"][0] / rows[f"one bearing, {kind}"][0]
            print(f"  ratio pair / one bearing ({kind}): {ratio:.2f} (target <= 2.5)")


if __name__ == "__main__":
    main()
