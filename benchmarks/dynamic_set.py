"""Benchmark of the dynamic model of a bearing set against one bearing (warm: numba compiled and
cached by a first, untimed run of each).

1. pair: the shipped DB pair ``spindle-pair-db-light-preload`` (7008C-class hybrid, 18 balls
   each, 12 000 rpm, 100 N preload, 100 N axial + 200 N radial at the spindle nose): the set's
   integration (:mod:`solver.models.dynamic.set_simulate`: the stepper on the set state, from the
   quasi-static set start);
2. one bearing: the pair's more loaded bearing alone at its operating point in the pair (its axial
   and radial load, its inner ring free in translation and tilt under no moment), integrated by the
   single-bearing model from its quasi-static start;

both with the set's method (``dopri5``), the case's tolerance and physics. For each, the process
CPU time per shaft revolution of the integration alone (the stepper's calls, not the start or the
Dataset), the median of ``--repeats`` runs of ``--revolutions`` revolutions each, alternating
pair and one bearing so that the load of a shared machine falls on both alike; steps and
right-hand-side evaluations per revolution; and the ratio pair / one bearing from the same run.
Target (issue 25): pair <= 2.2 x one bearing.

Run: python benchmarks/dynamic_set.py [--revolutions 1] [--repeats 3]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions
from solver.models.dynamic import layout as L
from solver.models.dynamic.initial import initial_state_from_quasistatic, quasistatic_solution
from solver.models.dynamic.integrate import stepper
from solver.models.dynamic.integrate.control import STATUS_OK, step_control
from solver.models.dynamic.integrate.model import SetModel, bearing_model
from solver.models.dynamic.params import build_params, build_quadrature, model_history
from solver.models.dynamic.set_simulate import SET_METHOD, build_set, set_scales
from solver.models.dynamic.simulate import state_scales

PAIR = "spindle-pair-db-light-preload"
TARGET = 2.2


def integrate(model, y0, scale, period, revolutions, tolerance, max_steps):
    """(CPU seconds, steps, right-hand-side evaluations) of integrating ``model`` from ``y0`` over
    ``revolutions`` shaft periods ``period`` [s], 40 output samples per revolution."""
    method = stepper(SET_METHOD)
    y = y0.copy()
    h = 0.05 * scale[L.B_POS] / scale[L.B_VEL]
    work = method.workspace(model, y.shape[0], 0.0, h)
    control = step_control(tolerance, scale, 1e-6 * h, max_steps)
    n = int(round(40 * revolutions))
    times = np.arange(1, n + 1) * (period / 40.0)
    out = np.empty((n, y.shape[0]))
    start = time.process_time()
    method.advance(y, times, out, control, work, model)
    cpu = time.process_time() - start
    progress = work.progress[0]
    if int(progress["status"]) != STATUS_OK or int(progress["written"]) != n:
        raise RuntimeError(f"the run stopped early (status {int(progress['status'])})")
    return cpu, int(progress["accepted"]), int(progress["rhs_evaluations"])


def pair_run(case, options):
    """(the run's model, state, scales, period, options) and the quasi-static set solution."""
    members, shaft, y, given, qs, resolved = build_set(case, options)
    model = SetModel(tuple(bearing_model(m.history, m.par, m.quad) for m in members), shaft)
    op = given.inputs.operating
    period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    return (model, y, set_scales(members, y), period, resolved), qs


def single_run(case, operating, options):
    """The single-bearing model of the pair's bearing at its ``operating`` point in the pair."""
    op = dataclasses.replace(
        operating, tilting_moment=0.0, moment_axis=0.0, misalignment=0.0, misalignment_axis=0.0
    )
    inputs = dataclasses.replace(to_inputs(case), operating=op)
    resolved = dataclasses.replace(options, method=SET_METHOD).resolved(inputs.simulation)
    par = build_params(inputs, resolved)
    history = model_history(inputs)
    quad = build_quadrature(resolved, par)
    y = initial_state_from_quasistatic(par, quasistatic_solution(inputs))
    period = 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)
    model = bearing_model(history, par, quad)
    return model, y, state_scales(history, par, y), period, resolved


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--revolutions", type=float, default=1.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    case = resolve_case(PAIR)
    options = SimulationOptions().validated()
    pair, qs = pair_run(case, options)
    loads = [math.hypot(o.axial_load, o.radial_load) for o in qs.operatings]
    index = int(np.argmax(loads))
    runs = {"pair": pair, "one bearing": single_run(case, qs.operatings[index], options)}
    # warm-up: compile or load each kernel variant
    for model, y, scale, period, resolved in runs.values():
        integrate(model, y, scale, period, 0.05, resolved.tolerance, resolved.max_steps_per_chunk)
    results = {name: [] for name in runs}
    for _ in range(args.repeats):
        for name, (model, y, scale, period, resolved) in runs.items():
            results[name].append(
                integrate(
                    model,
                    y,
                    scale,
                    period,
                    args.revolutions,
                    resolved.tolerance,
                    resolved.max_steps_per_chunk,
                )
            )
    print(f"case {PAIR}; one bearing: {qs.members[index].name} at its operating point in the pair")
    print(f"method {SET_METHOD}, {args.revolutions:g} revolutions x {args.repeats} repeats")
    median = {}
    for name, rows in results.items():
        cpu = statistics.median(r[0] for r in rows) / args.revolutions
        steps = statistics.median(r[1] for r in rows) / args.revolutions
        rhs = statistics.median(r[2] for r in rows) / args.revolutions
        median[name] = cpu
        print(
            f"{name:12s} CPU {cpu:.3f} s/rev (runs: "
            + ", ".join(f"{r[0] / args.revolutions:.3f}" for r in rows)
            + f"), {steps:.0f} steps/rev, {rhs:.0f} rhs evaluations/rev, "
            f"{cpu / rhs * 1e6:.1f} us CPU per evaluation"
        )
    ratio = median["pair"] / median["one bearing"]
    verdict = "meets" if ratio <= TARGET else "misses"
    print(f"ratio pair / one bearing: {ratio:.2f} ({verdict} the target <= {TARGET})")


if __name__ == "__main__":
    main()
